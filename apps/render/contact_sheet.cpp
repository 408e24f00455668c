#include "contact_sheet.hpp"

#include <vtkImageData.h>
#include <vtkImageResize.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace stiffsoft {

namespace {

/// White space between tiles and around the sheet, pixels.
constexpr int kGap = 4;

}  // namespace

std::vector<int> sheet_picks(int total, int count) {
  std::vector<int> picks;
  if (total <= 0 || count <= 0) return picks;
  if (count == 1 || total == 1) return {total - 1};
  for (int k = 0; k < std::min(count, total); ++k) {
    const int pick = int(std::lround(double(k) * (total - 1) / double(std::min(count, total) - 1)));
    if (picks.empty() || pick != picks.back()) picks.push_back(pick);
  }
  return picks;
}

void write_contact_sheet(const std::vector<std::filesystem::path>& pictures, int columns, double scale,
                         const std::filesystem::path& sheet) {
  if (pictures.empty()) throw std::runtime_error(sheet.string() + ": no pictures for the contact sheet");
  std::vector<vtkSmartPointer<vtkImageData>> tiles;
  for (const std::filesystem::path& picture : pictures) {
    auto reader = vtkSmartPointer<vtkPNGReader>::New();
    if (!reader->CanReadFile(picture.c_str())) throw std::runtime_error(picture.string() + ": not a readable PNG");
    reader->SetFileName(picture.c_str());
    auto resize = vtkSmartPointer<vtkImageResize>::New();
    resize->SetInputConnection(reader->GetOutputPort());
    resize->SetMagnificationFactors(scale, scale, 1.0);
    resize->SetResizeMethodToMagnificationFactors();
    resize->Update();
    tiles.push_back(resize->GetOutput());
  }
  int dims[3];
  tiles.front()->GetDimensions(dims);
  const int w = dims[0], h = dims[1], channels = tiles.front()->GetNumberOfScalarComponents();
  columns = std::max(1, std::min(columns, int(tiles.size())));
  const int rows = (int(tiles.size()) + columns - 1) / columns;
  const int width = columns * w + (columns + 1) * kGap, height = rows * h + (rows + 1) * kGap;
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->SetDimensions(width, height, 1);
  out->AllocateScalars(VTK_UNSIGNED_CHAR, channels);
  auto* pixels = static_cast<unsigned char*>(out->GetScalarPointer());
  std::memset(pixels, 255, std::size_t(width) * height * channels);
  for (std::size_t k = 0; k < tiles.size(); ++k) {
    int d[3];
    tiles[k]->GetDimensions(d);
    if (d[0] != w || d[1] != h || tiles[k]->GetNumberOfScalarComponents() != channels)
      throw std::runtime_error(pictures[k].string() + ": not the size of the other pictures");
    const int row = int(k) / columns, column = int(k) % columns;
    // VTK's images start at the bottom row: the sheet's first row is at the top.
    const int x0 = kGap + column * (w + kGap), y0 = height - (row + 1) * (h + kGap);
    const auto* tile = static_cast<const unsigned char*>(tiles[k]->GetScalarPointer());
    for (int y = 0; y < h; ++y)
      std::memcpy(pixels + (std::size_t(y0 + y) * width + x0) * channels, tile + std::size_t(y) * w * channels,
                  std::size_t(w) * channels);
  }
  auto writer = vtkSmartPointer<vtkPNGWriter>::New();
  writer->SetFileName(sheet.c_str());
  writer->SetInputData(out);
  writer->Write();
  if (writer->GetErrorCode() != 0) throw std::runtime_error(sheet.string() + ": cannot write the contact sheet");
}

}  // namespace stiffsoft
