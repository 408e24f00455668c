#include <stiffsoft/coupling/contact/broad_phase.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>

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

/// The primitives in [begin, end) whose box meets `region`, keyed along `axis`.
std::vector<Keyed> inside(const std::vector<Box>& boxes, int begin, int end, const Box& region,
                          int axis) {
  std::vector<Keyed> out;
  for (int i = begin; i < end; ++i)
    if (boxes[i].overlaps(region)) out.push_back({boxes[i].lo[axis], boxes[i].hi[axis], i});
  std::sort(out.begin(), out.end(), [](const Keyed& a, const Keyed& b) { return a.lo < b.lo; });
  return out;
}

/// Sort-and-sweep of two sorted lists: calls emit(a, b) for every pair whose full boxes overlap.
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
    const auto vb = inside(boxes.vertex, B.vertex_begin, B.vertex_end, region, axis);
    const auto fa = inside(boxes.face, A.face_begin, A.face_end, region, axis);
    const auto fb = inside(boxes.face, B.face_begin, B.face_end, region, axis);
    const auto ea = inside(boxes.edge, A.edge_begin, A.edge_end, region, axis);
    const auto eb = inside(boxes.edge, B.edge_begin, B.edge_end, region, axis);
    if (a == b) {
      // Self-contact of a soft body: every pair once, none that shares a vertex.
      sweep(va, boxes.vertex, fa, boxes.face, [&](int v, int f) {
        if ((mesh.F.row(f).array() != v).all()) out.vertex_face.push_back({v, f});
      });
      sweep(ea, boxes.edge, ea, boxes.edge, [&](int e, int g) {
        if (e < g && mesh.E(e, 0) != mesh.E(g, 0) && mesh.E(e, 0) != mesh.E(g, 1) &&
            mesh.E(e, 1) != mesh.E(g, 0) && mesh.E(e, 1) != mesh.E(g, 1))
          out.edge_edge.push_back({e, g});
      });
      return;
    }
    sweep(va, boxes.vertex, fb, boxes.face, [&](int v, int f) { out.vertex_face.push_back({v, f}); });
    sweep(vb, boxes.vertex, fa, boxes.face, [&](int v, int f) { out.vertex_face.push_back({v, f}); });
    sweep(ea, boxes.edge, eb, boxes.edge,
          [&](int e, int g) { out.edge_edge.push_back({std::min(e, g), std::max(e, g)}); });
  };
  Candidates all;
  in_ordered_chunks<Candidates>(body_pairs.size(), 8, fill, [&](const Candidates& part) { all.append(part); });
  return all;
}

}  // namespace stiffsoft
