#include <stiffsoft/study/time_series.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <stiffsoft/io/frame_reader.hpp>

namespace stiffsoft::study {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

[[noreturn]] void fail(const StudySpec& s, const QuantitySpec& q, const std::string& what) {
  throw StudyError(s.file.string() + ": " + q.json_path + ": " + what);
}

/// One CSV line split into cells (RFC 4180 quotes).
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') cells.back() += '"', ++i;
      else if (c == '"') quoted = false;
      else cells.back() += c;
    } else if (c == '"') quoted = true;
    else if (c == ',') cells.emplace_back();
    else cells.back() += c;
  }
  return cells;
}

double to_number(const std::string& cell) {
  if (cell == "nan" || cell == "-nan") return kNaN;
  if (cell == "inf") return std::numeric_limits<double>::infinity();
  if (cell == "-inf") return -std::numeric_limits<double>::infinity();
  return std::stod(cell);
}

/// A CSV file: header and rows of cells.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  int column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return int(i);
    return -1;
  }
};

Csv read_csv(const StudySpec& s, const QuantitySpec& q, const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) fail(s, q, "the run's " + file.string() + " is missing (did the run fail? see run.log beside it)");
  Csv csv;
  std::string line;
  std::getline(in, line);
  csv.header = split_csv(line);
  while (std::getline(in, line))
    if (!line.empty()) csv.rows.push_back(split_csv(line));
  return csv;
}

TimeSeries body_series(const StudySpec& s, const QuantitySpec& q, const std::filesystem::path& dir) {
  const Csv csv = read_csv(s, q, dir / "bodies.csv");
  static const std::map<Field, std::vector<std::string>> columns{
      {Field::Position, {"px", "py", "pz"}},
      {Field::Velocity, {"vx", "vy", "vz"}},
      {Field::AngularVelocity, {"wx", "wy", "wz"}},
      {Field::Affine, {"A00", "A01", "A02", "A10", "A11", "A12", "A20", "A21", "A22"}},
      {Field::KineticEnergy, {"kinetic_energy"}},
      {Field::ContactForce, {"fcx", "fcy", "fcz"}},
      {Field::FrictionForce, {"ffx", "ffy", "ffz"}}};
  std::vector<int> index;
  for (const std::string& c : columns.at(q.field)) {
    index.push_back(csv.column(c));
    if (index.back() < 0) fail(s, q, "bodies.csv in " + dir.string() + " has no column " + c);
  }
  const int time = csv.column("time"), body = csv.column("body");
  TimeSeries series;
  std::vector<std::string> names;
  for (const auto& row : csv.rows) {
    if (int(row.size()) != int(csv.header.size())) continue;  // a torn line cannot occur (atomic writes); be safe
    if (row[body] != q.body) {
      if (series.t.empty() && std::find(names.begin(), names.end(), row[body]) == names.end()) names.push_back(row[body]);
      continue;
    }
    Eigen::VectorXd v(index.size());
    for (std::size_t i = 0; i < index.size(); ++i) v[i] = to_number(row[index[i]]);
    series.t.push_back(to_number(row[time]));
    series.values.push_back(v);
  }
  if (series.t.empty()) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    fail(s, q, "the scene has no body '" + q.body + "' (bodies: " + list + ")");
  }
  if (q.displacement) {
    const Eigen::VectorXd first = series.values.front();
    for (Eigen::VectorXd& v : series.values) v -= first;
  }
  return series;
}

TimeSeries stats_series(const StudySpec& s, const QuantitySpec& q, const std::filesystem::path& dir) {
  const Csv csv = read_csv(s, q, dir / "stats.csv");
  const int column = csv.column(q.column), time = csv.column("time");
  if (column < 0) {
    std::string list;
    for (const std::string& h : csv.header) list += (list.empty() ? "" : ", ") + h;
    fail(s, q, "stats.csv has no column '" + q.column + "' (columns: " + list + ")");
  }
  TimeSeries series;
  for (const auto& row : csv.rows) {
    if (row.size() != csv.header.size()) continue;
    series.t.push_back(to_number(row[time]));
    series.values.push_back(Eigen::VectorXd::Constant(1, to_number(row[column])));
  }
  return series;
}

TimeSeries point_series(const StudySpec& s, const QuantitySpec& q, const std::filesystem::path& dir) {
  std::vector<PvdEntry> entries;
  try {
    entries = read_pvd(dir / "scene.pvd");
  } catch (const std::exception& e) {
    fail(s, q, std::string("cannot read the run's frames: ") + e.what());
  }
  if (entries.empty()) fail(s, q, "the run in " + dir.string() + " wrote no frames");
  // Reductions at one time need only the first frame and the frames around that time.
  std::vector<std::size_t> wanted;
  if (q.reduction == Reduction::End) wanted = {0, entries.size() - 1};
  else if (q.reduction == Reduction::At) {
    wanted = {0};
    for (std::size_t i = 0; i < entries.size(); ++i)
      if (std::abs(entries[i].time - q.time) <= 1e-9 * std::max(1.0, std::abs(q.time)) ||
          (i + 1 < entries.size() && entries[i].time < q.time && entries[i + 1].time > q.time))
        wanted.push_back(i), wanted.push_back(std::min(i + 1, entries.size() - 1));
  } else {
    for (std::size_t i = 0; i < entries.size(); ++i) wanted.push_back(i);
  }
  std::sort(wanted.begin(), wanted.end());
  wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
  auto block = [&](std::size_t i) {
    for (const NamedSurface& surface : read_frame(entries[i].file))
      if (surface.name == q.body) return surface.x;
    fail(s, q, "the frame " + entries[i].file.string() + " has no body '" + q.body + "'");
  };
  const Eigen::MatrixX3d x0 = block(0);
  Eigen::Index node = 0;
  (x0.rowwise() - q.rest_point.transpose()).rowwise().squaredNorm().minCoeff(&node);
  TimeSeries series;
  for (std::size_t i : wanted) {
    const Eigen::MatrixX3d x = i == 0 ? x0 : block(i);
    series.t.push_back(entries[i].time);
    series.values.push_back((x.row(node) - x0.row(node)).transpose());
  }
  return series;
}

}  // namespace

TimeSeries read_series(const StudySpec& study, const QuantitySpec& quantity, const std::filesystem::path& dir) {
  TimeSeries raw = quantity.source == Source::Body    ? body_series(study, quantity, dir)
                   : quantity.source == Source::Stats ? stats_series(study, quantity, dir)
                                                      : point_series(study, quantity, dir);
  if (quantity.from > -1e300 || quantity.until < 1e300) {
    TimeSeries kept;
    for (std::size_t k = 0; k < raw.t.size(); ++k)
      if (raw.t[k] >= quantity.from && raw.t[k] <= quantity.until) {
        kept.t.push_back(raw.t[k]);
        kept.values.push_back(raw.values[k]);
      }
    raw = std::move(kept);
  }
  if (quantity.components.empty()) return raw;
  for (Eigen::VectorXd& v : raw.values) {
    if (quantity.components[0] == -1) {
      v = Eigen::VectorXd::Constant(1, v.norm());
      continue;
    }
    Eigen::VectorXd picked(quantity.components.size());
    for (std::size_t i = 0; i < quantity.components.size(); ++i) picked[i] = v[quantity.components[i]];
    v = picked;
  }
  return raw;
}

Eigen::VectorXd value_at(const TimeSeries& series, double t) {
  const std::size_t n = series.t.size();
  const Eigen::Index size = series.values.empty() ? 1 : series.values[0].size();
  if (n == 0) return Eigen::VectorXd::Constant(size, kNaN);
  const double slack = 1e-9 * std::max({1.0, std::abs(series.t.front()), std::abs(series.t.back())});
  if (t < series.t.front() - slack || t > series.t.back() + slack) return Eigen::VectorXd::Constant(size, kNaN);
  if (t <= series.t.front()) return series.values.front();
  if (t >= series.t.back()) return series.values.back();
  const std::size_t k = std::size_t(std::upper_bound(series.t.begin(), series.t.end(), t) - series.t.begin());
  const double t0 = series.t[k - 1], t1 = series.t[k];
  const double w = t1 > t0 ? (t - t0) / (t1 - t0) : 1.0;
  return (1 - w) * series.values[k - 1] + w * series.values[k];
}

Eigen::VectorXd reduce(const QuantitySpec& q, const TimeSeries& series) {
  const Eigen::Index size = series.values.empty() ? 1 : series.values[0].size();
  if (series.values.empty()) return Eigen::VectorXd::Constant(size, kNaN);
  switch (q.reduction) {
    case Reduction::At: return value_at(series, q.time);
    case Reduction::End:
    case Reduction::Trajectory: return series.values.back();
    case Reduction::Change: return series.values.back() - series.values.front();
    case Reduction::Max:
    case Reduction::Min:
    case Reduction::MaxAbs: {
      double best = q.reduction == Reduction::Max ? -std::numeric_limits<double>::infinity()
                                                 : std::numeric_limits<double>::infinity();
      if (q.reduction == Reduction::MaxAbs) best = 0;
      for (const Eigen::VectorXd& v : series.values) {
        if (q.reduction == Reduction::Max) best = std::max(best, v[0]);
        else if (q.reduction == Reduction::Min) best = std::min(best, v[0]);
        else best = std::max(best, std::abs(v[0]));
      }
      return Eigen::VectorXd::Constant(1, best);
    }
    case Reduction::Crossing: {
      for (std::size_t k = 1; k < series.t.size(); ++k) {
        const double a = series.values[k - 1][0] - q.crossing_value, b = series.values[k][0] - q.crossing_value;
        if ((a < 0 && b >= 0) || (a > 0 && b <= 0))
          return Eigen::VectorXd::Constant(1, series.t[k - 1] + (series.t[k] - series.t[k - 1]) * a / (a - b));
      }
      return Eigen::VectorXd::Constant(1, kNaN);
    }
  }
  return Eigen::VectorXd::Constant(size, kNaN);
}

double reference_time(const QuantitySpec& q, const TimeSeries& series) {
  if (q.reduction == Reduction::At) return q.time;
  return series.t.empty() ? kNaN : series.t.back();
}

}  // namespace stiffsoft::study

namespace stiffsoft::study {

std::vector<double> stats_column(const std::filesystem::path& dir, const std::string& column) {
  std::ifstream in(dir / "stats.csv");
  std::vector<double> values;
  if (!in) return values;
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split_csv(line);
  const auto it = std::find(header.begin(), header.end(), column);
  if (it == header.end()) return values;
  const std::size_t index = std::size_t(it - header.begin());
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = split_csv(line);
    if (cells.size() == header.size()) values.push_back(to_number(cells[index]));
  }
  return values;
}

}  // namespace stiffsoft::study
