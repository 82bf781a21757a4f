#include "ffdkit/render/curve_plot.h"

#include <stdexcept>

#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>
#include "png_output.h"


namespace ffdkit::app {

namespace {

void checkProfile(const scenes::CurvatureProfile& p) {
  const Eigen::Index n = p.arcLength.size();
  if (n < 2) throw std::invalid_argument("curvature profile needs >= 2 samples, got " + std::to_string(n));
  if (p.curvature.size() != n)
    throw std::invalid_argument("curvature profile: " + std::to_string(p.curvature.size()) + " curvature values for " +
                                std::to_string(n) + " arc-length samples");
  if (p.torsion.size() != 0 && p.torsion.size() != n)
    throw std::invalid_argument("curvature profile: " + std::to_string(p.torsion.size()) + " torsion values for " +
                                std::to_string(n) + " arc-length samples");
  if (!p.arcLength.allFinite() || !p.curvature.allFinite() || !p.torsion.allFinite())
    throw std::invalid_argument("curvature profile has non-finite values");
  for (Eigen::Index i = 1; i < n; ++i)
    if (p.arcLength[i] < p.arcLength[i - 1])
      throw std::invalid_argument("curvature profile: arc length decreases at sample " + std::to_string(i));
}

vtkNew<vtkDoubleArray> column(const char* name, const Eigen::VectorXd& values) {
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfValues(values.size());
  for (Eigen::Index i = 0; i < values.size(); ++i) array->SetValue(i, values[i]);
  return array;
}

}  // namespace

void plotCurvatureToPng(const scenes::CurvatureProfile& profile, const std::filesystem::path& png,
                        const CurvePlotOptions& options) {
  if (options.width < 1 || options.height < 1 || options.width > 16384 || options.height > 16384)
    throw std::invalid_argument("plot size must be 1..16384 pixels per side, got " + std::to_string(options.width) +
                                "x" + std::to_string(options.height));
  checkProfile(profile);
  const bool hasTorsion = profile.torsion.size() != 0;

  detail::requireDisplay("plotting");
  vtkNew<vtkTable> table;
  table->AddColumn(column("arc length", profile.arcLength));
  table->AddColumn(column("curvature", profile.curvature));
  if (hasTorsion) table->AddColumn(column("torsion", profile.torsion));

  vtkNew<vtkContextView> view;
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  view->GetRenderWindow()->SetOffScreenRendering(true);
  view->GetRenderWindow()->SetSize(options.width, options.height);
  vtkNew<vtkChartXY> chart;
  view->GetScene()->AddItem(chart);
  if (!options.title.empty()) {
    chart->SetTitle(options.title);
    chart->GetTitleProperties()->SetFontSize(16);
  }
  chart->GetAxis(vtkAxis::BOTTOM)->SetTitle("arc length");
  chart->GetAxis(vtkAxis::LEFT)->SetTitle(hasTorsion ? "curvature, torsion (1/length)" : "curvature (1/length)");
  chart->SetShowLegend(true);

  vtkPlot* curvature = chart->AddPlot(vtkChart::LINE);
  curvature->SetInputData(table, 0, 1);
  curvature->SetColor(230, 110, 20, 255);
  curvature->SetWidth(2.5);
  if (hasTorsion) {
    vtkPlot* torsion = chart->AddPlot(vtkChart::LINE);
    torsion->SetInputData(table, 0, 2);
    torsion->SetColor(30, 90, 220, 255);
    torsion->SetWidth(2.5);
  }
  view->GetRenderWindow()->Render();

  detail::writeWindowPng(view->GetRenderWindow(), png);
}

}  // namespace ffdkit::app
