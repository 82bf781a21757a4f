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

}  // namespace ffdkit::cli::test
