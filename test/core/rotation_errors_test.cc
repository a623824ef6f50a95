// core/rotation_errors.h: a joint's angle errors (dq, dq', dq''), carried by angle_error_map to the
// joint's (dtheta, dw, dw') and by add_joint_rotation_variance to the bodies, against the change
// of forward_kinematics itself when the joint's angles and rates move by that much (first order).
#include "mb_kinematics/core/rotation_errors.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"

namespace {

// R - 1 (free, XYZ) - 2 (ball, ZXY, near its lock) - 3 (ball, XZX); 2 - 4 (ball, YXZ, turned
// joint frame) - 5 (revolute).
mbk::Model tree() {
  mbk::Model model;
  model.bodies.resize(6);
  const int lower[] = {0, 0, 1, 2, 2, 4};
  const mbk::JointType types[] = {mbk::JointType::kFixed,   mbk::JointType::kFree123,
                                  mbk::JointType::kBall123, mbk::JointType::kBall123,
                                  mbk::JointType::kBall123, mbk::JointType::kRevolute};
  const mbk::EulerOrder orders[] = {mbk::EulerOrder::kXYZ, mbk::EulerOrder::kXYZ,
                                    mbk::EulerOrder::kZXY, mbk::EulerOrder::kXZX,
                                    mbk::EulerOrder::kYXZ, mbk::EulerOrder::kXYZ};
  for (int k = 1; k <= 5; ++k) {
    mbk::Body& b = model.bodies[k];
    b.name = "B" + std::to_string(k);
    b.lower = lower[k];
    b.joint.name = "J" + std::to_string(k);
    b.joint.type = types[k];
    b.joint.euler_order = orders[k];
    b.joint.axis = mbk::Vec3<double>(0.6, 0.0, 0.8);
    b.joint.offset = mbk::Vec3<double>(0.1 * k, 0.3, -0.05 * k);
    b.mass_center = mbk::Vec3<double>(0.05, 0.2, 0.1 * k);
    b.mass = 1.0;
  }
  model.bodies[4].joint.rotation =
      Eigen::AngleAxisd(0.7, mbk::Vec3<double>(1, 2, 3).normalized()).toRotationMatrix();
  mbk::finalize_model(model);
  return model;
}

TEST(RotationErrorsTest, BodiesMoveAsTheJointsAnglesPredict) {
  const mbk::Model model = tree();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  mbk::JointState<double> state(model);
  for (int c = 0; c < model.nq; ++c)
    state.position[c] = u(rng), state.velocity[c] = 2 * u(rng), state.acceleration[c] = 3 * u(rng);
  const int beta2 = model.bodies[2].q_index + 1;
  state.position[beta2] = 1.52;  // 87 degrees: ZXY near its lock
  mbk::Data<double> data(model), moved(model);
  mbk::forward_kinematics(model, state, data, mbk::Level::kAcceleration);
  std::vector<char> scratch;
  constexpr double kStep = 1e-7;
  for (int b = 1; b <= 4; ++b) {
    const mbk::Body& body = model.bodies[b];
    const int c = body.q_index + mbk::translation_count(body.joint.type);
    Eigen::Matrix<double, 9, 1> d;
    for (int i = 0; i < 9; ++i) d[i] = kStep * u(rng);
    mbk::JointState<double> s = state;
    for (int a = 0; a < 3; ++a) {
      s.position[c + a] += d[a];
      s.velocity[c + a] += d[3 + a];
      s.acceleration[c + a] += d[6 + a];
    }
    mbk::forward_kinematics(model, s, moved, mbk::Level::kAcceleration);
    const mbk::Mat9 l =
        mbk::angle_error_map(body.joint, state.position.data() + c, state.velocity.data() + c,
                             state.acceleration.data() + c);
    const mbk::Mat9 cov = l * d * d.transpose() * l.transpose();  // the errors exactly d
    std::vector<mbk::Vec3<double>> alpha_var(6, mbk::Vec3<double>::Zero()), a_var = alpha_var;
    mbk::add_joint_rotation_variance(model, data, b, cov, alpha_var, a_var, scratch);
    for (int k = 1; k <= 5; ++k) {
      const mbk::Vec3<double> dalpha = moved.alpha[k] - data.alpha[k];
      const mbk::Vec3<double> da =
          moved.mass_center_acceleration[k] - data.mass_center_acceleration[k];
      bool outward = false;  // is k outward of b (or b)?
      for (int j = k; j != 0 && !outward; j = model.bodies[j].lower) outward = j == b;
      if (outward)  // the joint moves it, measurably
        EXPECT_GT(dalpha.norm(), 1e-8) << "joint " << b << ", body " << k;
      else
        EXPECT_EQ(alpha_var[k].norm() + a_var[k].norm(), 0.0) << "joint " << b << ", body " << k;
      for (int i = 0; i < 3; ++i) {
        // first order: the change's size, to its second-order part (kStep^2 x rates) and the
        // central differences' rounding
        EXPECT_NEAR(std::sqrt(alpha_var[k][i]), std::abs(dalpha[i]), 1e-11)
            << "joint " << b << ", body " << k << ", component " << i;
        EXPECT_NEAR(std::sqrt(a_var[k][i]), std::abs(da[i]), 1e-11)
            << "joint " << b << ", body " << k << ", component " << i;
      }
    }
  }
}

}  // namespace
