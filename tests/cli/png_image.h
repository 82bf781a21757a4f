#pragma once
// Reads a PNG back for pixel checks (VTK's reader: no Qt needed).

#include <filesystem>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkSmartPointer.h>

#include <Eigen/Core>

namespace ffdkit::cli::test {

struct PngImage {
  int width = 0;
  int height = 0;
  vtkSmartPointer<vtkImageData> data;
  /// RGB at (x, y), y from the top as in image viewers.
  Eigen::Vector3i rgb(int x, int y) const {
    const auto* p = static_cast<const unsigned char*>(data->GetScalarPointer(x, height - 1 - y, 0));
    return {p[0], p[1], p[2]};
  }
};

inline PngImage readPng(const std::filesystem::path& path) {
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(path.string().c_str());
  reader->Update();
  PngImage image;
  image.data = reader->GetOutput();
  const int* dims = image.data->GetDimensions();
  image.width = dims[0];
  image.height = dims[1];
  return image;
}

/// The sample scenes' orange (objects) and blue (widgets) as the renderer draws them.
inline bool orange(const Eigen::Vector3i& c) { return c.x() > 180 && c.y() > 60 && c.y() < 160 && c.z() < 90; }
inline bool blue(const Eigen::Vector3i& c) { return c.z() > 170 && c.x() < 100 && c.y() < 150; }

/// How many pixels of `image` `match` accepts.
inline int countPixels(const PngImage& image, bool (*match)(const Eigen::Vector3i&)) {
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) n += match(image.rgb(x, y)) ? 1 : 0;
  return n;
}

}  // namespace ffdkit::cli::test
