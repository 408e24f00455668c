// Hard cases fail loudly (docs/robustness.md): each scene under data/hard/ is refused with an
// error that names the file, the JSON path and what to change, before any expensive work.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>

#include <stiffsoft/scene/make_simulation.hpp>
#include <stiffsoft/scene/scene_loader.hpp>
#include <stiffsoft/scene/start_gaps.hpp>

namespace stiffsoft {
namespace {

const std::filesystem::path kHard = std::filesystem::path(STIFFSOFT_SOURCE_DIR) / "tests/scene/data/hard";

/// Seconds within which a body too fine to mesh is refused. Making its elements would take
/// hours or exhaust memory, so the bound only has to tell "refused first" from "tried": it is
/// loose enough for a sanitized build (a release build refuses in milliseconds; ASan + UBSan
/// with slow unwinding took 1.6 s reading the STEP file).
constexpr double kRefusedWithin = 10.0;

/// Seconds since `start`.
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The SceneError `run` throws (a test failure when it throws none); its file must be `file`.
SceneError error_of(const std::function<void()>& run, const std::string& file) {
  try {
    run();
  } catch (const SceneError& error) {
    EXPECT_EQ(error.file(), file);
    return error;
  }
  ADD_FAILURE() << "no SceneError";
  return SceneError(file, "", "(none)");
}

/// The error of preparing data/hard/<name>, which must start with `<file>: <path_and_start>`.
std::string prepare_error(const std::string& name, const std::string& path_and_start) {
  const std::string file = (kHard / name).string();
  const std::string what = error_of([&] { prepare_scene(kHard / name); }, file).what();
  EXPECT_EQ(what.rfind(file + ": " + path_and_start, 0), 0u) << "got:      " << what << "\nexpected: " << file
                                                             << ": " << path_and_start;
  return what;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// --- Start gaps ---------------------------------------------------------------------------

TEST(HardCases, BodiesStartingCloserThanDhatAreRefusedNamingBothTheGapAndDhat) {
  const std::string what = prepare_error(
      "start_gap_below_dhat.json",
      "bodies: bodies \"floor\" (bodies[0]) and \"crate\" (bodies[1]) start 0.0005 m apart (closest surface points), "
      "closer than d̂ = 0.001 m: the barrier would push them apart at t = 0.");
  EXPECT_TRUE(contains(what, "set contact.dhat to at most 0.00025 m (half the smallest gap)")) << what;
  EXPECT_TRUE(contains(what, "contact.check_start_gaps to false")) << what;
}

TEST(HardCases, DhatAboveOnePercentOfTheSmallestBodyIsRefusedNamingThatBody) {
  const std::string what = prepare_error(
      "dhat_above_body_size.json",
      "contact.dhat: d̂ = 0.05 m is above 1 % of the size of body \"pebble\" (bodies[2]), the smallest "
      "(bounding-box diagonal 0.173 m)");
  EXPECT_TRUE(contains(what, "Set contact.dhat to at most 0.00173 m (1 % of body \"pebble\")")) << what;
}

TEST(HardCases, TheDefaultDhatIsAtMostOnePercentOfTheSmallestBody) {
  // 1e-3 × the 40 m diagonal would be 0.04 m, above 1 % of the 2 cm die: the default is 1 % of the die.
  const PreparedScene scene = prepare_scene(kHard / "default_dhat_small_body.json");
  EXPECT_NEAR(scene.settings.dhat, 0.01 * std::sqrt(3.0) * 0.02, 1e-12);
  EXPECT_EQ(scene.settings.dhat, default_dhat(scene.model));
}

TEST(HardCases, TheStartGapCheckCanBeSwitchedOffByTheScene) {
  EXPECT_NO_THROW(prepare_scene(kHard / "start_gap_check_off.json"));
}

TEST(HardCases, ATowerOfBoxesWithGapsLargerThanDhatLoadsAndIsAccepted) {
  const PreparedScene tower = prepare_scene(kHard / "tower_with_gaps.json");
  EXPECT_EQ(tower.settings.dhat, 0.001);
  EXPECT_TRUE(start_gaps_below(tower.model, 0.001).empty());
  // Each box 2 mm above the one below: six gaps, found exactly.
  const std::vector<StartGap> gaps = start_gaps_below(tower.model, 0.0021);
  ASSERT_EQ(gaps.size(), 6u);
  for (const StartGap& gap : gaps) {
    EXPECT_EQ(gap.body_b, gap.body_a + 1);
    EXPECT_NEAR(gap.distance, 0.002, 1e-12);
  }
}

TEST(StartGaps, ASoftBodysDistanceToItselfIsNoStartGap) {
  SceneDescription scene = load_scene(kHard / "soft_tiny_mesh_size.json");
  scene.bodies[0].mesh_size = 0.1;  // a handful of tets: gmsh runs in milliseconds
  const PreparedScene prepared = prepare_scene(scene, "soft.json");
  EXPECT_TRUE(start_gaps_below(prepared.model, 1.0).empty());
}

// --- Limits before work -------------------------------------------------------------------

TEST(HardCases, ASoftBodyWithAMicrometreMeshSizeIsRefusedBeforeMeshing) {
  const auto start = std::chrono::steady_clock::now();
  const std::string what = prepare_error("soft_tiny_mesh_size.json",
                                         "bodies[0].mesh_size: body \"jelly\" would need about 6.79e+16 tetrahedra "
                                         "(volume 0.008 m³ at mesh_size 1e-06 m: V / (h³/(6√2))), more than the "
                                         "limit of 2000000; use a mesh_size of at least 0.00324 m");
  EXPECT_TRUE(contains(what, "`stiffsoft run --max-tets N`")) << what;
  EXPECT_LT(seconds_since(start), kRefusedWithin);
}

TEST(HardCases, ASphereWithTwoBillionSegmentsIsRefusedBeforeItIsMade) {
  const auto start = std::chrono::steady_clock::now();
  const std::string what = prepare_error("sphere_huge_resolution.json",
                                         "bodies[0].mesh.resolution: body \"marble\" (sphere, resolution 2000000000) "
                                         "would have 4e+18 triangles, more than the limit of 1000000; use a resolution "
                                         "of at most 1001");
  EXPECT_TRUE(contains(what, "`stiffsoft run --max-triangles N`")) << what;
  EXPECT_LT(seconds_since(start), kRefusedWithin);
}

TEST(HardCases, ACadBodyWithAMicrometreMeshSizeIsRefusedBeforeMeshing) {
  const auto start = std::chrono::steady_clock::now();
  const std::string what = prepare_error("soft_step_tiny_mesh_size.json",
                                         "bodies[0].mesh_size: body \"bracket\" would need about 5.09e+16 tetrahedra "
                                         "(volume 0.006 m³ at mesh_size 1e-06 m");
  EXPECT_TRUE(contains(what, "`stiffsoft run --max-tets N`")) << what;
  EXPECT_LT(seconds_since(start), kRefusedWithin);
}

TEST(HardCases, TheElementLimitsAreSettings) {
  EXPECT_EQ(ElementLimits{}.max_tets, 2'000'000);
  EXPECT_EQ(ElementLimits{}.max_triangles, 1'000'000);
  SceneDescription scene = load_scene(kHard / "soft_tiny_mesh_size.json");
  scene.bodies[0].mesh_size = 0.05;  // about 543 tets expected
  ElementLimits limits;
  limits.max_tets = 100;
  const std::string what = error_of([&] { prepare_scene(scene, "limits.json", limits); }, "limits.json").what();
  EXPECT_TRUE(contains(what, "limits.json: bodies[0].mesh_size: body \"jelly\" would need about 543 tetrahedra")) << what;
  EXPECT_TRUE(contains(what, "more than the limit of 100")) << what;
}

// --- Numbers in range ---------------------------------------------------------------------

/// The error of loading data/hard/<name>, which must start with `<file>: <path_and_start>`.
void expect_load_error(const std::string& name, const std::string& path_and_start) {
  const std::string file = (kHard / name).string();
  const std::string what = error_of([&] { load_scene(kHard / name); }, file).what();
  EXPECT_EQ(what.rfind(file + ": " + path_and_start, 0), 0u) << "got:      " << what << "\nexpected: " << file
                                                             << ": " << path_and_start;
}

TEST(HardCases, ANumberTooLargeForADoubleNamesTheFileAndThePath) {
  expect_load_error("dt_overflow.json", "time.dt: the number 1e400 is too large for a double (largest: 1.8e308)");
}

TEST(HardCases, ANumberThatWouldReadAsZeroIsRefused) {
  expect_load_error("dt_underflow.json", "time.dt: the number 1e-400 is too small for a double");
}

TEST(HardCases, ATimeStepLongerThanTheRunIsRefused) {
  expect_load_error("dt_above_duration.json", "time.dt: must be <= time.duration (1 s) (got 2 s)");
}

TEST(HardCases, MoreStepsThanARunCanCountAreRefused) {
  expect_load_error("too_many_steps.json", "time.dt: time.duration / time.dt = 1e+12 steps, more than a run can count");
}

TEST(HardCases, VelocitiesAboveAMillionMetresPerSecondAreRefused) {
  expect_load_error("velocity_too_fast.json", "bodies[1].velocity[0]: must be >= -1e+06 (got -2e+06)");
  expect_load_error("path_velocity_too_fast.json", "bodies[0].path[0].velocity[1]: must be >= -1e+06 (got -5e+06)");
}

TEST(HardCases, AngularVelocitiesAboveAHundredThousandRadiansPerSecondAreRefused) {
  expect_load_error("angular_velocity_too_fast.json", "bodies[0].angular_velocity[1]: must be <= 1e+05 (got 1e+06)");
}

TEST(HardCases, AKeyGivenTwiceIsRefused) {
  expect_load_error("duplicate_key.json", "time.dt: the key \"dt\" is given twice in this object");
}

TEST(HardCases, AnIntegerBeyondAnIntIsRefusedRatherThanWrapped) {
  expect_load_error("resolution_beyond_int.json",
                    "bodies[0].mesh.resolution: must be an integer between -2147483648 and 2147483647 (got 3000000000)");
}

TEST(HardCases, ANonFiniteNumberInASceneBuiltInCodeIsNamed) {
  SceneDescription scene = load_scene(kHard / "tower_with_gaps.json");
  scene.time.dt = std::numeric_limits<double>::quiet_NaN();
  EXPECT_STREQ(error_of([&] { prepare_scene(scene, "code.json"); }, "code.json").what(),
               "code.json: time.dt: must be a finite number (got nan)");
  scene.time.dt = 0.01;
  scene.bodies[2].velocity.x() = std::numeric_limits<double>::infinity();
  EXPECT_STREQ(error_of([&] { prepare_scene(scene, "code.json"); }, "code.json").what(),
               "code.json: bodies[2].velocity[0]: must be a finite number (got inf)");
}

// --- Messages -----------------------------------------------------------------------------

TEST(HardCases, AnInvalidUtf8ByteInANameIsShownEscaped) {
  const std::string file = (kHard / "invalid_utf8_in_name.json").string();
  const std::string what = error_of([&] { load_scene(kHard / "invalid_utf8_in_name.json"); }, file).what();
  EXPECT_EQ(what.rfind(file + ": line 3, column ", 0), 0u) << what;
  EXPECT_TRUE(contains(what, "crate\\xFF")) << what;
  EXPECT_EQ(what.find('\xff'), std::string::npos);
}

TEST(HardCases, AnInvalidUtf8ByteInAKeyIsShownEscaped) {
  const std::string file = (kHard / "invalid_utf8_in_key.json").string();
  const std::string what = error_of([&] { load_scene(kHard / "invalid_utf8_in_key.json"); }, file).what();
  EXPECT_TRUE(contains(what, "dens\\xFE")) << what;
  EXPECT_EQ(what.find('\xfe'), std::string::npos);
}

TEST(HardCases, AControlCharacterInANameIsRefusedAndShownEscaped) {
  expect_load_error("control_character_in_name.json",
                    "bodies[0].name: must not hold control characters (got \"bell\\x07\")");
}

TEST(HardCases, ANameOfNoBreakSpacesIsBlank) {
  expect_load_error("no_break_space_name.json", "bodies[0].name: must not be empty or only white space");
}

TEST(HardCases, InvalidUtf8InASceneBuiltInCodeIsNamed) {
  SceneDescription scene = load_scene(kHard / "tower_with_gaps.json");
  scene.bodies[1].name = "box\xff";
  EXPECT_STREQ(error_of([&] { prepare_scene(scene, "code.json"); }, "code.json").what(),
               "code.json: bodies[1].name: must be valid UTF-8 text (got \"box\\xFF\")");
}

TEST(HardCases, EveryPartOfASceneErrorIsPrintable) {
  const SceneError error("a\x01.json", "bodies[0].x\x7f", "got \"\xff\" and \xe2\x89\xa5");
  EXPECT_STREQ(error.what(), "a\\x01.json: bodies[0].x\\x7F: got \"\\xFF\" and ≥");
  EXPECT_EQ(error.file(), "a\\x01.json");
}

}  // namespace
}  // namespace stiffsoft
