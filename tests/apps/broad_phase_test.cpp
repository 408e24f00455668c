/// @file The broad phase's candidates: every pair closer than d̂ is one of them, the list,
/// order included, is the same whatever the thread count, and the remembering BroadPhase finds
/// the same set at every call of a moving scene.

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <stiffsoft/coupling/contact/broad_phase.hpp>
#include <stiffsoft/coupling/contact/constraint_set.hpp>
#include <stiffsoft/coupling/contact/distance_classification.hpp>
#include <stiffsoft/coupling/contact/ordered_chunks.hpp>
#include <stiffsoft/coupling/contact/swept_candidates.hpp>
#include <stiffsoft/coupling/terms/ordered_sum.hpp>

#include "scene_helpers.hpp"

namespace stiffsoft {
namespace {

/// Boxes and a sphere a few millimetres apart, turned, over a fixed floor (d̂ = 1 cm).
constexpr const char* kHeap = R"({
  "description": "broad-phase test heap",
  "time": {"dt": 0.01, "duration": 0.01},
  "contact": {"dhat": 0.01, "check_start_gaps": false},
  "bodies": [
    {"name": "floor", "kind": "fixed", "mesh": {"primitive": "box", "size": [2.0, 0.1, 2.0]}, "position": [0.0, -0.05, 0.0]},
    {"name": "a", "mesh": {"primitive": "box", "size": [0.3, 0.2, 0.4]}, "density": 1000.0,
     "position": [0.0, 0.105, 0.0], "rotation_deg": [0.0, 10.0, 0.0]},
    {"name": "b", "mesh": {"primitive": "box", "size": [0.3, 0.2, 0.3]}, "density": 1000.0,
     "position": [0.05, 0.318, 0.02], "rotation_deg": [3.0, 40.0, 0.0]},
    {"name": "c", "mesh": {"primitive": "box", "size": [0.2, 0.2, 0.2]}, "density": 1000.0,
     "position": [0.29, 0.106, 0.0], "rotation_deg": [0.0, 0.0, 0.0]},
    {"name": "d", "mesh": {"primitive": "sphere", "radius": 0.1, "resolution": 8}, "density": 1000.0,
     "position": [-0.05, 0.531, 0.0]}
  ]
})";

/// A flat soft slab (self-contact through the grid).
constexpr const char* kSlab = R"({
  "description": "self-contact slab",
  "time": {"dt": 0.01, "duration": 0.01},
  "bodies": [{"name": "slab", "model": "soft", "mesh": {"primitive": "box", "size": [0.6, 0.06, 0.4]},
              "mesh_size": 0.05, "density": 100.0,
              "material": {"model": "stable_neo_hookean", "young": 1e5, "poisson": 0.3}}]
})";

Candidates candidates_with(int threads, const Model& model, const Eigen::MatrixX3d& x, double inflation) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  return broad_phase(model, x, x, inflation);
}

TEST(BroadPhase, SameCandidatesInTheSameOrderWhateverTheThreadCount) {
  const PreparedScene p =
      prepare_scene(load_scene_from_string(kHeap, STIFFSOFT_SOURCE_DIR, "heap.json", "heap"), "heap.json");
  const Eigen::MatrixX3d x = p.model.surface(p.model.initial_q());
  const Candidates one = candidates_with(1, p.model, x, 0.005);
  const Candidates two = candidates_with(2, p.model, x, 0.005);
  EXPECT_GT(one.vertex_face.size(), 0u);
  EXPECT_GT(one.edge_edge.size(), 0u);
  EXPECT_EQ(one.vertex_face, two.vertex_face);
  EXPECT_EQ(one.edge_edge, two.edge_edge);
}

TEST(BroadPhase, HoldsEveryPairCloserThanDhat) {
  const PreparedScene p =
      prepare_scene(load_scene_from_string(kHeap, STIFFSOFT_SOURCE_DIR, "heap.json", "heap"), "heap.json");
  const Model& model = p.model;
  const CollisionMesh& mesh = model.mesh;
  const double dhat = 0.01;
  const Eigen::MatrixX3d x = model.surface(model.initial_q());
  const Candidates found = broad_phase(model, x, x, dhat / 2);
  const std::set<std::array<int, 2>> vf(found.vertex_face.begin(), found.vertex_face.end());
  const std::set<std::array<int, 2>> ee(found.edge_edge.begin(), found.edge_edge.end());
  EXPECT_EQ(vf.size(), found.vertex_face.size()) << "a vertex–face pair is listed twice";
  EXPECT_EQ(ee.size(), found.edge_edge.size()) << "an edge–edge pair is listed twice";
  const auto row = [&](int v) -> Eigen::Vector3d { return x.row(v).transpose(); };
  const auto moving = [&](int b) { return model.bodies[b].dof >= 0; };
  int close = 0;
  for (int v = 0; v < int(x.rows()); ++v)
    for (int f = 0; f < int(mesh.F.rows()); ++f) {
      const int bv = mesh.vertex_body[v], bf = mesh.face_body[f];
      if (bv == bf || (!moving(bv) && !moving(bf))) continue;
      const double d2 = contact::point_triangle_squared_distance(row(v), row(mesh.F(f, 0)), row(mesh.F(f, 1)),
                                                                 row(mesh.F(f, 2)));
      if (d2 >= dhat * dhat) continue;
      ++close;
      EXPECT_TRUE(vf.count({v, f})) << "vertex " << v << ", face " << f << " at " << std::sqrt(d2) << " m";
    }
  for (int e = 0; e < int(mesh.E.rows()); ++e)
    for (int g = e + 1; g < int(mesh.E.rows()); ++g) {
      const int be = mesh.edge_body[e], bg = mesh.edge_body[g];
      if (be == bg || (!moving(be) && !moving(bg))) continue;
      const double d2 = contact::segment_segment_squared_distance(row(mesh.E(e, 0)), row(mesh.E(e, 1)),
                                                                  row(mesh.E(g, 0)), row(mesh.E(g, 1)));
      if (d2 >= dhat * dhat) continue;
      ++close;
      EXPECT_TRUE(ee.count({e, g})) << "edges " << e << ", " << g << " at " << std::sqrt(d2) << " m";
    }
  EXPECT_GT(close, 20) << "the heap should have pairs closer than d̂";
}

TEST(BroadPhase, SelfContactCandidatesAreExactlyThePairsWhoseBoxesOverlap) {
  // A flat soft slab against itself goes through the grid (grid_pairs): the candidates must be
  // exactly the pairs sharing no vertex whose inflated boxes overlap, each once.
  const PreparedScene p =
      prepare_scene(load_scene_from_string(kSlab, STIFFSOFT_SOURCE_DIR, "slab.json", "slab"), "slab.json");
  const CollisionMesh& mesh = p.model.mesh;
  const Eigen::MatrixX3d x = p.model.surface(p.model.initial_q());
  const double inflation = 0.01;
  const Candidates found = candidates_with(2, p.model, x, inflation);
  EXPECT_EQ(found.vertex_face, candidates_with(1, p.model, x, inflation).vertex_face);
  const auto box = [&](std::initializer_list<int> vertices) {
    Eigen::Array3d lo = Eigen::Array3d::Constant(1e300), hi = -lo;
    for (int v : vertices) {
      lo = lo.min(x.row(v).transpose().array() - inflation);
      hi = hi.max(x.row(v).transpose().array() + inflation);
    }
    return std::make_pair(lo, hi);
  };
  const auto overlap = [](const auto& a, const auto& b) {
    return (a.first <= b.second).all() && (b.first <= a.second).all();
  };
  std::vector<std::array<int, 2>> vf, ee;
  for (int v = 0; v < int(x.rows()); ++v)
    for (int f = 0; f < int(mesh.F.rows()); ++f)
      if ((mesh.F.row(f).array() != v).all() && overlap(box({v}), box({mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)})))
        vf.push_back({v, f});
  for (int e = 0; e < int(mesh.E.rows()); ++e)
    for (int g = e + 1; g < int(mesh.E.rows()); ++g) {
      const bool shared = mesh.E(e, 0) == mesh.E(g, 0) || mesh.E(e, 0) == mesh.E(g, 1) ||
                          mesh.E(e, 1) == mesh.E(g, 0) || mesh.E(e, 1) == mesh.E(g, 1);
      if (!shared && overlap(box({mesh.E(e, 0), mesh.E(e, 1)}), box({mesh.E(g, 0), mesh.E(g, 1)})))
        ee.push_back({e, g});
    }
  std::vector<std::array<int, 2>> found_vf = found.vertex_face, found_ee = found.edge_edge;
  std::sort(found_vf.begin(), found_vf.end());
  std::sort(found_ee.begin(), found_ee.end());
  std::printf("    slab: %zu vertices, %zu faces, %zu edges; %zu vertex-face and %zu edge-edge candidates\n",
              std::size_t(x.rows()), std::size_t(mesh.F.rows()), std::size_t(mesh.E.rows()), vf.size(), ee.size());
  EXPECT_GT(vf.size(), 100u);
  EXPECT_EQ(found_vf, vf);
  EXPECT_EQ(found_ee, ee);
}

/// Sorted copies of the candidates, to compare them as sets.
Candidates sorted_pairs(Candidates c) {
  std::sort(c.vertex_face.begin(), c.vertex_face.end());
  std::sort(c.edge_edge.begin(), c.edge_edge.end());
  return c;
}

/// Moves every body of the model a few hundred calls' worth of small random steps (a
/// tenth of the margin; each vertex also jitters, so soft bodies deform), one body now and
/// then by 3 margins, alternating swept (x → x + step) and proximity (x + step) calls, and
/// checks that BroadPhase finds exactly broad_phase's set at every call, and with it the sets of
/// the boxes before their growth and grown by 0.7 of it (broad_phase with those inflations: equal
/// here, since no two boxes of these random motions miss by less than 1e-9 of the shrink; over
/// the calls each set smaller than the next). Returns how many of
/// the calls found some body pair's primitive pairs again and how many took every one from memory.
std::pair<int, int> remembered_against_fresh(const Model& model, double margin, double inflation) {
  BroadPhase remembered(margin);
  std::mt19937 rng(17);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixX3d x = model.surface(model.initial_q());
  int refreshing = 0, from_memory = 0;
  std::size_t ungrown_pairs = 0, tighter_pairs = 0, grown_pairs = 0;  // over the calls
  for (int call = 0; call < 60; ++call) {
    Eigen::MatrixX3d step = Eigen::MatrixX3d::Zero(x.rows(), 3);
    for (std::size_t b = 0; b < model.bodies.size(); ++b) {
      const BodyModel& body = model.bodies[b];
      if (body.dof < 0 && body.representation != Representation::Soft) continue;  // fixed
      const Eigen::RowVector3d shift(normal(rng), normal(rng), normal(rng));
      const double scale = call % 10 == int(b) % 10 ? 3.0 * margin : 0.1 * margin;
      for (int v = body.vertex_begin; v < body.vertex_end; ++v)
        step.row(v) = scale * shift.normalized() + 0.01 * margin * Eigen::RowVector3d(normal(rng), normal(rng), normal(rng));
    }
    const Eigen::MatrixX3d next = x + step;
    const Eigen::MatrixX3d& start = call % 2 ? next : x;
    Candidates ungrown, tighter;
    const Candidates found =
        sorted_pairs(remembered.find(model, start, next, inflation, {{inflation, &ungrown}, {0.3 * inflation, &tighter}}));
    const Candidates fresh = sorted_pairs(broad_phase(model, start, next, inflation));
    EXPECT_EQ(found.vertex_face, fresh.vertex_face) << "call " << call;
    EXPECT_EQ(found.edge_edge, fresh.edge_edge) << "call " << call;
    const Candidates fresh_ungrown = sorted_pairs(broad_phase(model, start, next, 0.0));
    EXPECT_EQ(sorted_pairs(ungrown).vertex_face, fresh_ungrown.vertex_face) << "call " << call;
    EXPECT_EQ(sorted_pairs(ungrown).edge_edge, fresh_ungrown.edge_edge) << "call " << call;
    EXPECT_LT(fresh_ungrown.vertex_face.size() + fresh_ungrown.edge_edge.size(),
              fresh.vertex_face.size() + fresh.edge_edge.size()) << "call " << call;
    const Candidates fresh_tighter = sorted_pairs(broad_phase(model, start, next, 0.7 * inflation));
    EXPECT_EQ(sorted_pairs(tighter).vertex_face, fresh_tighter.vertex_face) << "call " << call;
    EXPECT_EQ(sorted_pairs(tighter).edge_edge, fresh_tighter.edge_edge) << "call " << call;
    ungrown_pairs += fresh_ungrown.vertex_face.size() + fresh_ungrown.edge_edge.size();
    tighter_pairs += fresh_tighter.vertex_face.size() + fresh_tighter.edge_edge.size();
    grown_pairs += fresh.vertex_face.size() + fresh.edge_edge.size();
    if (call > 0) (remembered.refreshed_pairs() > 0 ? refreshing : from_memory) += 1;
    x = next;
  }
  // The three growths give three different sets over the run (within a call two may coincide).
  EXPECT_LT(ungrown_pairs, tighter_pairs);
  EXPECT_LT(tighter_pairs, grown_pairs);
  return {refreshing, from_memory};
}

TEST(BroadPhase, RememberedPairsAreTheFreshBroadPhasesAtEveryCall) {
  const PreparedScene heap =
      prepare_scene(load_scene_from_string(kHeap, STIFFSOFT_SOURCE_DIR, "heap.json", "heap"), "heap.json");
  const auto [heap_refreshing, heap_from_memory] = remembered_against_fresh(heap.model, 0.005, 0.005);
  const PreparedScene slab =
      prepare_scene(load_scene_from_string(kSlab, STIFFSOFT_SOURCE_DIR, "slab.json", "slab"), "slab.json");
  const auto [slab_refreshing, slab_from_memory] = remembered_against_fresh(slab.model, 0.01, 0.01);
  std::printf("    calls that found pairs again / took all from memory: heap %d / %d, slab %d / %d\n", heap_refreshing,
              heap_from_memory, slab_refreshing, slab_from_memory);
  // Both paths ran: bodies that left their reference boxes and calls served from memory.
  EXPECT_GT(heap_refreshing, 0);
  EXPECT_GT(heap_from_memory, 0);
  EXPECT_GT(slab_refreshing, 0);
  EXPECT_GT(slab_from_memory, 0);
}

/// True when every pair of `part` is one of `whole`'s.
bool holds(const Candidates& whole, const Candidates& part) {
  const Candidates w = sorted_pairs(whole), p = sorted_pairs(part);
  return std::includes(w.vertex_face.begin(), w.vertex_face.end(), p.vertex_face.begin(), p.vertex_face.end()) &&
         std::includes(w.edge_edge.begin(), w.edge_edge.end(), p.edge_edge.begin(), p.edge_edge.end());
}

/// The index of the body called `name`.
int body_named(const Model& model, const std::string& name) {
  for (std::size_t b = 0; b < model.bodies.size(); ++b)
    if (model.bodies[b].name == name) return int(b);
  throw std::invalid_argument("no body " + name);
}

/// x with body `name`'s vertices shifted by `shift` (m).
Eigen::MatrixX3d shifted(const Model& model, Eigen::MatrixX3d x, const std::string& name, const Eigen::RowVector3d& shift) {
  const BodyModel& body = model.bodies[std::size_t(body_named(model, name))];
  for (int v = body.vertex_begin; v < body.vertex_end; ++v) x.row(v) += shift;
  return x;
}

TEST(SweptCandidates, ServeASegmentTheirBoxesHoldOrWhoseMovedBodiesAreAlone) {
  const PreparedScene heap =
      prepare_scene(load_scene_from_string(kHeap, STIFFSOFT_SOURCE_DIR, "heap.json", "heap"), "heap.json");
  const Model& model = heap.model;
  const double proximity = 0.005, slack = 1e-4;  // d̂ = 1 cm
  BroadPhase finder(0.01);
  const Eigen::MatrixX3d x = model.surface(model.initial_q());
  SweptCandidates kept(model, x, x, proximity, slack, 0.0, finder);
  // Within the slack of every box: served with no body moved.
  const Eigen::MatrixX3d nudged = shifted(model, x, "b", Eigen::RowVector3d(0, 0.5 * slack, 0));
  const auto within = kept.extension(model, x, nudged);
  ASSERT_TRUE(within.has_value());
  EXPECT_TRUE(within->empty());
  // The sphere on top (13 mm above the box below it) lifted by 0.3 m: its segment starts
  // near the box, so not served; from 0.3 m to 0.35 m up it is alone, served, and its boxes
  // follow it.
  const int sphere = body_named(model, "d");
  const Eigen::MatrixX3d lifted = shifted(model, x, "d", Eigen::RowVector3d(0, 0.3, 0));
  const Eigen::MatrixX3d higher = shifted(model, x, "d", Eigen::RowVector3d(0, 0.35, 0));
  EXPECT_FALSE(kept.extension(model, x, lifted).has_value());
  const auto alone = kept.extension(model, lifted, higher);
  ASSERT_TRUE(alone.has_value());
  EXPECT_EQ(*alone, std::vector<int>{sphere});
  EXPECT_FALSE(kept.covers(higher));
  kept.extend(model, lifted, higher, *alone);
  EXPECT_TRUE(kept.covers(lifted));
  EXPECT_TRUE(kept.covers(higher));
  EXPECT_TRUE(holds(kept.all(), broad_phase(model, lifted, higher, proximity + slack)));
  // Back down onto the box, or the box under it moved a centimetre: pairs the candidates may
  // lack, so not served.
  EXPECT_FALSE(kept.extension(model, higher, x).has_value());
  EXPECT_FALSE(kept.extension(model, higher, shifted(model, higher, "b", Eigen::RowVector3d(0.01, 0, 0))).has_value());
  // A soft body has pairs with itself: never served once it left its boxes.
  const PreparedScene slab =
      prepare_scene(load_scene_from_string(kSlab, STIFFSOFT_SOURCE_DIR, "slab.json", "slab"), "slab.json");
  const Eigen::MatrixX3d s = slab.model.surface(slab.model.initial_q());
  const SweptCandidates slab_kept(slab.model, s, s, 0.01, 1e-4, 0.0, finder);
  EXPECT_FALSE(slab_kept.extension(slab.model, s, shifted(slab.model, s, "slab", Eigen::RowVector3d(0, 1, 0))).has_value());
}

TEST(SweptCandidates, AServedSegmentsPairsAreAmongTheirs) {
  // Random small moves of every body (a quarter of the slack, so most segments are served)
  // and, now and then, one body by 3 cm (served only when it stays alone): whenever a segment
  // is served, the fresh broad phase of the segment, grown as the candidates were, is a subset.
  const PreparedScene heap =
      prepare_scene(load_scene_from_string(kHeap, STIFFSOFT_SOURCE_DIR, "heap.json", "heap"), "heap.json");
  const Model& model = heap.model;
  const double proximity = 0.005, slack = 4e-4;
  BroadPhase finder(0.01);
  std::mt19937 rng(23);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixX3d x = model.surface(model.initial_q());
  std::optional<SweptCandidates> kept;
  kept.emplace(model, x, x, proximity, slack, 0.0, finder);
  int served = 0, refused = 0;
  for (int call = 0; call < 80; ++call) {
    Eigen::MatrixX3d next = x;
    for (std::size_t b = 0; b < model.bodies.size(); ++b) {
      const BodyModel& body = model.bodies[b];
      if (body.dof < 0) continue;
      const Eigen::RowVector3d shift(normal(rng), normal(rng), normal(rng));
      const double scale = call % 7 == int(b) ? 0.03 : 0.25 * slack;
      for (int v = body.vertex_begin; v < body.vertex_end; ++v) next.row(v) += scale * shift.normalized();
    }
    if (const auto moved = kept->extension(model, x, next)) {
      kept->extend(model, x, next, *moved);
      ++served;
      EXPECT_TRUE(kept->covers(x) && kept->covers(next)) << "call " << call;
      EXPECT_TRUE(holds(kept->all(), broad_phase(model, x, next, proximity + slack))) << "call " << call;
    } else {
      ++refused;
      kept.emplace(model, x, next, proximity, slack, 0.0, finder);
    }
    x = next;
  }
  std::printf("    segments served by kept candidates / by a new broad phase: %d / %d\n", served, refused);
  EXPECT_GT(served, 10);
  EXPECT_GT(refused, 3);
}

/// A random configuration covered by candidates of the segment x0 → x1 with this slack (m):
/// each body at a random point of its segment, shifted by the slack along every axis, each
/// way at random (a corner of the region its vertices may reach, where pairs come closest).
Eigen::MatrixX3d covered_at_random(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1,
                                   double slack, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Eigen::MatrixX3d x = x0;
  for (const BodyModel& body : model.bodies) {
    const double t = unit(rng);
    Eigen::RowVector3d corner;
    for (int i = 0; i < 3; ++i) corner(i) = (unit(rng) < 0.5 ? -1 : 1) * (1 - 1e-9) * slack;
    for (int v = body.vertex_begin; v < body.vertex_end; ++v) x.row(v) = x0.row(v) + t * (x1.row(v) - x0.row(v)) + corner;
  }
  return x;
}

bool same_contacts(const std::vector<ContactConstraint>& a, const std::vector<ContactConstraint>& b) {
  const auto same = [](const ContactConstraint& p, const ContactConstraint& q) {
    return p.stencil.kind == q.stencil.kind && p.vertices == q.vertices && p.weight == q.weight &&
           p.distance == q.distance && p.stencil.eps_x == q.stencil.eps_x &&
           p.stencil.segment_distance == q.stencil.segment_distance;
  };
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), same);
}

TEST(SweptCandidates, TheNearOnesGiveEveryCoveredConfigurationsContacts) {
  // Every body of the heap moved by 4 mm, then anywhere on that move and 2 mm off it along each
  // axis (d̂ = 1 cm, bodies 5–18 mm apart): the contacts change from one configuration to the
  // next, and the candidates sorted out at the first one give them all, bit for bit, at every
  // other.
  const PreparedScene heap =
      prepare_scene(load_scene_from_string(kHeap, STIFFSOFT_SOURCE_DIR, "heap.json", "heap"), "heap.json");
  const Model& model = heap.model;
  const double dhat = 0.01, slack = 2e-3;
  BroadPhase finder(dhat);
  std::mt19937 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::MatrixX3d x0 = model.surface(model.initial_q());
  Eigen::MatrixX3d x1 = x0;
  for (const BodyModel& body : model.bodies) {
    if (body.dof < 0) continue;
    const Eigen::RowVector3d shift = 4e-3 * Eigen::RowVector3d(normal(rng), normal(rng), normal(rng)).normalized();
    for (int v = body.vertex_begin; v < body.vertex_end; ++v) x1.row(v) += shift;
  }
  SweptCandidates kept(model, x0, x1, 0.5 * dhat, slack, 0.0, finder);
  const Eigen::MatrixX3d first = covered_at_random(model, x0, x1, slack, rng);
  ASSERT_TRUE(kept.covers(first));
  const std::vector<double> reach = kept.reach_from(first);
  Candidates near;
  const NearCandidates sort_out{reach, near};
  EXPECT_TRUE(same_contacts(build_constraints(model, first, kept.all(), dhat, &sort_out),
                            build_constraints(model, first, kept.all(), dhat)));
  const std::size_t all = kept.all().vertex_face.size() + kept.all().edge_edge.size();
  const std::size_t kept_near = near.vertex_face.size() + near.edge_edge.size();
  std::printf("    candidates: %zu, near: %zu\n", all, kept_near);
  EXPECT_LT(kept_near, all);
  std::set<std::size_t> counts;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::MatrixX3d x = covered_at_random(model, x0, x1, slack, rng);
    ASSERT_TRUE(kept.covers(x));
    const std::vector<ContactConstraint> contacts = build_constraints(model, x, kept.all(), dhat);
    counts.insert(contacts.size());
    EXPECT_TRUE(same_contacts(build_constraints(model, x, near, dhat), contacts)) << "trial " << trial;
  }
  EXPECT_GT(counts.size(), 3u);  // the configurations differ in their contacts
}

TEST(SweptCandidates, AnAdvancedSegmentHasANewBroadPhasesSetsForItsCcdAndIslands) {
  // Random small moves of every body (0.9 of the slack) and, in turn, one or two bodies by
  // 3–8 mm, mostly next to the others (d̂ = 1 cm): each segment extension() refuses or serves
  // without a moved body is advanced, and
  // its for_ccd() and tight() are a new SweptCandidates' of the segment, as sets; all() holds
  // that one's, and the near candidates, completed from pending() at the segment's start, give
  // the contacts all() gives at configurations anywhere the candidates serve.
  const PreparedScene heap =
      prepare_scene(load_scene_from_string(kHeap, STIFFSOFT_SOURCE_DIR, "heap.json", "heap"), "heap.json");
  const Model& model = heap.model;
  const double dhat = 0.01, proximity = 0.5 * dhat, slack = 4e-4, tight_slack = 2e-3;
  BroadPhase finder(dhat), fresh_finder(dhat);
  std::mt19937 rng(41);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Eigen::MatrixX3d x = model.surface(model.initial_q());
  std::optional<SweptCandidates> swept;
  int advanced = 0, with_pending = 0;
  for (int call = 0; call < 80; ++call) {
    // Every fifth segment from new candidates and with small moves only: all its pairs are the
    // first broad phase's (which must hold tight()'s pairs of a segment of the slack).
    const bool small = call % 5 == 0;
    if (small) swept.emplace(model, x, x, proximity, slack, tight_slack, finder);
    SweptCandidates& kept = *swept;
    Eigen::MatrixX3d next = x;
    for (std::size_t b = 0; b < model.bodies.size(); ++b) {
      const BodyModel& body = model.bodies[b];
      if (body.dof < 0) continue;
      const Eigen::RowVector3d shift(normal(rng), normal(rng), normal(rng));
      const bool far = !small && (int(b) == 1 + call % 4 || (call % 3 == 0 && int(b) == 1 + (call + 2) % 4));
      const double scale = far ? 3e-3 + 5e-3 * unit(rng) : 0.9 * slack;
      for (int v = body.vertex_begin; v < body.vertex_end; ++v) next.row(v) += scale * shift.normalized();
    }
    // The near candidates sorted out at the segment's start before the move, as a line search does.
    if (!kept.near() && !kept.pending() && kept.covers(x)) {
      const std::vector<double> reach = kept.reach_from(x);
      Candidates near;
      const NearCandidates sort_out{reach, near};
      build_constraints(model, x, kept.all(), dhat, &sort_out);
      kept.keep_near(model, std::move(near), reach);
    }
    const auto alone = kept.extension(model, x, next);
    if (alone && !alone->empty()) {  // the moved bodies alone: nothing to find
      kept.extend(model, x, next, *alone);
      x = next;
      continue;
    }
    ASSERT_TRUE(kept.advance(model, x, next)) << "call " << call;
    ++advanced;
    const SweptCandidates fresh(model, x, next, proximity, slack, tight_slack, fresh_finder);
    EXPECT_EQ(sorted_pairs(kept.for_ccd()).vertex_face, sorted_pairs(fresh.for_ccd()).vertex_face) << "call " << call;
    EXPECT_EQ(sorted_pairs(kept.for_ccd()).edge_edge, sorted_pairs(fresh.for_ccd()).edge_edge) << "call " << call;
    EXPECT_EQ(sorted_pairs(kept.tight()).vertex_face, sorted_pairs(fresh.tight()).vertex_face) << "call " << call;
    EXPECT_EQ(sorted_pairs(kept.tight()).edge_edge, sorted_pairs(fresh.tight()).edge_edge) << "call " << call;
    EXPECT_TRUE(holds(kept.all(), fresh.all())) << "call " << call;
    EXPECT_TRUE(kept.covers(x) && kept.covers(next)) << "call " << call;
    if (const Candidates* pending = kept.pending()) {
      ++with_pending;
      const std::vector<double> reach = kept.reach_from(x);
      Candidates near;
      const NearCandidates sort_out{reach, near};
      build_constraints(model, x, *pending, dhat, &sort_out);
      kept.add_near(model, near, reach);
      ASSERT_TRUE(kept.near() != nullptr);
      for (int trial = 0; trial < 5; ++trial) {
        const Eigen::MatrixX3d at = covered_at_random(model, x, next, 0.0, rng);
        ASSERT_TRUE(kept.covers(at));
        EXPECT_TRUE(same_contacts(build_constraints(model, at, *kept.near(), dhat), build_constraints(model, at, kept.all(), dhat)))
            << "call " << call << " trial " << trial;
      }
    }
    x = next;
  }
  std::printf("    segments advanced: %d, of them with near candidates completed: %d\n", advanced, with_pending);
  EXPECT_GT(with_pending, 20);
}

TEST(InOrderedChunks, GathersInItemOrderWhateverTheThreadCount) {
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    std::vector<int> out;
    in_ordered_chunks<std::vector<int>>(
        1003, 7,
        [](std::size_t i, std::vector<int>& part) {
          if (i % 3) part.push_back(int(i));
        },
        [&](const std::vector<int>& part) { out.insert(out.end(), part.begin(), part.end()); });
    std::vector<int> serial;
    for (int i = 0; i < 1003; ++i)
      if (i % 3) serial.push_back(i);
    EXPECT_EQ(out, serial) << threads << " threads";
  }
}

TEST(OrderedSum, IsTheSerialLoopsSumBitForBitWhateverTheThreadCount) {
  // Terms of very different sizes, so that any other order of addition rounds differently.
  const auto term = [](std::size_t k) { return std::ldexp(1.0 + 1e-3 * double(k % 17), int(k % 61) - 30) * (k % 2 ? 1 : -1); };
  double serial = 0.25;
  for (std::size_t k = 0; k < 5000; ++k) serial += term(k);
  double reversed = 0.25;
  for (std::size_t k = 5000; k-- > 0;) reversed += term(k);
  EXPECT_NE(reversed, serial);  // the order matters for these terms
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    EXPECT_EQ(ordered_sum(0.25, 5000, 7, term), serial) << threads << " threads";
  }
}

}  // namespace
}  // namespace stiffsoft
