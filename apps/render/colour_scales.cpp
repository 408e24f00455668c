#include "colour_scales.hpp"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataObjectTreeIterator.h>
#include <vtkDataSet.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <cmath>

namespace stiffsoft {

namespace {

/// The largest Euclidean norm of the tuples of `array` (a scalar's absolute value).
double largest_norm(vtkDataArray* array) {
  if (!array) return 0;
  double top = 0;
  const int n = array->GetNumberOfComponents();
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i) {
    double s = 0;
    for (int c = 0; c < n; ++c) s += array->GetComponent(i, c) * array->GetComponent(i, c);
    top = std::max(top, std::sqrt(s));
  }
  return top;
}

/// The kRangeQuantile quantile of `values` (the smallest value at or above that fraction), 0 when empty.
double quantile(std::vector<double> values) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const auto at = std::size_t(std::max(0.0, std::ceil(kRangeQuantile * double(values.size())) - 1));
  return values[std::min(at, values.size() - 1)];
}

}  // namespace

std::string block_model(vtkDataObject* block) {
  vtkFieldData* field = block ? block->GetFieldData() : nullptr;
  auto* model = field ? vtkStringArray::SafeDownCast(field->GetAbstractArray("model")) : nullptr;
  return model && model->GetNumberOfValues() > 0 ? model->GetValue(0) : std::string();
}

void ColourScales::extend(vtkMultiBlockDataSet* frame) {
  double von_mises = 0, speed = 0;
  auto it = vtkSmartPointer<vtkDataObjectTreeIterator>::Take(frame->NewTreeIterator());
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem()) {
    auto* block = vtkDataSet::SafeDownCast(it->GetCurrentDataObject());
    if (!block) continue;
    const std::string model = block_model(block);
    if (model == "soft") von_mises = std::max(von_mises, largest_norm(block->GetCellData()->GetArray("von_mises")));
    if (model == "affine") speed = std::max(speed, largest_norm(block->GetPointData()->GetArray("velocity")));
    if (model == "soft" || model == "affine")
      m_contact_force = std::max(m_contact_force, largest_norm(block->GetPointData()->GetArray("contact_force")));
  }
  m_von_mises.push_back(von_mises);
  m_speed.push_back(speed);
}

double ColourScales::stress_top() const { return quantile(m_von_mises); }

double ColourScales::speed_top() const { return quantile(m_speed); }

vtkSmartPointer<vtkColorTransferFunction> colour_map(const std::vector<Rgb>& colours, double top) {
  auto f = vtkSmartPointer<vtkColorTransferFunction>::New();
  f->SetColorSpaceToRGB();
  const double range = top > 0 ? top : 1.0;  // a run at rest: one colour, a range that can be labelled
  for (std::size_t k = 0; k < colours.size(); ++k)
    f->AddRGBPoint(range * double(k) / double(colours.size() - 1), colours[k][0], colours[k][1], colours[k][2]);
  f->ClampingOn();
  return f;
}

}  // namespace stiffsoft
