#pragma once
/// @file The one list of every scene struct's JSON keys (private to stiffsoft/scene). Reading a
/// scene file (scene_loader.cpp: JSON → SceneDescription) and writing `scene.resolved.json`
/// (resolved_scene_json()) both walk these lists, so a key is mapped once.
///
/// `fields(v, s)` calls `v(key, member)` for each key of struct `s`, or `v(key, member, when)`
/// for a key the schema allows only in some cases (its `when` conditions: a primitive's
/// dimensions, a soft body's material, a joint kind's limits): the writer writes such a key
/// only when `when` holds; the reader reads every key the filled JSON has.

#include <array>
#include <concepts>
#include <string>
#include <type_traits>

#include <stiffsoft/scene/scene.hpp>

namespace stiffsoft::scene_fields {

/// S, const or not.
template <class T, class S>
concept Either = std::same_as<std::remove_const_t<T>, S>;

/// The scene-file names of an enum's values, indexed by the value.
template <class E>
struct EnumNames;

template <>
struct EnumNames<Integrator> {
  static constexpr std::array<const char*, 2> names{"backward_euler", "bdf2"};
};
template <>
struct EnumNames<contact::BarrierHessian> {
  static constexpr std::array<const char*, 2> names{"projected", "gauss_newton"};
};
template <>
struct EnumNames<Motion> {
  static constexpr std::array<const char*, 3> names{"dynamic", "fixed", "kinematic"};
};
template <>
struct EnumNames<ModelChoice> {
  static constexpr std::array<const char*, 3> names{"affine", "soft", "auto"};
};
template <>
struct EnumNames<PrimitiveShape::Type> {
  static constexpr std::array<const char*, 5> names{"box", "sphere", "cylinder", "torus", "plane"};
};
template <>
struct EnumNames<JointKind> {
  static constexpr std::array<const char*, 6> names = kJointKindNames;
};
template <>
struct EnumNames<DirichletDescription::Select> {
  static constexpr std::array<const char*, 3> names{"box", "half_space", "node_set"};
};

/// An enum value's scene-file name.
template <class E>
const char* enum_name(E value) {
  return EnumNames<E>::names.at(std::size_t(value));
}

/// Whether the schema allows `key` of `bodies[*].mesh` for this primitive (its `when`).
bool primitive_uses(const std::string& key, PrimitiveShape::Type type);

void fields(const auto& v, Either<TimeDescription> auto& t) {
  v("dt", t.dt);
  v("duration", t.duration);
  v("integrator", t.integrator);
}

void fields(const auto& v, Either<ContactPairDescription> auto& p) {
  v("body_a", p.body_a);
  v("body_b", p.body_b);
  v("damping", p.damping);
}

void fields(const auto& v, Either<ContactDescription> auto& c) {
  v("dhat", c.dhat);
  v("mu", c.mu);
  v("eps_v", c.eps_v);
  v("kappa", c.kappa);
  v("balance_kappa", c.balance_kappa);
  v("friction_iterations", c.friction_iterations);
  v("damping", c.damping);
  v("check_start_gaps", c.check_start_gaps);
  v("pairs", c.pairs);
}

void fields(const auto& v, Either<SolverDescription> auto& s) {
  v("tolerance", s.tolerance);
  v("gap_tolerance", s.gap_tolerance);
  v("max_iterations", s.max_iterations);
  v("barrier_hessian", s.barrier_hessian);
  v("release_hessian", s.release_hessian);
  v("geodesic_line_search", s.geodesic_line_search);
  v("island_line_search", s.island_line_search);
  v("entering_springs", s.entering_springs);
  v("linear", s.linear);
  v("krylov_rtol_max", s.krylov_rtol_max);
  v("rigidity_bound", s.rigidity_bound);
  v("sleep_time", s.sleep_time);
  v("sleep_speed", s.sleep_speed);
}

void fields(const auto& v, Either<OutputDescription> auto& o) { v("frame_dt", o.frame_dt); }

void fields(const auto& v, Either<PrimitiveShape> auto& shape) {
  v("primitive", shape.type);
  v("size", shape.extents, primitive_uses("size", shape.type));
  v("radius", shape.radius, primitive_uses("radius", shape.type));
  v("minor_radius", shape.minor_radius, primitive_uses("minor_radius", shape.type));
  v("height", shape.height, primitive_uses("height", shape.type));
  v("resolution", shape.resolution, primitive_uses("resolution", shape.type));
}

void fields(const auto& v, Either<SoftMaterial> auto& m) {
  v("model", m.model);
  v("young", m.young);
  v("poisson", m.poisson);
}

void fields(const auto& v, Either<DirichletDescription> auto& d) {
  using Select = DirichletDescription::Select;
  v("select", d.select);
  v("min", d.min, d.select == Select::Box);
  v("max", d.max, d.select == Select::Box);
  v("point", d.point, d.select == Select::HalfSpace);
  v("normal", d.normal, d.select == Select::HalfSpace);
  v("node_set", d.node_set, d.select == Select::NodeSet);
  v("velocity", d.velocity);
}

void fields(const auto& v, Either<PathSegment> auto& leg) {
  v("duration", leg.duration);
  v("velocity", leg.velocity);
  v("angular_velocity", leg.angular_velocity);
}

void fields(const auto& v, Either<BodyDescription> auto& b) {
  const bool deformable = b.model != ModelChoice::Affine;
  v("name", b.name);
  v("kind", b.kind);
  v("model", b.model);
  v("mesh", b.mesh);
  v("density", b.density);
  v("material", b.material, deformable);
  v("mesh_size", b.mesh_size, deformable);
  v("dirichlet", b.dirichlet, deformable);
  v("kappa", b.kappa);
  v("position", b.position);
  v("rotation_deg", b.rotation_deg);
  v("scale", b.scale);
  v("velocity", b.velocity);
  v("angular_velocity", b.angular_velocity);
  v("path", b.path, b.kind == Motion::Kinematic);
}

void fields(const auto& v, Either<JointDescription> auto& j) {
  const JointKind k = j.kind;
  const bool distance = k == JointKind::Distance || k == JointKind::BoundedDistance;
  const bool limited =
      k == JointKind::Hinge || k == JointKind::Prismatic || k == JointKind::BoundedDistance || k == JointKind::ConeTwist;
  const bool cone = k == JointKind::ConeTwist;
  v("name", j.name);
  v("kind", j.kind);
  v("body_a", j.body_a);
  v("body_b", j.body_b);
  v("anchor", j.anchor);
  v("anchor_b", j.anchor_b, distance);
  v("axis", j.axis, k == JointKind::Hinge || k == JointKind::Prismatic || cone);
  v("stiffness", j.stiffness, k == JointKind::Prismatic || k == JointKind::Distance);
  v("swing", j.swing, cone);
  v("twist_lower", j.twist_lower, cone);
  v("twist_upper", j.twist_upper, cone);
  v("lower", j.lower, limited && !cone);
  v("upper", j.upper, limited && !cone);
  v("limit_stiffness", j.limit_stiffness, limited);
  v("limit_activation", j.limit_activation, limited);
  v("damping", j.damping);
  v("nodes_within", j.nodes_within, k == JointKind::Ball);
}

void fields(const auto& v, Either<SceneDescription> auto& s) {
  v("description", s.description);
  v("time", s.time);
  v("gravity", s.gravity);
  v("contact", s.contact);
  v("solver", s.solver);
  v("output", s.output);
  v("bodies", s.bodies);
  v("joints", s.joints);
}

/// A visitor that does nothing: for the concept below.
struct NoVisitor {
  /// Ignores the key.
  template <class T>
  void operator()(const char*, T&, bool = true) const {}
};

/// A struct with a key list above.
template <class S>
concept Described = requires(NoVisitor v, S& s) { fields(v, s); };

}  // namespace stiffsoft::scene_fields
