#include <stiffsoft/coupling/joints/linear_constraints.hpp>

#include <Eigen/LU>

namespace stiffsoft {

std::vector<std::pair<JointVector, JointVector>> linear_equalities(const Model& model, const JointModel& joint) {
  std::vector<std::pair<JointVector, JointVector>> pairs;
  const auto point_pair = [&](double along) {
    pairs.emplace_back(end_point(model, joint.a, joint.a.anchor + along * joint.a.axis),
                       end_point(model, joint.b, joint.b.anchor + along * joint.b.axis));
  };
  switch (joint.kind) {
    case JointKind::Ball:
    case JointKind::ConeTwist:
      point_pair(0);
      for (const NodePin& pin : joint.pins) {
        JointEnd node;
        node.node = pin.node;
        pairs.emplace_back(end_point(model, joint.a, pin.anchor), end_point(model, node, Eigen::Vector3d::Zero()));
      }
      break;
    case JointKind::Hinge:
      point_pair(-0.5 * joint.axis_length);
      point_pair(0.5 * joint.axis_length);
      break;
    case JointKind::Prismatic: {
      // A_a A_a0⁻¹ e_i = A_b A_b0⁻¹ e_i: the relative orientation of the initial pose is kept.
      const auto frame_inverse = [&](const JointEnd& end) -> Eigen::Matrix3d {
        if (end.body < 0) return Eigen::Matrix3d::Identity();
        return abd::affine_matrix(model.bodies[end.body].q0).inverse();
      };
      const Eigen::Matrix3d Ra = frame_inverse(joint.a), Rb = frame_inverse(joint.b);
      for (int i = 0; i < 3; ++i)
        pairs.emplace_back(end_direction(model, joint.a, Ra.col(i)), end_direction(model, joint.b, Rb.col(i)));
      break;
    }
    case JointKind::Distance:
    case JointKind::BoundedDistance:
      break;
  }
  return pairs;
}

LinearConstraints linear_joint_constraints(const Model& model) {
  LinearConstraints out;
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<double> d;
  for (int j = 0; j < int(model.joints.size()); ++j) {
    const bool points = model.joints[j].kind != JointKind::Prismatic;
    for (const auto& [u, v] : linear_equalities(model, model.joints[j])) {
      const int row = int(d.size());
      for (int i = 0; i < 3; ++i) {
        if (u.block >= 0)
          for (int c = 0; c < u.size; ++c)
            if (u.J(i, c) != 0) triplets.emplace_back(row + i, u.dof + c, u.J(i, c));
        if (v.block >= 0)
          for (int c = 0; c < v.size; ++c)
            if (v.J(i, c) != 0) triplets.emplace_back(row + i, v.dof + c, -v.J(i, c));
        // u − v = 0 with u = J_u q + c_u, v = J_v q + c_v: (J_u − J_v) q = c_v − c_u.
        d.push_back(v.constant[i] - u.constant[i]);
        out.row_joint.push_back(j);
        out.row_is_point.push_back(points);
      }
    }
  }
  out.C.resize(int(d.size()), model.num_dofs);
  out.C.setFromTriplets(triplets.begin(), triplets.end());
  out.d = Eigen::Map<const Eigen::VectorXd>(d.data(), Eigen::Index(d.size()));
  return out;
}

std::vector<double> joint_violations(const LinearConstraints& constraints, const Eigen::VectorXd& q, int joints) {
  std::vector<double> worst(joints, 0.0);
  if (constraints.rows() == 0) return worst;
  const Eigen::VectorXd r = constraints.C * q - constraints.d;
  for (int i = 0; i < r.size(); ++i)
    worst[constraints.row_joint[i]] = std::max(worst[constraints.row_joint[i]], std::abs(r[i]));
  return worst;
}

}  // namespace stiffsoft
