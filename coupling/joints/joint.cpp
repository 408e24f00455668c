#include "coupling/joints/joint.hpp"

namespace stiffsoft {

const char* joint_kind_name(JointKind kind) {
  switch (kind) {
    case JointKind::Ball: return "ball";
    case JointKind::Hinge: return "hinge";
    case JointKind::Prismatic: return "prismatic";
    case JointKind::Distance: return "distance";
    case JointKind::BoundedDistance: return "bounded_distance";
    case JointKind::ConeTwist: return "cone_twist";
  }
  return "ball";
}

}  // namespace stiffsoft
