#pragma once
/// @file A convergence study as read from its JSON file (studies/*.json; keys in
/// docs/accuracy.md): a base scene, the parameters swept, the quantities of interest and their
/// references.

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <stiffsoft/study/expression.hpp>

namespace stiffsoft::study {

/// Bad study input: the message names the study file and the JSON path (`<file>: <path>: …`).
/// `stiffsoft study` exits with code 2 on it.
class StudyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One entry of `sweep`: a scene key and the values it takes.
struct SweepParameter {
  std::string path;                   ///< JSON pointer into the scene, e.g. "/time/dt"
  std::vector<nlohmann::json> values; ///< values in the order given
  std::string label;                  ///< axis label (default: the path)
  std::string name;                   ///< short name in series labels ("eps_v" → "eps_v=0.001"); empty: the value alone
};

/// Where a quantity's raw values come from.
enum class Source {
  Body,   ///< a column group of bodies.csv for one body
  Stats,  ///< a column of stats.csv (whole scene)
  Point   ///< displacement of the soft-body node nearest to a rest point, read from the frames
};

/// A body field of bodies.csv.
enum class Field {
  Position,         ///< p (m), 3 components
  Velocity,         ///< v (m/s), 3
  AngularVelocity,  ///< w (rad/s), 3
  Affine,           ///< A, 9 (row-major)
  KineticEnergy,    ///< J, 1
  ContactForce,     ///< sum of contact forces on the body (N), 3
  FrictionForce     ///< sum of friction forces on the body (N), 3
};

/// How a time series becomes the compared value.
enum class Reduction {
  At,          ///< value at a time (linear interpolation between rows)
  End,         ///< value at the last row
  Max,         ///< largest value over the run (scalar quantities)
  Min,         ///< smallest value (e.g. smallest_distance: the penetration-free margin)
  MaxAbs,      ///< largest |value|
  Change,      ///< last minus first row (e.g. energy drift)
  Crossing,    ///< first time the value crosses `crossing_value` (s), e.g. a flip time
  Trajectory   ///< the whole series: error = max over the run's rows of |value − reference|
};

/// What a quantity's error is divided by.
enum class Normalization {
  None,       ///< absolute error
  Reference,  ///< divided by |reference|
  Initial     ///< divided by |first value of the series|
};

/// Where the reference value of a quantity comes from.
enum class ReferenceKind {
  Analytic,    ///< formula(s) of the study (or a built-in validation problem)
  Finest,      ///< the finest run of the same series (smallest, or largest, swept x)
  Richardson,  ///< extrapolated from the finest runs of the series
  Run          ///< an extra run: the series' scene with `overrides`
};

/// The reference of a quantity.
struct ReferenceSpec {
  ReferenceKind kind = ReferenceKind::Finest;  ///< which kind
  std::vector<std::string> expressions;  ///< Analytic: one per compared component (variables: t, constants, swept keys)
  std::string builtin;                   ///< Analytic: name of the built-in it came from, if any
  bool finest_is_largest = false;        ///< Finest/Richardson: the largest x is the finest (e.g. κ)
  std::optional<double> order;           ///< Richardson: the known order; unset: estimated from the three finest runs
  nlohmann::json overrides = nlohmann::json::object();  ///< Run: JSON pointer → value, on top of the series' scene
};

/// One quantity of interest.
struct QuantitySpec {
  std::string name;                   ///< label in tables and plots
  std::string json_path;              ///< "/quantities/i" (for messages)
  Source source = Source::Body;       ///< where values come from
  std::string body;                   ///< Body, Point: the body's name
  Field field = Field::Position;      ///< Body: which field
  bool displacement = false;          ///< Body position: minus the first row's (field "displacement")
  std::string column;                 ///< Stats: the stats.csv column
  Eigen::Vector3d rest_point = Eigen::Vector3d::Zero();  ///< Point: rest position (m) of the tracked node
  std::vector<int> components;        ///< indices compared (into the field's components); empty: all
  Reduction reduction = Reduction::End;  ///< how the series is reduced
  double time = 0;                    ///< At: the time (s)
  double crossing_value = 0;          ///< Crossing: the level crossed
  double from = -1e300;               ///< only rows with time ≥ from (s) are used
  double until = 1e300;               ///< only rows with time ≤ until (s) are used
  Normalization normalization = Normalization::None;  ///< absolute or relative error
  ReferenceSpec reference;            ///< what the value is compared with
  std::string unit;                   ///< unit of the error, for labels ("m", "1", …)
  std::map<std::string, double> expected_order;  ///< by series label ("" for every series); overrides the study's
};

/// A whole study.
struct StudySpec {
  std::filesystem::path file;          ///< the study file
  std::string name;                    ///< its stem
  std::string description;             ///< what the study shows
  std::filesystem::path scene;         ///< base scene (absolute)
  nlohmann::json set = nlohmann::json::object();  ///< fixed overrides, JSON pointer → value
  std::vector<SweepParameter> sweep;   ///< swept parameters (Cartesian product)
  int x = 0;                           ///< index in `sweep` of the x-axis parameter (numbers only)
  Variables constants;                 ///< named numbers for expressions
  std::vector<QuantitySpec> quantities;   ///< at least one
  std::map<std::string, double> expected_order;  ///< by series label ("" for every series)
  bool check_intersections = true;     ///< run `stiffsoft check` on every run's frames
};

/// Reads and checks a study file; the scene path is resolved against the study's folder.
/// Throws StudyError (`<file>: <json path>: <what was expected>`).
StudySpec load_study(const std::filesystem::path& file);

/// Number of components of a body field (1, 3 or 9).
int field_size(Field field);

}  // namespace stiffsoft::study
