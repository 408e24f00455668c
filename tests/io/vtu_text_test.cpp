#include <stiffsoft/io/vtu_text.hpp>

#include <gtest/gtest.h>
#include <unistd.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

namespace stiffsoft {
namespace {

/// VTK's own reader gets back every array VtuText wrote, exactly, including arrays larger than
/// one 32 KiB compression block, both kinds of field data, and blocks both stored (the points:
/// few zero bytes) and deflated (the connectivity: mostly zero bytes).
TEST(VtuText, VtkReadsBackEveryArrayExactly) {
  const int n = 3000, tets = 2000, triangles = 1500;  // points: 72 KB, three compression blocks
  std::vector<double> x(3 * n), v(3 * n), stress(tets + triangles);
  for (int i = 0; i < 3 * n; ++i) {
    x[i] = 0.001 * i + 1.0 / 3.0;
    v[i] = i % 7 == 0 ? 0.0 : -1e-9 * i;
  }
  for (int c = 0; c < tets + triangles; ++c) stress[c] = 1e6 + c;
  std::vector<std::int64_t> connectivity, ends;
  std::vector<std::uint8_t> types;
  for (int t = 0; t < tets; ++t) {
    for (int k = 0; k < 4; ++k) connectivity.push_back((t + 17 * k) % n);
    ends.push_back(std::int64_t(connectivity.size()));
    types.push_back(VTK_TETRA);
  }
  for (int f = 0; f < triangles; ++f) {
    for (int k = 0; k < 3; ++k) connectivity.push_back((5 * f + k) % n);
    ends.push_back(std::int64_t(connectivity.size()));
    types.push_back(VTK_TRIANGLE);
  }
  VtuText vtu(n, tets + triangles);
  vtu.add_field("time", 0.125);
  vtu.add_field("body", "ball <one> & \"two\"");
  vtu.add_point_vectors("velocity", v.data());
  vtu.add_cell_scalars("von_mises", stress.data());
  vtu.set_points(x.data());
  vtu.set_cells(connectivity.data(), ends.data(), types.data());

  const auto file = std::filesystem::temp_directory_path() / ("stiffsoft_vtu_text_" + std::to_string(::getpid()) + ".vtu");
  {
    std::ofstream out(file, std::ios::binary);
    const std::string text = vtu.str();
    out.write(text.data(), std::streamsize(text.size()));
  }
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  std::filesystem::remove(file);
  vtkUnstructuredGrid* grid = reader->GetOutput();
  ASSERT_EQ(grid->GetNumberOfPoints(), n);
  ASSERT_EQ(grid->GetNumberOfCells(), tets + triangles);
  for (int i = 0; i < n; ++i) {
    double p[3];
    grid->GetPoint(i, p);
    for (int k = 0; k < 3; ++k) ASSERT_EQ(p[k], x[3 * i + k]) << "point " << i;
  }
  for (int c = 0; c < tets + triangles; ++c) {
    ASSERT_EQ(grid->GetCellType(c), types[c]) << "cell " << c;
    vtkIdType count = 0;
    const vtkIdType* ids = nullptr;
    grid->GetCellPoints(c, count, ids);
    const std::int64_t begin = c == 0 ? 0 : ends[c - 1];
    ASSERT_EQ(count, ends[c] - begin) << "cell " << c;
    for (vtkIdType k = 0; k < count; ++k) ASSERT_EQ(ids[k], connectivity[begin + k]) << "cell " << c;
  }
  auto* velocity = vtkDoubleArray::SafeDownCast(grid->GetPointData()->GetArray("velocity"));
  ASSERT_NE(velocity, nullptr);
  ASSERT_EQ(velocity->GetNumberOfComponents(), 3);
  for (int i = 0; i < 3 * n; ++i) ASSERT_EQ(velocity->GetValue(i), v[i]) << i;
  auto* von_mises = vtkDoubleArray::SafeDownCast(grid->GetCellData()->GetArray("von_mises"));
  ASSERT_NE(von_mises, nullptr);
  for (int c = 0; c < tets + triangles; ++c) ASSERT_EQ(von_mises->GetValue(c), stress[c]) << c;
  auto* time = vtkDoubleArray::SafeDownCast(grid->GetFieldData()->GetAbstractArray("time"));
  ASSERT_NE(time, nullptr);
  EXPECT_EQ(time->GetValue(0), 0.125);
  auto* body = vtkStringArray::SafeDownCast(grid->GetFieldData()->GetAbstractArray("body"));
  ASSERT_NE(body, nullptr);
  ASSERT_EQ(body->GetNumberOfValues(), 1);
  EXPECT_EQ(body->GetValue(0), "ball <one> & \"two\"");
}

}  // namespace
}  // namespace stiffsoft
