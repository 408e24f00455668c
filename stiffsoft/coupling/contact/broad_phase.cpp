#include <stiffsoft/coupling/contact/broad_phase.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <stiffsoft/coupling/contact/ordered_chunks.hpp>
#include <stiffsoft/coupling/for_each_item.hpp>

namespace stiffsoft {

namespace {

using Box = AxisBox;

Box intersection(const Box& a, const Box& b) { return {a.lo.max(b.lo), a.hi.min(b.hi)}; }

/// Grows a to hold b (inlined: called once per vertex of every primitive's box).
[[gnu::always_inline]] inline void extend(Box& a, const Box& b) {
  a.lo = a.lo.min(b.lo);
  a.hi = a.hi.max(b.hi);
}

struct Keyed {
  double lo, hi;  // extent along the sweep axis
  int id;
};

/// out[k] spans the boxes of the vertices of primitive k (a row of F or E), for k in [begin, end).
template <class Primitives>
void span(const Primitives& primitives, const std::vector<Box>& vertex, Eigen::Index begin, Eigen::Index end,
          std::vector<Box>& out) {
  for (Eigen::Index k = begin; k < end; ++k) {
    Box box = vertex[primitives(k, 0)];
    for (Eigen::Index i = 1; i < primitives.cols(); ++i) extend(box, vertex[primitives(k, i)]);
    out[k] = box;
  }
}

/// Boxes of every surface vertex, face and edge (rows of CollisionMesh's F and E) on the
/// segment x0 → x1 (|V|×3 each, m), each vertex's box spanning both ends grown by the inflation
/// (m) and each primitive's spanning its vertices' boxes.
struct PrimitiveBoxes {
  std::vector<AxisBox> vertex, face, edge;
};

/// PrimitiveBoxes of the segment x0 → x1 grown by `inflation` (m).
PrimitiveBoxes primitive_boxes(const CollisionMesh& mesh, const Eigen::MatrixX3d& x0,
                               const Eigen::MatrixX3d& x1, double inflation) {
  // In tasks of 1024 primitives, each spanned in one call: one task or call per primitive
  // cost as much as its box.
  constexpr Eigen::Index kGrain = 1024;
  PrimitiveBoxes boxes;
  const auto span_all = [&](const auto& primitives, std::vector<Box>& out) {
    out.resize(primitives.rows());
    tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, primitives.rows(), kGrain),
                      [&](const tbb::blocked_range<Eigen::Index>& r) { span(primitives, boxes.vertex, r.begin(), r.end(), out); });
  };
  boxes.vertex.resize(x0.rows());
  for_each_item(std::size_t(x0.rows()), std::size_t(kGrain), [&](std::size_t v) {
    const Eigen::Array3d a = x0.row(v).transpose().array(), b = x1.row(v).transpose().array();
    boxes.vertex[v] = {a.min(b) - inflation, a.max(b) + inflation};
  });
  span_all(mesh.F, boxes.face);
  span_all(mesh.E, boxes.edge);
  return boxes;
}

/// `out` becomes the primitives in [begin, end) whose box meets `region`, keyed along `axis`, in
/// id order (its storage reused: a broad phase asks six times per pair of bodies).
std::vector<Keyed>& inside(const std::vector<Box>& boxes, int begin, int end, const Box& region, int axis,
                           std::vector<Keyed>& out) {
  out.clear();
  for (int i = begin; i < end; ++i)
    if (boxes[i].overlaps(region)) out.push_back({boxes[i].lo[axis], boxes[i].hi[axis], i});
  return out;
}

/// The list sorted in place by the low end of its key, as sweep() needs it.
std::vector<Keyed>& sorted(std::vector<Keyed>& list) {
  std::sort(list.begin(), list.end(), [](const Keyed& a, const Keyed& b) { return a.lo < b.lo; });
  return list;
}

/// Sort-and-sweep of two lists sorted by sorted(): calls emit(a, b) for every pair whose full boxes overlap.
template <class Emit>
void sweep(const std::vector<Keyed>& A, const std::vector<Box>& boxes_a, const std::vector<Keyed>& B,
           const std::vector<Box>& boxes_b, Emit&& emit) {
  size_t j0 = 0;
  for (const Keyed& a : A) {
    // A prefix of B that ends before a starts ends before every later a too.
    while (j0 < B.size() && B[j0].hi < a.lo) ++j0;
    for (size_t j = j0; j < B.size() && B[j].lo <= a.hi; ++j) {
      if (B[j].hi < a.lo) continue;
      if (boxes_a[a.id].overlaps(boxes_b[B[j].id])) emit(a.id, B[j].id);
    }
  }
}

/// Pairs (i, j) of the lists A and B (ids into boxes_a, boxes_b) whose boxes overlap, through a
/// uniform grid over `region`: every box goes into the cells it meets, and a pair is tested in
/// the cell that holds the low corner of its two boxes' intersection only, so once. That cell
/// is the componentwise largest of the two boxes' low-corner cells: along each axis it is the
/// first cell of one of the two boxes, so three bits kept per cell member (is this the box's
/// first cell along x, y, z) decide it. When A and B are the same list (a body against itself),
/// each unordered pair is tested once and emitted as (i, j) with i < j. For a body against
/// itself, where a sweep along one axis of a flat body meets most of the body at every step.
/// Calls emit(i, j) in cell order, then list order: fixed by the boxes.
template <class Emit>
void grid_pairs(const std::vector<Keyed>& A, const std::vector<Box>& boxes_a, const std::vector<Keyed>& B,
                const std::vector<Box>& boxes_b, const Box& region, Emit&& emit) {
  if (A.empty() || B.empty()) return;
  const bool same = &A == &B && &boxes_a == &boxes_b;
  // Cells about the mean box (measured on cube_on_mattress: a cell twice that tests more pairs,
  // one of 0.7 fills more cells), at most a few cells per box in all.
  Eigen::Array3d mean = Eigen::Array3d::Zero();
  for (const Keyed& k : A) mean += boxes_a[k.id].hi - boxes_a[k.id].lo;
  for (const Keyed& k : B) mean += boxes_b[k.id].hi - boxes_b[k.id].lo;
  const Eigen::Array3d extent = (region.hi - region.lo).max(1e-300);
  const double boxes = double(A.size() + B.size());
  double cell = std::max(mean.maxCoeff() / boxes, std::cbrt(extent.prod() / (2.0 * boxes)));
  if (!(cell > 0.0)) cell = extent.maxCoeff();
  const auto dims_for = [&](double h) -> Eigen::Array3d { return (extent / h).min(1e6).ceil().max(1.0); };
  while (dims_for(cell).prod() > 4.0 * boxes + 64.0) cell *= 2.0;  // flat or empty boxes
  const Eigen::Array3i dims = dims_for(cell).template cast<int>();
  const auto cell_of = [&](const Eigen::Array3d& p) -> Eigen::Array3i {
    return ((p - region.lo) / cell).floor().cast<int>().max(0).min(dims - 1);
  };
  const auto flat = [&](const Eigen::Array3i& c) { return (c[2] * dims[1] + c[1]) * dims[0] + c[0]; };
  /// Cell lists by a counting sort: each member's id, and in bit k whether the cell is the
  /// box's first along axis k.
  struct Member {
    int id, first;
  };
  const auto bucket = [&](const std::vector<Keyed>& list, const std::vector<Box>& boxes,
                          std::vector<int>& offsets, std::vector<Member>& members) {
    offsets.assign(std::size_t(dims.prod()) + 1, 0);
    const auto each_cell = [&](const Box& b, auto&& f) {
      const Eigen::Array3i lo = cell_of(b.lo), hi = cell_of(b.hi);
      for (int k = lo[2]; k <= hi[2]; ++k)
        for (int j = lo[1]; j <= hi[1]; ++j)
          for (int i = lo[0]; i <= hi[0]; ++i)
            f(flat({i, j, k}), int(i == lo[0]) | int(j == lo[1]) << 1 | int(k == lo[2]) << 2);
    };
    for (const Keyed& e : list) each_cell(boxes[e.id], [&](int c, int) { ++offsets[c + 1]; });
    for (std::size_t c = 1; c < offsets.size(); ++c) offsets[c] += offsets[c - 1];
    members.resize(std::size_t(offsets.back()));
    std::vector<int> next(offsets.begin(), offsets.end() - 1);
    for (const Keyed& e : list) each_cell(boxes[e.id], [&](int c, int first) { members[next[c]++] = {e.id, first}; });
  };
  std::vector<int> offsets_a, offsets_b;
  std::vector<Member> members_a, members_b;
  bucket(A, boxes_a, offsets_a, members_a);
  if (!same) bucket(B, boxes_b, offsets_b, members_b);
  const std::vector<int>& offsets_other = same ? offsets_a : offsets_b;
  const std::vector<Member>& members_other = same ? members_a : members_b;
  for (int c = 0; c + 1 < int(offsets_a.size()); ++c)
    for (int p = offsets_a[c]; p < offsets_a[c + 1]; ++p) {
      const Member& a = members_a[p];
      for (int q = same ? p + 1 : offsets_other[c]; q < offsets_other[c + 1]; ++q) {
        const Member& b = members_other[q];
        if ((a.first | b.first) == 7 && boxes_a[a.id].overlaps(boxes_b[b.id]))
          same ? emit(std::min(a.id, b.id), std::max(a.id, b.id)) : emit(a.id, b.id);
      }
    }
}

/// Each body's box: the union of its vertices' boxes.
std::vector<Box> body_boxes(const Model& model, const std::vector<Box>& vertex) {
  const int nb = int(model.bodies.size());
  std::vector<Box> body_box(nb);
  tbb::parallel_for(0, nb, [&](int b) {
    const BodyModel& body = model.bodies[b];
    Box box{Eigen::Array3d::Constant(1e300), Eigen::Array3d::Constant(-1e300)};
    for (int v = body.vertex_begin; v < body.vertex_end; ++v) extend(box, vertex[v]);
    body_box[b] = box;
  });
  return body_box;
}

/// Body pairs (a < b) whose boxes overlap and one of which moves, by sort-and-sweep along x,
/// then (b, b) for every body with self-contact.
std::vector<std::array<int, 2>> body_pairs(const Model& model, const std::vector<Box>& body_box) {
  const int nb = int(model.bodies.size());
  std::vector<int> order(nb);
  for (int b = 0; b < nb; ++b) order[b] = b;
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return body_box[a].lo[0] < body_box[b].lo[0]; });
  // The boxes' bounds and whether each body moves, in sweep order and one array each: the inner
  // loop reads them in a row (from an array of boxes it took a quarter more instructions).
  std::array<std::vector<double>, 6> bound;  // lo x, hi x, lo y, hi y, lo z, hi z
  for (std::vector<double>& b : bound) b.resize(std::size_t(nb));
  std::vector<char> moving(static_cast<std::size_t>(nb));
  for (int i = 0; i < nb; ++i) {
    const Box& box = body_box[order[i]];
    for (int k = 0; k < 3; ++k) bound[2 * k][i] = box.lo[k], bound[2 * k + 1][i] = box.hi[k];
    moving[i] = model.bodies[order[i]].carries_dofs();
  }
  // Most bodies the sweep meets do not overlap in y or z, unpredictably: each is written and
  // kept only when it does, without a branch on it. The sweep runs in chunks of bodies in
  // parallel, their pairs gathered in the serial sweep's order.
  struct Found {
    std::vector<std::array<int, 2>> pairs;  // positions in the sweep order
    std::size_t count = 0;
  };
  std::vector<std::array<int, 2>> pairs;
  in_ordered_chunks<Found>(
      std::size_t(nb), 64,
      [&](std::size_t i, Found& found) {
        const double lo_x = bound[0][i], hi_x = bound[1][i];
        const double lo_y = bound[2][i], hi_y = bound[3][i], lo_z = bound[4][i], hi_z = bound[5][i];
        const char moves_i = moving[i];
        int end = int(i) + 1;  // the bodies the sweep meets: i + 1 … end − 1
        while (end < nb && bound[0][std::size_t(end)] <= hi_x) ++end;
        if (found.pairs.size() < found.count + std::size_t(end))
          found.pairs.resize(2 * (found.count + std::size_t(end)));
        const double *hx = bound[1].data(), *ly = bound[2].data(), *hy = bound[3].data();
        const double *lz = bound[4].data(), *hz = bound[5].data();
        for (int j = int(i) + 1; j < end; ++j) {
          found.pairs[found.count] = {int(i), j};
          found.count += (moves_i | moving[std::size_t(j)]) & (lo_x <= hx[j]) & (lo_y <= hy[j]) &
                         (ly[j] <= hi_y) & (lo_z <= hz[j]) & (lz[j] <= hi_z);
        }
      },
      [&](const Found& found) {
        for (std::size_t k = 0; k < found.count; ++k) {
          const int a = order[std::size_t(found.pairs[k][0])], b = order[std::size_t(found.pairs[k][1])];
          pairs.push_back({std::min(a, b), std::max(a, b)});
        }
      });
  for (int b = 0; b < nb; ++b)
    if (model.bodies[b].self_contact()) pairs.push_back({b, b});
  return pairs;
}

/// Appends to `out` the primitive pairs of bodies a and b (a = b: a soft body against itself)
/// whose boxes overlap.
void primitive_pairs(const Model& model, const PrimitiveBoxes& boxes, const std::vector<Box>& body_box, int a, int b,
                     Candidates& out) {
  const CollisionMesh& mesh = model.mesh;
  const BodyModel& A = model.bodies[a];
  const BodyModel& B = model.bodies[b];
  const Box region = intersection(body_box[a], body_box[b]);
  int axis;
  (region.hi - region.lo).maxCoeff(&axis);
  thread_local std::array<std::vector<Keyed>, 6> lists;  // each thread's, reused from pair to pair
  auto& va = inside(boxes.vertex, A.vertex_begin, A.vertex_end, region, axis, lists[0]);
  auto& fa = inside(boxes.face, A.face_begin, A.face_end, region, axis, lists[1]);
  auto& ea = inside(boxes.edge, A.edge_begin, A.edge_end, region, axis, lists[2]);
  if (a == b) {
    // Self-contact of a soft body: every pair once, none that shares a vertex.
    grid_pairs(va, boxes.vertex, fa, boxes.face, region, [&](int v, int f) {
      if ((mesh.F.row(f).array() != v).all()) out.vertex_face.push_back({v, f});
    });
    grid_pairs(ea, boxes.edge, ea, boxes.edge, region, [&](int e, int g) {
      if (mesh.E(e, 0) != mesh.E(g, 0) && mesh.E(e, 0) != mesh.E(g, 1) &&
          mesh.E(e, 1) != mesh.E(g, 0) && mesh.E(e, 1) != mesh.E(g, 1))
        out.edge_edge.push_back({e, g});
    });
    return;
  }
  const auto& vb = sorted(inside(boxes.vertex, B.vertex_begin, B.vertex_end, region, axis, lists[3]));
  const auto& fb = sorted(inside(boxes.face, B.face_begin, B.face_end, region, axis, lists[4]));
  const auto& eb = sorted(inside(boxes.edge, B.edge_begin, B.edge_end, region, axis, lists[5]));
  sweep(sorted(va), boxes.vertex, fb, boxes.face, [&](int v, int f) { out.vertex_face.push_back({v, f}); });
  sweep(vb, boxes.vertex, sorted(fa), boxes.face, [&](int v, int f) { out.vertex_face.push_back({v, f}); });
  sweep(sorted(ea), boxes.edge, eb, boxes.edge,
        [&](int e, int g) { out.edge_edge.push_back({std::min(e, g), std::max(e, g)}); });
}

/// Where keep_overlapping() appends each shrunk set's pairs.
using Shrunk = std::array<std::vector<std::array<int, 2>>*, BroadPhase::kMostShrunk>;

/// keep_overlapping() with `Levels` shrunk sets, a compile-time count: the loop over them
/// unrolled and their counts in registers (a loop over a run-time count took half as long again);
/// the overlapping pairs themselves kept in `out` only when `Grown`.
template <std::size_t Levels, bool Grown>
void keep_overlapping_in(const std::array<int, 2>* pairs, std::size_t n, const std::vector<Box>& a,
                         const std::vector<Box>& b, std::vector<std::array<int, 2>>* out, const Shrunk& shrunk,
                         const std::array<double, BroadPhase::kMostShrunk>& shrink) {
  // Overlap of the shrunk boxes, x.lo + shrink ≤ y.hi − shrink, tested as an overlap of the
  // grown ones no smaller than 2·shrink less 1e-9 of it: a superset by far less than the CCD's
  // own rounding allowance (additive_ccd.hpp), whose box test then rejects those pairs.
  std::array<double, Levels + 1> gap{};  // Levels + 1 here and below: no zero-sized arrays
  for (std::size_t l = 0; l < Levels; ++l) gap[l] = 2 * shrink[l] * (1 - 1e-9);
  constexpr std::size_t kBlock = 256;
  std::array<int, 2> kept[kBlock], kept_shrunk[Levels + 1][kBlock];
  for (std::size_t begin = 0; begin < n; begin += kBlock) {
    const std::size_t end = std::min(n, begin + kBlock);
    std::size_t count = 0;
    std::array<std::size_t, Levels + 1> shrunk_count{};
    for (std::size_t k = begin; k < end; ++k) {
      const auto& pair = pairs[k];
      const Box& x = a[pair[0]];
      const Box& y = b[pair[1]];
      // How far the boxes overlap along the axis where they overlap least (negative: a gap).
      // u − v ≥ 0 exactly when u ≥ v, so the overlap test is exact.
      const double overlap = std::min({y.hi[0] - x.lo[0], x.hi[0] - y.lo[0], y.hi[1] - x.lo[1], x.hi[1] - y.lo[1],
                                       y.hi[2] - x.lo[2], x.hi[2] - y.lo[2]});
      if constexpr (Grown) {
        kept[count] = pair;
        count += overlap >= 0;
      }
      for (std::size_t l = 0; l < Levels; ++l) {
        kept_shrunk[l][shrunk_count[l]] = pair;
        shrunk_count[l] += overlap >= gap[l];
      }
    }
    if constexpr (Grown) out->insert(out->end(), kept, kept + count);
    for (std::size_t l = 0; l < Levels; ++l)
      shrunk[l]->insert(shrunk[l]->end(), kept_shrunk[l], kept_shrunk[l] + shrunk_count[l]);
  }
}

/// Appends to `out` (unless null) the pairs (i, j) of pairs[0, n) whose boxes a[i] and b[j] overlap, in
/// order, and to each of the first `levels` sets of `shrunk` those whose boxes still overlap shrunk by
/// its `shrink` on every side. Most do in a resting pile, unpredictably: each pair is written
/// and kept only when its boxes overlap, without a branch on it, into a block on the stack (not
/// zero-filled, unlike a resized vector) that is then appended.
void keep_overlapping(const std::array<int, 2>* pairs, std::size_t n, const std::vector<Box>& a,
                      const std::vector<Box>& b, std::vector<std::array<int, 2>>* out, const Shrunk& shrunk,
                      const std::array<double, BroadPhase::kMostShrunk>& shrink, std::size_t levels) {
  static_assert(BroadPhase::kMostShrunk == 2, "one case per count below");
  if (!out) {
    if (levels == 1) keep_overlapping_in<1, false>(pairs, n, a, b, out, shrunk, shrink);
    if (levels >= 2) keep_overlapping_in<2, false>(pairs, n, a, b, out, shrunk, shrink);
    return;
  }
  switch (levels) {
    case 0: keep_overlapping_in<0, true>(pairs, n, a, b, out, shrunk, shrink); break;
    case 1: keep_overlapping_in<1, true>(pairs, n, a, b, out, shrunk, shrink); break;
    default: keep_overlapping_in<2, true>(pairs, n, a, b, out, shrunk, shrink); break;
  }
}

}  // namespace

Candidates broad_phase(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1,
                       double inflation) {
  const PrimitiveBoxes boxes = primitive_boxes(model.mesh, x0, x1, inflation);
  const std::vector<Box> body_box = body_boxes(model, boxes.vertex);
  const std::vector<std::array<int, 2>> pairs = body_pairs(model, body_box);
  // Primitive pairs of a few body pairs per task, gathered in body-pair order.
  Candidates all;
  in_ordered_chunks<Candidates>(
      pairs.size(), 8, [&](std::size_t k, Candidates& out) { primitive_pairs(model, boxes, body_box, pairs[k][0], pairs[k][1], out); },
      [&](const Candidates& part) { all.append(part); });
  return all;
}

Candidates pairs_of_bodies(const Model& model, const Eigen::ArrayX3d& lo, const Eigen::ArrayX3d& hi,
                           double inflation, const std::vector<AxisBox>& body_box,
                           const std::vector<int>& bodies) {
  const CollisionMesh& mesh = model.mesh;
  const int nb = int(model.bodies.size());
  // The vertices', faces' and edges' boxes only of the bodies a pair needs.
  PrimitiveBoxes boxes;
  boxes.vertex.resize(std::size_t(lo.rows()));
  boxes.face.resize(std::size_t(mesh.F.rows()));
  boxes.edge.resize(std::size_t(mesh.E.rows()));
  std::vector<int> place(std::size_t(nb), -1);  // in `bodies`
  for (std::size_t i = 0; i < bodies.size(); ++i) place[std::size_t(bodies[i])] = int(i);
  std::vector<char> spanned(std::size_t(nb), 0);
  const auto span_body = [&](int b) {
    if (spanned[std::size_t(b)]) return;
    const BodyModel& body = model.bodies[std::size_t(b)];
    for (int v = body.vertex_begin; v < body.vertex_end; ++v)
      boxes.vertex[std::size_t(v)] = {lo.row(v).transpose() - inflation, hi.row(v).transpose() + inflation};
    span(mesh.F, boxes.vertex, body.face_begin, body.face_end, boxes.face);
    span(mesh.E, boxes.vertex, body.edge_begin, body.edge_end, boxes.edge);
    spanned[std::size_t(b)] = 1;
  };
  std::vector<std::array<int, 2>> pairs;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const int a = bodies[i];
    if (model.bodies[std::size_t(a)].self_contact())
      throw std::invalid_argument("pairs_of_bodies: body " + model.bodies[std::size_t(a)].name +
                                  " has self-contact");
    for (int b = 0; b < nb; ++b) {
      // Two of `bodies` once, with the first of them.
      if (b == a || (place[std::size_t(b)] >= 0 && place[std::size_t(b)] < int(i))) continue;
      if (!body_box[std::size_t(a)].overlaps(body_box[std::size_t(b)])) continue;
      span_body(a);
      span_body(b);
      pairs.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  Candidates out;
  in_ordered_chunks<Candidates>(
      pairs.size(), 8,
      [&](std::size_t k, Candidates& part) {
        primitive_pairs(model, boxes, body_box, pairs[k][0], pairs[k][1], part);
      },
      [&](const Candidates& part) { out.append(part); });
  return out;
}

void keep_shrunk(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1, double inflation,
                 const Candidates& pairs, const std::vector<ShrunkCandidates>& shrunk) {
  if (shrunk.empty() || shrunk.size() > BroadPhase::kMostShrunk)
    throw std::invalid_argument("keep_shrunk: 1 to " + std::to_string(BroadPhase::kMostShrunk) +
                                " shrunk candidate sets, got " + std::to_string(shrunk.size()));
  const PrimitiveBoxes now = primitive_boxes(model.mesh, x0, x1, inflation);
  std::array<double, BroadPhase::kMostShrunk> shrink{};
  for (std::size_t l = 0; l < shrunk.size(); ++l) shrink[l] = shrunk[l].shrink;
  // By chunks of pairs in parallel, gathered in order (the grown boxes' pairs are not asked for).
  using Pairs = std::vector<std::array<int, 2>>;
  constexpr std::size_t kChunk = 4096;
  using Found = std::array<Pairs, BroadPhase::kMostShrunk>;
  const auto keep = [&](const Pairs& list, const std::vector<Box>& a, const std::vector<Box>& b,
                        Pairs Candidates::*set) {
    std::vector<Found> found((list.size() + kChunk - 1) / kChunk);
    tbb::parallel_for(std::size_t(0), found.size(), [&](std::size_t c) {
      const std::size_t begin = c * kChunk, end = std::min(list.size(), begin + kChunk);
      Found& f = found[c];
      for (std::size_t l = 0; l < shrunk.size(); ++l) f[l].reserve(end - begin);
      keep_overlapping(list.data() + begin, end - begin, a, b, nullptr, {&f[0], &f[1]}, shrink,
                       shrunk.size());
    });
    for (std::size_t l = 0; l < shrunk.size(); ++l) {
      Pairs& out = shrunk[l].out->*set;
      out.clear();
      for (const Found& f : found) out.insert(out.end(), f[l].begin(), f[l].end());
    }
  };
  keep(pairs.vertex_face, now.vertex, now.face, &Candidates::vertex_face);
  keep(pairs.edge_edge, now.edge, now.edge, &Candidates::edge_edge);
}

Candidates BroadPhase::find(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1,
                            double inflation, const std::vector<ShrunkCandidates>& shrunk,
                            std::vector<AxisBox>* bodies) {
  if (shrunk.size() > kMostShrunk)
    throw std::invalid_argument("BroadPhase::find: at most " + std::to_string(kMostShrunk) + " shrunk candidate sets, got " +
                                std::to_string(shrunk.size()));
  const CollisionMesh& mesh = model.mesh;
  const PrimitiveBoxes now = primitive_boxes(mesh, x0, x1, inflation);
  const int nb = int(model.bodies.size());
  if (m_vertex.size() != now.vertex.size() || m_version.size() != std::size_t(nb)) {  // a new model: forget
    m_vertex.assign(now.vertex.size(), Box{Eigen::Array3d::Constant(1), Eigen::Array3d::Constant(-1)});
    m_face.resize(now.face.size());
    m_edge.resize(now.edge.size());
    m_body.assign(nb, Box{Eigen::Array3d::Constant(1e300), Eigen::Array3d::Constant(-1e300)});
    m_version.assign(nb, 0);
    m_pairs.clear();
  }
  // A body whose vertices left their reference boxes gets new ones: its current boxes grown by the margin.
  tbb::parallel_for(0, nb, [&](int b) {
    const BodyModel& body = model.bodies[b];
    bool kept = true;
    for (int v = body.vertex_begin; v < body.vertex_end && kept; ++v) kept = m_vertex[v].contains(now.vertex[v]);
    if (kept) return;
    for (int v = body.vertex_begin; v < body.vertex_end; ++v)
      m_vertex[v] = {now.vertex[v].lo - m_margin, now.vertex[v].hi + m_margin};
    span(mesh.F, m_vertex, body.face_begin, body.face_end, m_face);
    span(mesh.E, m_vertex, body.edge_begin, body.edge_end, m_edge);
    Box box{Eigen::Array3d::Constant(1e300), Eigen::Array3d::Constant(-1e300)};
    for (int v = body.vertex_begin; v < body.vertex_end; ++v) extend(box, m_vertex[v]);
    m_body[b] = box;
    ++m_version[b];
  });
  PrimitiveBoxes reference{std::move(m_vertex), std::move(m_face), std::move(m_edge)};
  std::vector<Box> body_box = body_boxes(model, now.vertex);
  const std::vector<std::array<int, 2>> pairs = body_pairs(model, body_box);
  if (bodies) *bodies = std::move(body_box);
  // Each body pair's primitive pairs from memory when both bodies kept their reference boxes,
  // else found again at them; then those whose current boxes overlap, in body-pair order.
  std::vector<PairCandidates> next(pairs.size());
  const auto remembered = [&](int a, int b) -> PairCandidates* {
    const auto it = std::lower_bound(m_pairs.begin(), m_pairs.end(), std::make_pair(a, b),
                                     [](const PairCandidates& p, const std::pair<int, int>& k) { return std::make_pair(p.a, p.b) < k; });
    if (it == m_pairs.end() || it->a != a || it->b != b) return nullptr;
    return it->version_a == m_version[a] && it->version_b == m_version[b] ? &*it : nullptr;
  };
  std::vector<char> refreshed(pairs.size(), 0);
  /// A chunk's pairs: those of the grown boxes, and those of each shrunk set.
  struct Found {
    Candidates grown;
    std::array<Candidates, kMostShrunk> shrunk;
  };
  std::array<double, kMostShrunk> shrink{};
  for (std::size_t l = 0; l < shrunk.size(); ++l) {
    shrink[l] = shrunk[l].shrink;
    *shrunk[l].out = {};
  }
  Candidates all;
  in_ordered_chunks<Found>(
      pairs.size(), 8,
      [&](std::size_t k, Found& out) {
        const auto [a, b] = pairs[k];
        PairCandidates& p = next[k];
        if (PairCandidates* old = remembered(a, b)) {
          p = std::move(*old);  // each remembered pair is taken by one body pair at most
        } else {
          p = {a, b, m_version[a], m_version[b], {}};
          primitive_pairs(model, reference, m_body, a, b, p.pairs);
          refreshed[k] = 1;
        }
        const Candidates& c = p.pairs;
        keep_overlapping(c.vertex_face.data(), c.vertex_face.size(), now.vertex, now.face, &out.grown.vertex_face,
                         {&out.shrunk[0].vertex_face, &out.shrunk[1].vertex_face}, shrink, shrunk.size());
        keep_overlapping(c.edge_edge.data(), c.edge_edge.size(), now.edge, now.edge, &out.grown.edge_edge,
                         {&out.shrunk[0].edge_edge, &out.shrunk[1].edge_edge}, shrink, shrunk.size());
      },
      [&](const Found& part) {
        all.append(part.grown);
        for (std::size_t l = 0; l < shrunk.size(); ++l) shrunk[l].out->append(part.shrunk[l]);
      });
  m_vertex = std::move(reference.vertex);
  m_face = std::move(reference.face);
  m_edge = std::move(reference.edge);
  std::sort(next.begin(), next.end(),
            [](const PairCandidates& p, const PairCandidates& q) { return std::make_pair(p.a, p.b) < std::make_pair(q.a, q.b); });
  m_pairs = std::move(next);
  m_refreshed = std::size_t(std::count(refreshed.begin(), refreshed.end(), 1));
  return all;
}

}  // namespace stiffsoft
