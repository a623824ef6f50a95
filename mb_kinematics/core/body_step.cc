#include "mb_kinematics/core/body_step.h"

#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/core/model.h"

namespace mbk {
namespace {

JointKernel revolute_kernel(const Joint& joint, bool rotated) {
  if (!rotated) {
    if (joint.axis == Vec3<double>::UnitX()) return JointKernel::kRevoluteX;
    if (joint.axis == Vec3<double>::UnitY()) return JointKernel::kRevoluteY;
    if (joint.axis == Vec3<double>::UnitZ()) return JointKernel::kRevoluteZ;
  }
  return JointKernel::kRevolute;
}

// The kernel of a joint: the types that have their own (opt-in specializations, each tested
// against joint_motion in generic_kernel_test); every other type runs joint_motion (kGeneric),
// so a new joint type needs nothing here.
JointKernel kernel_of(const Joint& joint) {
  const bool rotated = joint.rotation != Mat3<double>::Identity();
  const JointType type = joint.type;  // not a switch: -Wswitch-enum would flag a new type here
  if (type == JointType::kFixed) return rotated ? JointKernel::kFixedRotated : JointKernel::kFixed;
  if (type == JointType::kRevolute) return revolute_kernel(joint, rotated);
  if (type == JointType::kPrismatic)
    return rotated ? JointKernel::kPrismaticRotated : JointKernel::kPrismatic;
  const bool xyz = joint.euler_order == EulerOrder::kXYZ;
  if (type == JointType::kBall123) return xyz ? JointKernel::kBall123 : JointKernel::kBallOrdered;
  if (type == JointType::kBallEuler) return JointKernel::kBallEuler;
  if (type == JointType::kFree123) return xyz ? JointKernel::kFree123 : JointKernel::kFreeOrdered;
  if (type == JointType::kFreeEuler) return JointKernel::kFreeEuler;
  if (type == JointType::kPlanar) return JointKernel::kPlanar;
  return JointKernel::kGeneric;  // no kernel of its own: joint_motion
}

VectorShape shape_of(const Vec3<double>& v) {
  const int nonzero = (v.array() != 0.0).count();
  if (nonzero == 0) return VectorShape::kZero;
  if (nonzero > 1) return VectorShape::kDense;
  return v.x() != 0.0 ? VectorShape::kX : v.y() != 0.0 ? VectorShape::kY : VectorShape::kZ;
}

// C_k R(a, q) = C_k (a a^T + cos q (I - a a^T) + sin q [a]x) (Rodrigues), multiplied out.
void add_revolute_matrices(const Joint& joint, std::vector<Mat3<double>>& matrices) {
  const Mat3<double> aat = joint.axis * joint.axis.transpose();
  const Mat3<double>& c = joint.rotation;
  matrices.push_back(c * aat);
  matrices.push_back(c * (Mat3<double>::Identity() - aat));
  matrices.push_back(c * skew(joint.axis));
}

// A planar joint's P0 P1 P2 about its normal a, then [C u1, C u2, C a]: its plane's axes and
// normal in Bj (u1, u2 as joint_motion takes them).
void add_planar_matrices(const Joint& joint, std::vector<Mat3<double>>& matrices) {
  add_revolute_matrices(joint, matrices);
  Vec3<double> u1, u2;
  detail::plane_basis(joint.axis, u1, u2);
  Mat3<double> plane;  // each column as joint_motion carries it into Bj (bit for bit)
  plane << joint.rotation * u1, joint.rotation * u2, joint.rotation * joint.axis;
  matrices.push_back(plane);
}

// The angles a kernel turns by, as offsets from the joint's first coordinate.
std::vector<int> angle_offsets(JointKernel kernel) {
  switch (kernel) {
    case JointKernel::kRevoluteX:
    case JointKernel::kRevoluteY:
    case JointKernel::kRevoluteZ:
    case JointKernel::kRevolute:
      return {0};
    case JointKernel::kBall123:
    case JointKernel::kBallOrdered:
      return {0, 1, 2};
    case JointKernel::kFree123:
    case JointKernel::kFreeOrdered:
      return {3, 4, 5};
    case JointKernel::kPlanar:
      return {2};
    case JointKernel::kFixed:
    case JointKernel::kFixedRotated:
    case JointKernel::kPrismatic:
    case JointKernel::kPrismaticRotated:
    case JointKernel::kBallEuler:
    case JointKernel::kFreeEuler:
    case JointKernel::kGeneric:
      break;
  }
  return {};
}

PaddedMat3 padded(const Mat3<double>& m) {
  PaddedMat3 out;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) out.col[c][r] = m(r, c);
    out.col[c][3] = 0.0;
  }
  return out;
}

}  // namespace

BodySteps make_body_steps(const Model& model, KernelChoice choice) {
  BodySteps out;
  out.steps.resize(model.bodies.size());
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    BodyStep& step = out.steps[k];
    step.kernel = choice == KernelChoice::kFast ? kernel_of(body.joint) : JointKernel::kGeneric;
    out.generic = out.generic || step.kernel == JointKernel::kGeneric;
    step.reorthonormalize = body.depth % detail::kReorthonormalizeEvery == 0;
    step.lower = body.lower;
    step.q_index = body.q_index;
    step.v_index = body.v_index;
    step.offset = body.joint.offset;
    step.mass_center = body.mass_center;
    step.offset_shape = shape_of(step.offset);
    step.mass_center_shape = shape_of(step.mass_center);
    step.axis = body.joint.rotation * body.joint.axis;
    for (int offset : angle_offsets(step.kernel)) {
      if (step.angle < 0) step.angle = static_cast<int>(out.angles.size());
      out.angles.push_back(body.q_index + offset);
    }
    step.euler_order = body.joint.euler_order;
    if (is_ball_or_free(step.kernel)) {
      if (body.joint.rotation != Mat3<double>::Identity()) {  // else M = S0J by the kernel
        step.matrices = static_cast<int>(out.matrices.size());
        out.matrices.push_back(body.joint.rotation);
      }
    } else if (step.kernel == JointKernel::kFixedRotated ||
               step.kernel == JointKernel::kPrismaticRotated) {
      step.matrices = static_cast<int>(out.matrices.size());
      out.matrices.push_back(body.joint.rotation);
    } else if (step.kernel == JointKernel::kRevolute) {
      step.matrices = static_cast<int>(out.matrices.size());
      add_revolute_matrices(body.joint, out.matrices);
    } else if (step.kernel == JointKernel::kPlanar) {
      step.matrices = static_cast<int>(out.matrices.size());
      add_planar_matrices(body.joint, out.matrices);
    }
  }
  for (const Mat3<double>& m : out.matrices) out.padded.push_back(padded(m));
  return out;
}

}  // namespace mbk
