#include <stiffsoft/scene/start_gaps.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <stiffsoft/coupling/contact/broad_phase.hpp>
#include <stiffsoft/coupling/contact/distance_classification.hpp>
#include <stiffsoft/libfem/format_number.hpp>
#include <stiffsoft/scene/scene_schema.hpp>

namespace stiffsoft {

namespace {

/// A length for a message, 3 significant digits.
std::string metres(double x) { return fem::format_significant(x) + " m"; }

/// x rounded down to 3 significant digits, so a suggested bound printed by metres() still holds.
double round_down(double x) {
  if (!(x > 0) || !std::isfinite(x)) return x;
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 2);
  return std::floor(x / unit * (1 + 1e-12)) * unit;
}

/// The diagonal of the box around each body's surface at x (m).
std::vector<double> body_sizes(const Model& model, const Eigen::MatrixX3d& x) {
  std::vector<double> size;
  for (const BodyModel& body : model.bodies) {
    const auto rows = x.middleRows(body.vertex_begin, body.vertex_end - body.vertex_begin);
    size.push_back(rows.rows() ? (rows.colwise().maxCoeff() - rows.colwise().minCoeff()).norm() : 0.0);
  }
  return size;
}

std::string body_label(const Model& model, int b) {
  return "\"" + model.bodies[b].name + "\" (bodies[" + std::to_string(b) + "])";
}

}  // namespace

double smallest_body_size(const Model& model) {
  const std::vector<double> size = body_sizes(model, model.surface(model.initial_q()));
  return size.empty() ? 0.0 : *std::min_element(size.begin(), size.end());
}

double default_dhat(const Model& model) {
  return std::min(1e-3 * model.bounding_box_diagonal(), kMaxDhatPerBodySize * smallest_body_size(model));
}

std::vector<StartGap> start_gaps_below(const Model& model, double below) {
  const Eigen::MatrixX3d x = model.surface(model.initial_q());
  // Boxes grown by below/2 on every side meet whenever two primitives are closer than `below`.
  const Candidates candidates = broad_phase(model, x, x, below / 2);
  const CollisionMesh& mesh = model.mesh;
  std::map<std::pair<int, int>, double> squared;  // body pair → smallest squared distance
  const auto offer = [&](int a, int b, double d2) {
    if (a == b) return;  // a soft body's self-distance is not a start gap
    const auto key = std::minmax(a, b);
    const auto [it, inserted] = squared.emplace(key, d2);
    if (!inserted) it->second = std::min(it->second, d2);
  };
  const auto row = [&](int v) -> Eigen::Vector3d { return x.row(v).transpose(); };
  for (const auto& [v, f] : candidates.vertex_face)
    offer(mesh.vertex_body[v], mesh.face_body[f],
          contact::point_triangle_squared_distance(row(v), row(mesh.F(f, 0)), row(mesh.F(f, 1)), row(mesh.F(f, 2))));
  for (const auto& [e, g] : candidates.edge_edge)
    offer(mesh.edge_body[e], mesh.edge_body[g],
          contact::segment_segment_squared_distance(row(mesh.E(e, 0)), row(mesh.E(e, 1)), row(mesh.E(g, 0)),
                                                    row(mesh.E(g, 1))));
  std::vector<StartGap> gaps;
  for (const auto& [pair, d2] : squared) {
    const double d = std::sqrt(d2);
    if (d < below) gaps.push_back({pair.first, pair.second, d});
  }
  std::sort(gaps.begin(), gaps.end(), [](const StartGap& a, const StartGap& b) {
    return a.distance != b.distance ? a.distance < b.distance
                                    : std::tie(a.body_a, a.body_b) < std::tie(b.body_a, b.body_b);
  });
  return gaps;
}

void check_start_gaps(const Model& model, double dhat, bool dhat_given, const std::string& file) {
  if (model.bodies.empty()) return;
  const std::vector<double> size = body_sizes(model, model.surface(model.initial_q()));
  const int smallest = int(std::min_element(size.begin(), size.end()) - size.begin());
  const double size_bound = kMaxDhatPerBodySize * size[smallest];
  const std::vector<StartGap> gaps = start_gaps_below(model, dhat);
  const bool gap_bound = !gaps.empty() && gaps.front().distance / 2 < size_bound;
  const double fits = round_down(gap_bound ? gaps.front().distance / 2 : size_bound);
  const std::string why_fits =
      gap_bound ? " (half the smallest gap)" : " (1 % of body \"" + model.bodies[smallest].name + "\")";
  const std::string dhat_text =
      "d̂ = " + metres(dhat) +
      (dhat_given ? std::string()
                  : " (the default: the smaller of 1e-3 × the scene's bounding-box diagonal, " +
                                   metres(model.bounding_box_diagonal()) + ", and 1 % of the smallest body)");
  const std::string turn_off = "; setting contact.check_start_gaps to false skips this check";
  if (dhat > size_bound)
    throw SceneError(file, "contact.dhat",
                     dhat_text + " is above 1 % of the size of body " + body_label(model, smallest) +
                         ", the smallest (bounding-box diagonal " + metres(size[smallest]) +
                         "): its contacts would act at a visible distance. Set contact.dhat to at most " +
                         metres(fits) + why_fits + turn_off);
  if (!gaps.empty()) {
    const StartGap& g = gaps.front();
    const std::string others =
        gaps.size() > 1 ? " (" + std::to_string(gaps.size()) + " body pairs in all start closer than d̂)" : "";
    throw SceneError(file, "bodies",
                     "bodies " + body_label(model, g.body_a) + " and " + body_label(model, g.body_b) + " start " +
                         metres(g.distance) + " apart (closest surface points), closer than " + dhat_text + others +
                         ": the barrier would push them apart at t = 0. Move them further apart, or set "
                         "contact.dhat to at most " + metres(fits) + why_fits + turn_off);
  }
}

}  // namespace stiffsoft
