#include <stiffsoft/coupling/contact/broad_phase.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include <stiffsoft/coupling/contact/ordered_chunks.hpp>

namespace stiffsoft {

namespace {

struct Box {
  Eigen::Array3d lo, hi;
  bool overlaps(const Box& o) const { return (lo <= o.hi).all() && (o.lo <= hi).all(); }
  Box intersection(const Box& o) const { return {lo.max(o.lo), hi.min(o.hi)}; }
  void extend(const Box& o) {
    lo = lo.min(o.lo);
    hi = hi.max(o.hi);
  }
};

struct Keyed {
  double lo, hi;  // extent along the sweep axis
  int id;
};

/// Boxes of vertices, faces and edges for one broad-phase call.
struct PrimitiveBoxes {
  std::vector<Box> vertex, face, edge;
};

PrimitiveBoxes primitive_boxes(const CollisionMesh& mesh, const Eigen::MatrixX3d& x0,
                               const Eigen::MatrixX3d& x1, double inflation) {
  PrimitiveBoxes boxes;
  boxes.vertex.resize(x0.rows());
  tbb::parallel_for(Eigen::Index(0), x0.rows(), [&](Eigen::Index v) {
    const Eigen::Array3d a = x0.row(v).transpose().array(), b = x1.row(v).transpose().array();
    boxes.vertex[v] = {a.min(b) - inflation, a.max(b) + inflation};
  });
  // The box of primitive k (a row of F or E) spans its vertices' boxes.
  const auto spanned = [&](const auto& primitives, Eigen::Index k, std::vector<Box>& out) {
    Box box = boxes.vertex[primitives(k, 0)];
    for (Eigen::Index i = 1; i < primitives.cols(); ++i) box.extend(boxes.vertex[primitives(k, i)]);
    out[k] = box;
  };
  boxes.face.resize(mesh.F.rows());
  tbb::parallel_for(Eigen::Index(0), mesh.F.rows(), [&](Eigen::Index f) { spanned(mesh.F, f, boxes.face); });
  boxes.edge.resize(mesh.E.rows());
  tbb::parallel_for(Eigen::Index(0), mesh.E.rows(), [&](Eigen::Index e) { spanned(mesh.E, e, boxes.edge); });
  return boxes;
}

/// The primitives in [begin, end) whose box meets `region`, keyed along `axis`, in id order.
std::vector<Keyed> inside(const std::vector<Box>& boxes, int begin, int end, const Box& region,
                          int axis) {
  std::vector<Keyed> out;
  for (int i = begin; i < end; ++i)
    if (boxes[i].overlaps(region)) out.push_back({boxes[i].lo[axis], boxes[i].hi[axis], i});
  return out;
}

/// The list sorted by the low end of its key, as sweep() needs it.
std::vector<Keyed> sorted(std::vector<Keyed> list) {
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

/// True when the body carries DOFs (an affine body that is not fixed, or a soft body).
bool moves(const BodyModel& body) {
  return body.dof >= 0 || body.representation == Representation::Soft;
}

}  // namespace

Candidates broad_phase(const Model& model, const Eigen::MatrixX3d& x0, const Eigen::MatrixX3d& x1,
                       double inflation) {
  const CollisionMesh& mesh = model.mesh;
  const PrimitiveBoxes boxes = primitive_boxes(mesh, x0, x1, inflation);

  // Body boxes, then body pairs by sort-and-sweep along x.
  const int nb = int(model.bodies.size());
  std::vector<Box> body_box(nb);
  for (int b = 0; b < nb; ++b) {
    const BodyModel& body = model.bodies[b];
    Box box{Eigen::Array3d::Constant(1e300), Eigen::Array3d::Constant(-1e300)};
    for (int v = body.vertex_begin; v < body.vertex_end; ++v) box.extend(boxes.vertex[v]);
    body_box[b] = box;
  }
  std::vector<int> order(nb);
  for (int b = 0; b < nb; ++b) order[b] = b;
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return body_box[a].lo[0] < body_box[b].lo[0]; });
  std::vector<std::array<int, 2>> body_pairs;
  for (int i = 0; i < nb; ++i) {
    const int a = order[i];
    for (int j = i + 1; j < nb && body_box[order[j]].lo[0] <= body_box[a].hi[0]; ++j) {
      const int b = order[j];
      if (!moves(model.bodies[a]) && !moves(model.bodies[b])) continue;
      if (body_box[a].overlaps(body_box[b])) body_pairs.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  for (int b = 0; b < nb; ++b)
    if (model.bodies[b].self_contact()) body_pairs.push_back({b, b});

  // Primitive pairs of a few body pairs per task, gathered in body-pair order.
  const auto fill = [&](std::size_t k, Candidates& out) {
    const auto [a, b] = body_pairs[k];
    const BodyModel& A = model.bodies[a];
    const BodyModel& B = model.bodies[b];
    const Box region = body_box[a].intersection(body_box[b]);
    int axis;
    (region.hi - region.lo).maxCoeff(&axis);
    const auto va = inside(boxes.vertex, A.vertex_begin, A.vertex_end, region, axis);
    const auto fa = inside(boxes.face, A.face_begin, A.face_end, region, axis);
    const auto ea = inside(boxes.edge, A.edge_begin, A.edge_end, region, axis);
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
    const auto vb = sorted(inside(boxes.vertex, B.vertex_begin, B.vertex_end, region, axis));
    const auto fb = sorted(inside(boxes.face, B.face_begin, B.face_end, region, axis));
    const auto eb = sorted(inside(boxes.edge, B.edge_begin, B.edge_end, region, axis));
    sweep(sorted(va), boxes.vertex, fb, boxes.face, [&](int v, int f) { out.vertex_face.push_back({v, f}); });
    sweep(vb, boxes.vertex, sorted(fa), boxes.face, [&](int v, int f) { out.vertex_face.push_back({v, f}); });
    sweep(sorted(ea), boxes.edge, eb, boxes.edge,
          [&](int e, int g) { out.edge_edge.push_back({std::min(e, g), std::max(e, g)}); });
  };
  Candidates all;
  in_ordered_chunks<Candidates>(body_pairs.size(), 8, fill, [&](const Candidates& part) { all.append(part); });
  return all;
}

}  // namespace stiffsoft
