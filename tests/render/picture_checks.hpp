#pragma once
/// @file Checks on a rendered picture (PNG): its size, that it is not one flat colour, and that
/// it shows the colours of affine (blue) and soft (yellow to red) bodies.

#include <vtkImageData.h>
#include <vtkPNGReader.h>
#include <vtkSmartPointer.h>

#include <filesystem>
#include <set>

namespace stiffsoft::testing {

/// What a picture holds.
struct PictureSummary {
  int width = 0, height = 0;  ///< pixels; 0 when it cannot be read
  std::size_t colours = 0;    ///< distinct RGB colours
  std::size_t bluish = 0;     ///< pixels clearly bluer than red (affine bodies' speed map)
  std::size_t warm = 0;       ///< pixels clearly redder than blue (soft bodies' stress map, arrows)
};

/// Reads `png` and counts what PictureSummary lists.
inline PictureSummary summarize_picture(const std::filesystem::path& png) {
  PictureSummary s;
  auto reader = vtkSmartPointer<vtkPNGReader>::New();
  if (!reader->CanReadFile(png.c_str())) return s;
  reader->SetFileName(png.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  s.width = dims[0];
  s.height = dims[1];
  const int channels = image->GetNumberOfScalarComponents();
  const auto* p = static_cast<const unsigned char*>(image->GetScalarPointer());
  std::set<int> colours;
  for (long i = 0; i < long(dims[0]) * dims[1]; ++i, p += channels) {
    const int r = p[0], g = channels >= 3 ? p[1] : p[0], b = channels >= 3 ? p[2] : p[0];
    colours.insert((r << 16) | (g << 8) | b);
    if (b > r + 25) ++s.bluish;
    if (r > b + 25) ++s.warm;
  }
  s.colours = colours.size();
  return s;
}

}  // namespace stiffsoft::testing
