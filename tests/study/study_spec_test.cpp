/// @file Study files: bad input is refused with the file and the JSON path; the sweep expands
/// to validated scenes identified by hash (stiffsoft/study/study_spec.hpp, stiffsoft/study/sweep.hpp).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include <stiffsoft/study/study_spec.hpp>
#include <stiffsoft/study/sweep.hpp>
#include <temporary_folder.hpp>

using namespace stiffsoft::study;

namespace {

/// Writes `text` to a fresh study file next to the shipped study scenes' folder and returns it.
std::filesystem::path study_file(const std::string& text) {
  const auto file = stiffsoft::testing::temporary_folder("study_spec") / "s.json";
  std::ofstream(file) << text;
  return file;
}

const std::string kScene = STIFFSOFT_SOURCE_DIR "/studies/scenes/spinning_box.json";

std::string study_text(const std::string& sweep, const std::string& quantity = R"({"name": "q", "body": "box",
  "field": "position", "reference": {"finest": "smallest"}})") {
  return R"({"scene": ")" + kScene + R"(", "sweep": [)" + sweep + R"(], "quantities": [)" + quantity + "]}";
}

/// The StudyError message of loading and planning `text` ("" when none is thrown).
std::string error_of(const std::string& text) {
  try {
    make_plan(load_study(study_file(text)));
  } catch (const StudyError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(StudySpec, ExpandsTheSweepIntoValidatedScenes) {
  const StudySpec s = load_study(study_file(study_text(
      R"({"path": "/time/dt", "values": [0.02, 0.01]}, {"path": "/time/integrator", "values": ["backward_euler", "bdf2"]})")));
  const Plan plan = make_plan(s);
  ASSERT_EQ(plan.runs.size(), 4u);
  EXPECT_EQ(plan.series, (std::vector<std::string>{"backward_euler", "bdf2"}));
  std::set<std::string> hashes;
  for (const RunPlan& r : plan.runs) {
    hashes.insert(r.hash);
    EXPECT_EQ(r.scene["time"]["dt"].get<double>(), r.x);
    EXPECT_EQ(r.scene["time"]["integrator"].get<std::string>(), r.series);
    EXPECT_EQ(r.scene["bodies"][0]["kappa"].get<double>(), 1e10);  // the base scene's value stays
  }
  EXPECT_EQ(hashes.size(), 4u);
  // The same study planned again gives the same hashes (the cache key).
  EXPECT_EQ(make_plan(s).runs[2].hash, plan.runs[2].hash);
}

TEST(StudySpec, UnknownScenePathNamesStudyFileAndJsonPath) {
  const std::string e = error_of(study_text(R"({"path": "/time/dtt", "values": [0.01]})"));
  EXPECT_NE(e.find("s.json"), std::string::npos) << e;
  EXPECT_NE(e.find("/sweep/0/values/0"), std::string::npos) << e;
  EXPECT_NE(e.find("dtt"), std::string::npos) << e;
}

TEST(StudySpec, WrongValueTypeIsRefused) {
  const std::string e = error_of(study_text(R"({"path": "/time/integrator", "values": [2]}, {"path": "/time/dt", "values": [0.01]})"));
  EXPECT_NE(e.find("/sweep/0/values/0"), std::string::npos) << e;
  EXPECT_NE(e.find("wrong type"), std::string::npos) << e;
  // Right type, value out of range: the scene loader's message comes through.
  const std::string range = error_of(study_text(R"({"path": "/time/dt", "values": [-0.01]})"));
  EXPECT_NE(range.find("/sweep/0/values/0"), std::string::npos) << range;
}

TEST(StudySpec, MissingBaseSceneAndBadQuantitiesAreRefused) {
  const std::string missing = error_of(R"({"scene": "nowhere.json", "sweep": [{"path": "/time/dt", "values": [0.01]}],
    "quantities": [{"name": "q", "stats": "kappa", "reference": {"analytic": "0"}}]})");
  EXPECT_NE(missing.find("/scene"), std::string::npos) << missing;
  EXPECT_NE(missing.find("does not exist"), std::string::npos) << missing;
  const std::string field = error_of(study_text(R"({"path": "/time/dt", "values": [0.01]})",
                                                R"({"name": "q", "body": "box", "field": "spin", "reference": {"analytic": "0"}})"));
  EXPECT_NE(field.find("/quantities/0/field"), std::string::npos) << field;
  const std::string components = error_of(study_text(
      R"({"path": "/time/dt", "values": [0.01]})",
      R"({"name": "q", "body": "box", "field": "position", "reference": {"analytic": ["0", "0"]}})"));
  EXPECT_NE(components.find("/quantities/0/reference"), std::string::npos) << components;
  const std::string builtin = error_of(study_text(
      R"({"path": "/time/dt", "values": [0.01]})",
      R"({"name": "q", "body": "box", "field": "affine_matrix", "reference": {"builtin": "steady_rotation_z"}})"));
  EXPECT_NE(builtin.find("/constants/omega"), std::string::npos) << builtin;
  const std::string x = error_of(study_text(R"({"path": "/time/integrator", "values": ["bdf2"]})"));
  EXPECT_NE(x.find("positive numbers"), std::string::npos) << x;
}

// Every shipped study (studies/*.json) parses and every scene of its sweep validates; the full
// studies are run by hand (docs/accuracy.md), not here.
TEST(StudySpec, EveryShippedStudyPlans) {
  int studies = 0;
  for (const auto& entry : std::filesystem::directory_iterator(STIFFSOFT_SOURCE_DIR "/studies")) {
    if (entry.path().extension() != ".json") continue;
    ++studies;
    SCOPED_TRACE(entry.path().string());
    const StudySpec s = load_study(entry.path());
    const Plan plan = make_plan(s);
    std::size_t expected = 1;
    for (const SweepParameter& p : s.sweep) expected *= p.values.size();
    EXPECT_EQ(plan.runs.size(), expected);
    EXPECT_FALSE(s.description.empty());
  }
  EXPECT_GE(studies, 7);
}
