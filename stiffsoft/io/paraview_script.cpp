#include "paraview_script.hpp"

#include <nlohmann/json.hpp>

#include <stiffsoft/io/atomic_file.hpp>
#include <stiffsoft/io/colour_maps.hpp>

namespace stiffsoft {

namespace {

/// The script; @NAME@ fields are filled in by paraview_script(). Tested with pvbatch 5.11
/// (tests/apps/paraview_script_test.cpp).
constexpr const char* kTemplate = R"PY(# ParaView 5.11 script written by stiffsoft beside @PVD@: it opens the series coloured and
# ready to look at: soft bodies by von Mises stress, affine bodies by speed, fixed bodies grey,
# contact forces on the moving bodies as red arrows (hidden where they point into a body: set the
# bodies' Opacity below 1 to see them all), the simulated time in a corner. Press Play.
#   paraview --script=@SCRIPT@                      (or View > Python Shell > Run Script)
#   pvbatch @SCRIPT@ --screenshot FILE.png          (headless: the last frame as a picture)
import math
import os
import sys
import paraview.simple
from paraview.simple import *

HERE = os.path.dirname(os.path.abspath(__file__))
PVD = os.path.join(HERE, @PVD_JSON@)
SOFT = @SOFT@
AFFINE = @AFFINE@
SCENERY = @SCENERY@
WALLS = @WALLS@  # drawn translucent: the bodies behind them show
# The camera (stiffsoft/io/scene_view.hpp): it looks along DIRECTION at the box the moving bodies
# reach over all frames (grown by ROOM on each side), from where that box's sphere fills
# VIEW_ANGLE, DOLLY times closer; the longest arrow is ARROW_FRACTION of the box's diagonal.
UP = @UP@
DIRECTION = @DIRECTION@
VIEW_ANGLE = @VIEW_ANGLE@
DOLLY = @DOLLY@
ROOM = @ROOM@
ARROW_FRACTION = @ARROW_FRACTION@
STRESS_COLOURS = @STRESS_COLOURS@
SPEED_COLOURS = @SPEED_COLOURS@
SCENERY_COLOUR = @SCENERY_COLOUR@
ARROW_COLOUR = @ARROW_COLOUR@
RANGE_QUANTILE = @RANGE_QUANTILE@
WALL_OPACITY = @WALL_OPACITY@
BLACK = [0.0, 0.0, 0.0]


def blocks(source, names, label):
    return ExtractBlock(registrationName=label, Input=source, Selectors=["/Root/" + n for n in names])


def frame_tops(source, array, cells, times):
    """The largest value (magnitude for vectors) of `array` in each frame."""
    tops = []
    for t in times:
        source.UpdatePipeline(t)
        info = source.GetCellDataInformation() if cells else source.GetPointDataInformation()
        a = info.GetArray(array)
        tops.append(a.GetRange(-1)[1] if a is not None else 0.0)
    return tops


def framed_box(source, times):
    """The box the moving bodies reach over every frame, grown by ROOM on each side."""
    lo, hi = [math.inf] * 3, [-math.inf] * 3
    for t in times:
        source.UpdatePipeline(t)
        b = source.GetDataInformation().GetBounds()
        for i in range(3):
            if b[2 * i] <= b[2 * i + 1]:
                lo[i], hi[i] = min(lo[i], b[2 * i]), max(hi[i], b[2 * i + 1])
    if lo[0] > hi[0]:
        lo, hi = [0.0] * 3, [0.0] * 3
    room = ROOM * (max(h - l for l, h in zip(lo, hi)) + 1e-9)
    return [l - room for l in lo], [h + room for h in hi]


def range_top(tops):
    """The RANGE_QUANTILE quantile of the per-frame largest values (one impact's spike does
    not wash out the rest of the run), as `stiffsoft render` takes it."""
    tops = sorted(tops)
    return tops[min(len(tops) - 1, max(0, math.ceil(RANGE_QUANTILE * len(tops)) - 1))] if tops else 0.0


def colour_bar(display, view, array, colours, top, title, x):
    lut = GetColorTransferFunction(array)
    top = top if top > 0 else 1.0
    points = []
    for k, c in enumerate(colours):
        points += [top * k / (len(colours) - 1)] + list(c)
    lut.RGBPoints = points
    lut.ColorSpace = "RGB"
    lut.AutomaticRescaleRangeMode = "Never"
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = BLACK
    bar.TitleFontSize = 14
    bar.LabelFontSize = 12
    bar.Orientation = "Horizontal"
    bar.WindowLocation = "Any Location"
    bar.Position = [x, 0.80]
    bar.ScalarBarThickness = 12
    bar.RangeLabelFormat = "%-#6.3g"
    bar.ScalarBarLength = 0.3


reader = PVDReader(registrationName=os.path.basename(PVD), FileName=PVD)
times = list(reader.TimestepValues) or [0.0]
LoadPalette("WhiteBackground")  # black text on white, colour bars included
view = GetActiveViewOrCreate("RenderView")
view.OrientationAxesVisibility = 0

if SCENERY:
    d = Show(blocks(reader, SCENERY, "fixed bodies"), view)
    d.ColorArrayName = ["POINTS", ""]
    d.AmbientColor = d.DiffuseColor = SCENERY_COLOUR

if WALLS:
    d = Show(blocks(reader, WALLS, "walls"), view)
    d.ColorArrayName = ["POINTS", ""]
    d.AmbientColor = d.DiffuseColor = SCENERY_COLOUR
    d.Opacity = WALL_OPACITY

if AFFINE:
    affine = Calculator(registrationName="affine bodies: speed", Input=blocks(reader, AFFINE, "affine bodies"))
    affine.ResultArrayName = "speed"
    affine.Function = "mag(velocity)"
    d = Show(affine, view)
    ColorBy(d, ("POINTS", "speed"))
    colour_bar(d, view, "speed", SPEED_COLOURS, range_top(frame_tops(affine, "speed", False, times)),
               "affine bodies: speed (m/s)", 0.02)

if SOFT:
    soft = blocks(reader, SOFT, "soft bodies")
    d = Show(soft, view)
    ColorBy(d, ("CELLS", "von_mises"))
    colour_bar(d, view, "von_mises", STRESS_COLOURS, range_top(frame_tops(soft, "von_mises", True, times)),
               "soft bodies: von Mises stress (Pa)", 0.64)

moving = blocks(reader, SOFT + AFFINE, "moving bodies") if SOFT + AFFINE else None
lo, hi = framed_box(moving or reader, times)
diagonal = math.dist(lo, hi)
force = max(frame_tops(moving, "contact_force", False, times)) if moving else 0.0
if force > 0:
    arrows = Glyph(registrationName="contact forces", Input=moving, GlyphType="Arrow")
    arrows.OrientationArray = ["POINTS", "contact_force"]
    arrows.ScaleArray = ["POINTS", "contact_force"]
    arrows.VectorScaleMode = "Scale by Magnitude"
    arrows.ScaleFactor = ARROW_FRACTION * diagonal / force
    arrows.GlyphMode = "All Points"
    d = Show(arrows, view)
    d.ColorArrayName = ["POINTS", ""]
    d.AmbientColor = d.DiffuseColor = ARROW_COLOUR

clock = AnnotateTime(registrationName="time")
clock.Format = "t = {time:.3f} s"
d = Show(clock, view)
d.Color = BLACK
d.FontSize = 20
d.WindowLocation = "Lower Left Corner"

focal = [0.5 * (l + h) for l, h in zip(lo, hi)]
distance = 0.5 * diagonal / math.sin(math.radians(0.5 * VIEW_ANGLE)) / DOLLY
view.CameraFocalPoint = focal
view.CameraPosition = [f + distance * d for f, d in zip(focal, DIRECTION)]
view.CameraViewUp = UP
view.CameraViewAngle = VIEW_ANGLE
animation = GetAnimationScene()
animation.UpdateAnimationUsingDataTimeSteps()
animation.AnimationTime = times[0]
SetActiveSource(reader)
paraview.simple._DisableFirstRenderCameraReset()  # keep the camera above
Render(view)

if "--screenshot" in sys.argv:
    animation.AnimationTime = times[-1]
    view.ViewSize = [960, 540]  # the picture's size: fonts keep their size
    SaveScreenshot(sys.argv[sys.argv.index("--screenshot") + 1], view, ImageResolution=[960, 540])
)PY";

void replace(std::string& text, const std::string& field, const std::string& value) {
  for (std::size_t at = text.find(field); at != std::string::npos; at = text.find(field, at + value.size()))
    text.replace(at, field.size(), value);
}

std::string vector_literal(const Eigen::Vector3d& v) { return nlohmann::json{v.x(), v.y(), v.z()}.dump(); }

std::string colours_literal(const std::vector<Rgb>& colours) { return nlohmann::json(colours).dump(); }

}  // namespace

ParaViewScene paraview_scene(const std::string& name, const std::vector<BodyFrame>& bodies,
                             const Eigen::Vector3d& gravity) {
  ParaViewScene scene;
  scene.pvd_name = name + ".pvd";
  std::vector<BodyBounds> bounds;
  for (const BodyFrame& b : bodies) {
    BodyBounds box{b.model, {}};
    for (Eigen::Index i = 0; i < b.x.rows(); ++i) box.box.extend(Eigen::Vector3d(b.x.row(i).transpose()));
    bounds.push_back(box);
  }
  scene.view = scene_view(gravity);
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const std::string& model = bodies[k].model;
    (model == "soft"                   ? scene.soft
     : model == "affine"               ? scene.affine
     : is_wall(bounds[k], scene.view.up) ? scene.walls
                                       : scene.scenery)
        .push_back(bodies[k].name);
  }
  return scene;
}

std::filesystem::path paraview_script_path(const std::filesystem::path& out, const std::string& name) {
  return out / (name + ".paraview.py");
}

std::string paraview_script(const ParaViewScene& scene) {
  std::string text = kTemplate;
  const std::string stem = std::filesystem::path(scene.pvd_name).stem().string();
  // JSON strings and lists of strings are valid Python literals.
  replace(text, "@PVD_JSON@", nlohmann::json(scene.pvd_name).dump());
  replace(text, "@PVD@", scene.pvd_name);
  replace(text, "@SCRIPT@", stem + ".paraview.py");
  replace(text, "@SOFT@", nlohmann::json(scene.soft).dump());
  replace(text, "@AFFINE@", nlohmann::json(scene.affine).dump());
  replace(text, "@SCENERY@", nlohmann::json(scene.scenery).dump());
  replace(text, "@WALLS@", nlohmann::json(scene.walls).dump());
  replace(text, "@WALL_OPACITY@", nlohmann::json(kWallOpacity).dump());
  replace(text, "@UP@", vector_literal(scene.view.up));
  replace(text, "@DIRECTION@", vector_literal(scene.view.direction));
  replace(text, "@VIEW_ANGLE@", nlohmann::json(scene.view.view_angle_deg).dump());
  replace(text, "@DOLLY@", nlohmann::json(scene.view.dolly).dump());
  replace(text, "@ROOM@", nlohmann::json(scene.view.room).dump());
  replace(text, "@ARROW_FRACTION@", nlohmann::json(scene.view.arrow_fraction).dump());
  replace(text, "@STRESS_COLOURS@", colours_literal(stress_colours()));
  replace(text, "@SPEED_COLOURS@", colours_literal(speed_colours()));
  replace(text, "@SCENERY_COLOUR@", nlohmann::json(kSceneryColour).dump());
  replace(text, "@ARROW_COLOUR@", nlohmann::json(kArrowColour).dump());
  replace(text, "@RANGE_QUANTILE@", nlohmann::json(kRangeQuantile).dump());
  return text;
}

void write_paraview_script(const std::filesystem::path& file, const ParaViewScene& scene) {
  const std::string text = paraview_script(scene);
  write_file_atomically(file, [&](std::ostream& out) { out << text; });
}

}  // namespace stiffsoft
