#include "frame_renderer.hpp"

#include <vtkActor.h>
#include <vtkArrowSource.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCompositeDataSet.h>
#include <vtkInformation.h>
#include <vtkDataObjectTreeIterator.h>
#include <vtkDoubleArray.h>
#include <vtkGeometryFilter.h>
#include <vtkGlyph3D.h>
#include <vtkLightKit.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkScalarBarActor.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnstructuredGrid.h>
#include <vtkWindowToImageFilter.h>
#include <vtkXMLMultiBlockDataReader.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>


namespace stiffsoft {

namespace {

/// Arrows below this fraction of the largest contact force are not drawn (resting contacts
/// spread a body's weight over many vertices; those arrows would be dots).
constexpr double kSmallestArrow = 0.02;

/// Every leaf block of a frame with its name (the block's name in the .vtm, the body's name).
template <class Visit>
void for_each_block(vtkMultiBlockDataSet* frame, Visit visit) {
  auto it = vtkSmartPointer<vtkDataObjectTreeIterator>::Take(frame->NewTreeIterator());
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    if (auto* block = vtkDataSet::SafeDownCast(it->GetCurrentDataObject())) {
      const char* name = it->GetCurrentMetaData()->Has(vtkCompositeDataSet::NAME())
                             ? it->GetCurrentMetaData()->Get(vtkCompositeDataSet::NAME())
                             : "";
      visit(block, std::string(name ? name : ""));
    }
}

/// The bounds of one block.
BodyBounds block_bounds(vtkDataSet* block) {
  double b[6];
  block->GetBounds(b);
  return {block_model(block), Eigen::AlignedBox3d(Eigen::Vector3d(b[0], b[2], b[4]), Eigen::Vector3d(b[1], b[3], b[5]))};
}

/// A body's surface as an actor: scenery grey, soft by von Mises (cells), affine by speed (points).
vtkSmartPointer<vtkActor> body_actor(vtkDataSet* block, const std::string& model, vtkColorTransferFunction* stress,
                                     vtkColorTransferFunction* speed) {
  vtkSmartPointer<vtkDataSet> input = block;
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  if (model == "affine") {
    // speed = |velocity| per vertex, on a shallow copy (the frame stays as read)
    vtkSmartPointer<vtkDataSet> copy = vtkSmartPointer<vtkDataSet>::Take(block->NewInstance());
    copy->ShallowCopy(block);
    auto s = vtkSmartPointer<vtkDoubleArray>::New();
    s->SetName("speed");
    s->SetNumberOfTuples(block->GetNumberOfPoints());
    vtkDataArray* v = block->GetPointData()->GetArray("velocity");
    for (vtkIdType i = 0; i < block->GetNumberOfPoints(); ++i) {
      double n = 0;
      if (v)
        for (int c = 0; c < 3; ++c) n += v->GetComponent(i, c) * v->GetComponent(i, c);
      s->SetValue(i, std::sqrt(n));
    }
    copy->GetPointData()->AddArray(s);
    input = copy;
  }
  auto surface = vtkSmartPointer<vtkGeometryFilter>::New();
  surface->SetInputData(input);
  mapper->SetInputConnection(surface->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  if (model == "soft" && block->GetCellData()->GetArray("von_mises")) {
    mapper->SetScalarModeToUseCellFieldData();
    mapper->SelectColorArray("von_mises");
    mapper->SetLookupTable(stress);
    mapper->UseLookupTableScalarRangeOn();
    mapper->ScalarVisibilityOn();
  } else if (model == "affine") {
    mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectColorArray("speed");
    mapper->SetLookupTable(speed);
    mapper->UseLookupTableScalarRangeOn();
    mapper->ScalarVisibilityOn();
  } else {
    mapper->ScalarVisibilityOff();
    actor->GetProperty()->SetColor(kSceneryColour[0], kSceneryColour[1], kSceneryColour[2]);
  }
  actor->GetProperty()->SetAmbient(0.25);
  actor->GetProperty()->SetDiffuse(0.8);
  return actor;
}

/// The contact forces on the moving bodies as arrows from the vertex along the force, the
/// longest `length` m; null when there is none worth drawing.
vtkSmartPointer<vtkActor> arrows_actor(vtkMultiBlockDataSet* frame, double top, double length) {
  if (!(top > 0)) return nullptr;
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto forces = vtkSmartPointer<vtkDoubleArray>::New();
  forces->SetName("contact_force");
  forces->SetNumberOfComponents(3);
  for_each_block(frame, [&](vtkDataSet* block, const std::string&) {
    const std::string model = block_model(block);
    if (model != "affine" && model != "soft") return;
    vtkDataArray* f = block->GetPointData()->GetArray("contact_force");
    if (!f) return;
    for (vtkIdType i = 0; i < block->GetNumberOfPoints(); ++i) {
      double v[3];
      f->GetTuple(i, v);
      if (std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) < kSmallestArrow * top) continue;
      points->InsertNextPoint(block->GetPoint(i));
      forces->InsertNextTuple(v);
    }
  });
  if (points->GetNumberOfPoints() == 0) return nullptr;
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  cloud->GetPointData()->SetVectors(forces);
  auto arrow = vtkSmartPointer<vtkArrowSource>::New();
  arrow->SetTipResolution(12);
  arrow->SetShaftResolution(8);
  auto glyphs = vtkSmartPointer<vtkGlyph3D>::New();
  glyphs->SetInputData(cloud);
  glyphs->SetSourceConnection(arrow->GetOutputPort());
  glyphs->SetVectorModeToUseVector();
  glyphs->SetScaleModeToScaleByVector();
  glyphs->OrientOn();
  glyphs->SetScaleFactor(length / top);
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputConnection(glyphs->GetOutputPort());
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(kArrowColour[0], kArrowColour[1], kArrowColour[2]);
  return actor;
}

vtkSmartPointer<vtkScalarBarActor> colour_bar(vtkColorTransferFunction* lut, const char* title, double x, int height) {
  auto bar = vtkSmartPointer<vtkScalarBarActor>::New();
  bar->SetLookupTable(lut);
  bar->SetTitle(title);
  bar->SetOrientationToHorizontal();
  bar->SetNumberOfLabels(3);
  bar->SetLabelFormat("%-#6.3g");
  bar->SetPosition(x, 0.86);
  bar->SetWidth(0.3);
  bar->SetHeight(0.13);
  bar->SetBarRatio(0.25);
  bar->UnconstrainedFontSizeOn();
  for (vtkTextProperty* t : {bar->GetTitleTextProperty(), bar->GetLabelTextProperty()}) {
    t->SetColor(0, 0, 0);
    t->ShadowOff();
    t->ItalicOff();
    t->BoldOff();
    t->SetFontSize(std::max(10, height / 36));
  }
  return bar;
}

}  // namespace

vtkSmartPointer<vtkMultiBlockDataSet> read_frame_blocks(const std::filesystem::path& vtm) {
  if (!std::filesystem::exists(vtm)) throw std::runtime_error(vtm.string() + ": no such frame");
  auto reader = vtkSmartPointer<vtkXMLMultiBlockDataReader>::New();
  reader->SetFileName(vtm.c_str());
  reader->Update();
  auto* frame = vtkMultiBlockDataSet::SafeDownCast(reader->GetOutput());
  if (reader->GetErrorCode() != 0 || !frame || frame->GetNumberOfBlocks() == 0)
    throw std::runtime_error(vtm.string() + ": VTK cannot read the frame");
  return frame;
}

std::vector<BodyBounds> frame_bounds(vtkMultiBlockDataSet* frame) {
  std::vector<BodyBounds> bounds;
  for_each_block(frame, [&](vtkDataSet* block, const std::string&) {
    if (block->GetNumberOfPoints() > 0) bounds.push_back(block_bounds(block));
  });
  return bounds;
}

std::set<std::string> frame_walls(vtkMultiBlockDataSet* frame, const Eigen::Vector3d& up) {
  std::set<std::string> walls;
  for_each_block(frame, [&](vtkDataSet* block, const std::string& name) {
    if (block->GetNumberOfPoints() > 0 && is_wall(block_bounds(block), up)) walls.insert(name);
  });
  return walls;
}

FrameRenderer::FrameRenderer(int width, int height, const SceneView& view, const Eigen::AlignedBox3d& framed,
                             const ColourScales& scales, std::set<std::string> walls)
    : m_arrow_length(view.arrow_fraction * framed.diagonal().norm()),
      m_scales(scales),
      m_walls(std::move(walls)),
      m_window(vtkSmartPointer<vtkRenderWindow>::New()),
      m_bodies(vtkSmartPointer<vtkRenderer>::New()),
      m_arrows(vtkSmartPointer<vtkRenderer>::New()) {
  m_window->SetOffScreenRendering(1);
  m_window->SetSize(width, height);
  m_window->SetNumberOfLayers(2);
  m_window->SetMultiSamples(0);
  m_bodies->SetLayer(0);
  m_bodies->SetBackground(1, 1, 1);
  m_bodies->SetUseFXAA(true);
  m_bodies->SetUseDepthPeeling(true);  // translucent walls in front of opaque bodies, sorted
  m_window->SetAlphaBitPlanes(1);
  m_arrows->SetLayer(1);  // a higher layer clears depth: the arrows are drawn over the bodies
  m_arrows->InteractiveOff();
  // Key, fill and back lights: a horizontal ground seen at a grazing angle is not left dark.
  auto lights = vtkSmartPointer<vtkLightKit>::New();
  lights->AddLightsToRenderer(m_bodies);
  lights->AddLightsToRenderer(m_arrows);
  m_window->AddRenderer(m_bodies);
  m_window->AddRenderer(m_arrows);
  vtkCamera* camera = m_bodies->GetActiveCamera();
  const Eigen::Vector3d focal = framed.center(), eye = eye_position(framed, view);
  camera->SetFocalPoint(focal.data());
  camera->SetPosition(eye.data());
  camera->SetViewUp(view.up.data());
  camera->SetViewAngle(view.view_angle_deg);
  m_arrows->SetActiveCamera(camera);
}

void FrameRenderer::render(vtkMultiBlockDataSet* frame, double time, const std::filesystem::path& png) {
  m_bodies->RemoveAllViewProps();
  m_arrows->RemoveAllViewProps();
  const auto stress = colour_map(stress_colours(), m_scales.stress_top());
  const auto speed = colour_map(speed_colours(), m_scales.speed_top());
  bool soft = false, affine = false;
  for_each_block(frame, [&](vtkDataSet* block, const std::string& name) {
    const std::string model = block_model(block);
    soft = soft || model == "soft";
    affine = affine || model == "affine";
    const auto actor = body_actor(block, model, stress, speed);
    if (m_walls.count(name)) actor->GetProperty()->SetOpacity(kWallOpacity);
    m_bodies->AddActor(actor);
  });
  if (auto arrows = arrows_actor(frame, m_scales.contact_force_top(), m_arrow_length)) m_arrows->AddActor(arrows);
  const int height = m_window->GetSize()[1];
  if (affine) m_bodies->AddActor2D(colour_bar(speed, "affine bodies: speed (m/s)", 0.02, height));
  if (soft) m_bodies->AddActor2D(colour_bar(stress, "soft bodies: von Mises stress (Pa)", 0.64, height));
  auto clock = vtkSmartPointer<vtkTextActor>::New();
  char text[64];
  std::snprintf(text, sizeof text, "t = %.3f s", time);
  clock->SetInput(text);
  clock->GetTextProperty()->SetColor(0, 0, 0);
  clock->GetTextProperty()->SetFontSize(std::max(12, height / 22));
  clock->SetDisplayPosition(height / 40, height / 40);
  m_bodies->AddActor2D(clock);
  m_bodies->ResetCameraClippingRange();

  m_window->Render();
  auto image = vtkSmartPointer<vtkWindowToImageFilter>::New();
  image->SetInput(m_window);
  image->SetInputBufferTypeToRGB();
  image->ReadFrontBufferOff();
  image->Update();
  auto writer = vtkSmartPointer<vtkPNGWriter>::New();
  writer->SetFileName(png.c_str());
  writer->SetInputConnection(image->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != 0 || !std::filesystem::exists(png) || std::filesystem::file_size(png) == 0)
    throw std::runtime_error(png.string() + ": cannot write the picture");
}

}  // namespace stiffsoft
