#include <stiffsoft/io/joint_frame_writer.hpp>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <cstdio>
#include <stdexcept>
#include <system_error>

#include <stiffsoft/coupling/joints/joint.hpp>
#include <stiffsoft/io/atomic_file.hpp>
#include <stiffsoft/io/frame_writer.hpp>
#include <stiffsoft/io/vtk_error_catcher.hpp>

namespace stiffsoft {

namespace {

vtkSmartPointer<vtkDoubleArray> vectors(const char* name, vtkIdType n) {
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(n);
  return a;
}

vtkSmartPointer<vtkIntArray> integers(const char* name, vtkIdType n) {
  auto a = vtkSmartPointer<vtkIntArray>::New();
  a->SetName(name);
  a->SetNumberOfValues(n);
  return a;
}

vtkSmartPointer<vtkPolyData> joints_polydata(double time, const std::vector<JointFrameEntry>& joints) {
  const vtkIdType n = vtkIdType(joints.size());
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(2 * n);
  vtkNew<vtkCellArray> lines;
  auto point_joint = integers("joint", 2 * n), point_end = integers("end", 2 * n);
  auto point_force = vectors("force", 2 * n);
  auto cell_joint = integers("joint", n), cell_kind = integers("kind", n);
  auto cell_force = vectors("force", n);
  vtkNew<vtkDoubleArray> magnitude, gap;
  magnitude->SetName("force_magnitude");
  magnitude->SetNumberOfValues(n);
  gap->SetName("gap");
  gap->SetNumberOfValues(n);
  vtkNew<vtkStringArray> names;
  names->SetName("joint_names");
  for (vtkIdType j = 0; j < n; ++j) {
    const JointFrameEntry& e = joints[j];
    points->SetPoint(2 * j, e.x_a.data());
    points->SetPoint(2 * j + 1, e.x_b.data());
    const vtkIdType line[2] = {2 * j, 2 * j + 1};
    lines->InsertNextCell(2, line);
    for (int end = 0; end < 2; ++end) {
      point_joint->SetValue(2 * j + end, int(j));
      point_end->SetValue(2 * j + end, end);
      const Eigen::Vector3d f = end == 0 ? e.force : Eigen::Vector3d(-e.force);
      point_force->SetTuple(2 * j + end, f.data());
    }
    cell_joint->SetValue(j, int(j));
    cell_kind->SetValue(j, e.kind);
    cell_force->SetTuple(j, e.force.data());
    magnitude->SetValue(j, e.force.norm());
    gap->SetValue(j, e.gap);
    names->InsertNextValue(e.name);
  }
  poly->SetPoints(points);
  poly->SetLines(lines);
  poly->GetPointData()->AddArray(point_joint);
  poly->GetPointData()->AddArray(point_end);
  poly->GetPointData()->AddArray(point_force);
  poly->GetCellData()->AddArray(cell_joint);
  poly->GetCellData()->AddArray(cell_kind);
  poly->GetCellData()->AddArray(cell_force);
  poly->GetCellData()->AddArray(magnitude);
  poly->GetCellData()->AddArray(gap);
  vtkNew<vtkDoubleArray> time_array;
  time_array->SetName("time");
  time_array->InsertNextValue(time);
  vtkNew<vtkStringArray> kinds;
  kinds->SetName("kind_names");
  for (int k = 0; k < kJointKindCount; ++k) kinds->InsertNextValue(joint_kind_name(JointKind(k)));
  poly->GetFieldData()->AddArray(time_array);
  poly->GetFieldData()->AddArray(names);
  poly->GetFieldData()->AddArray(kinds);
  return poly;
}

}  // namespace

JointFrameWriter::JointFrameWriter(std::filesystem::path out_dir, std::string scene_name)
    : m_out_dir(std::move(out_dir)), m_stem(scene_name + "_joints") {
  if (scene_name.empty() || scene_name.find('/') != std::string::npos)
    throw std::invalid_argument("scene name '" + scene_name + "' cannot name output files (empty or contains '/')");
  std::error_code ec;
  std::filesystem::create_directories(m_out_dir / "frames", ec);
  if (ec)
    throw std::runtime_error("cannot create output folder '" + (m_out_dir / "frames").string() + "': " + ec.message());
  write_pvd_collection(pvd_path(), m_frames);
}

void JointFrameWriter::continue_from(std::vector<std::pair<double, std::string>> frames) {
  m_frames = std::move(frames);
  write_pvd_collection(pvd_path(), m_frames);
}

std::filesystem::path JointFrameWriter::pvd_path() const { return m_out_dir / (m_stem + ".pvd"); }

void JointFrameWriter::write(double time, const std::vector<JointFrameEntry>& joints) {
  char number[16];
  std::snprintf(number, sizeof(number), "%06d", frame_count());
  const std::string file = "frames/" + m_stem + "_" + number + ".vtp";
  const auto poly = joints_polydata(time, joints);
  vtkNew<vtkXMLPolyDataWriter> writer;
  vtkNew<VtkErrorCatcher> errors;
  writer->AddObserver(vtkCommand::ErrorEvent, errors);
  writer->SetInputData(poly);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToZLib();
  writer->SetHeaderTypeToUInt64();
  writer->WriteToOutputStringOn();
  const std::filesystem::path path = m_out_dir / file;
  if (writer->Write() != 1 || errors->failed)
    throw std::runtime_error("cannot write '" + path.string() + "': VTK: " + errors->message);
  const std::string text = writer->GetOutputString();
  write_file_atomically(path, [&](std::ostream& out) { out.write(text.data(), text.size()); });
  m_frames.emplace_back(time, file);
  try {
    write_pvd_collection(pvd_path(), m_frames);
  } catch (...) {
    m_frames.pop_back();  // not listed, so it does not count
    throw;
  }
}

}  // namespace stiffsoft
