#include <stiffsoft/io/joint_frame_reader.hpp>

#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataReader.h>

#include <stdexcept>

#include <stiffsoft/io/vtk_error_catcher.hpp>

namespace stiffsoft {

JointFrameRead read_joint_frame(const std::filesystem::path& vtp) {
  if (!std::filesystem::exists(vtp)) throw std::runtime_error("cannot read '" + vtp.string() + "': no such file");
  vtkNew<vtkXMLPolyDataReader> reader;
  vtkNew<VtkErrorCatcher> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName(vtp.c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  if (errors->failed || poly == nullptr)
    throw std::runtime_error("cannot read '" + vtp.string() + "': VTK: " + errors->message);
  vtkCellData* cells = poly->GetCellData();
  vtkDataArray* kind = cells->GetArray("kind");
  vtkDataArray* force = cells->GetArray("force");
  vtkDataArray* gap = cells->GetArray("gap");
  vtkDataArray* time = poly->GetFieldData()->GetArray("time");
  auto* names = vtkStringArray::SafeDownCast(poly->GetFieldData()->GetAbstractArray("joint_names"));
  const vtkIdType n = poly->GetNumberOfLines();
  if (!kind || !force || !gap || !time || !names || names->GetNumberOfValues() != n ||
      poly->GetNumberOfPoints() != 2 * n)
    throw std::runtime_error("cannot read '" + vtp.string() +
                             "': not a joints frame (expected 2 points and 1 line per joint, cell arrays kind, force, "
                             "gap and field data time, joint_names)");
  JointFrameRead out;
  out.time = time->GetTuple1(0);
  for (vtkIdType j = 0; j < n; ++j) {
    JointFrameEntry e;
    e.name = names->GetValue(j);
    e.kind = int(kind->GetTuple1(j));
    poly->GetPoint(2 * j, e.x_a.data());
    poly->GetPoint(2 * j + 1, e.x_b.data());
    force->GetTuple(j, e.force.data());
    e.gap = gap->GetTuple1(j);
    out.joints.push_back(e);
  }
  return out;
}

}  // namespace stiffsoft
