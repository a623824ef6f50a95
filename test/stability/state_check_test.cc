// mbk::check_state: what it accepts and rejects, and that each message names the place.
#include "mb_kinematics/core/state_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mb_kinematics/analysis/model_generators.h"

namespace {

mbk::Model euler_chain() {
  mbk::Model model = mbk::make_chain(3, mbk::JointType::kRevolute);
  model.bodies[2].joint.type = mbk::JointType::kFreeEuler;
  model.bodies[3].joint.type = mbk::JointType::kPrismatic;
  mbk::finalize_model(model);
  return model;
}

TEST(StateCheck, AcceptsOrdinaryAndExtremeButComputableStates) {
  const mbk::Model model = euler_chain();
  mbk::JointState<double> s(model);
  EXPECT_EQ(mbk::check_state(model, s), "");
  s.position[0] = std::numeric_limits<double>::max();  // an angle: sin/cos are bounded
  s.position[model.nq - 1] = 1e50;                     // travel at the limit
  s.velocity.setConstant(std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(mbk::check_state(model, s), "");
  for (int i = 4; i < 8; ++i) s.position[i] = 0.5e-6;  // |e|^2 = 1e-12: the threshold itself
  EXPECT_EQ(mbk::check_state(model, s), "");
}

TEST(StateCheck, RejectsWithTheCoordinateNamed) {
  const mbk::Model model = euler_chain();
  struct Case {
    int part, index;
    double value;
    std::string fragment;
  };
  const Case cases[] = {
      {0, 0, NAN, "coordinate 'joint1': not finite (nan)"},
      {1, 2, INFINITY, "speed 'joint2/y': not finite (inf)"},
      {2, 8, -INFINITY, "acceleration of 'joint3'"},
      {0, 8, 2e50, "coordinate 'joint3': magnitude 2.0000000000000002e+50 above the limit 1e50"},
      {0, 7, 0.0, "coordinates 'joint2/e1..e4': Euler parameters of |e|^2 = 0, below 1e-12"},
  };
  for (const Case& c : cases) {
    mbk::JointState<double> s(model);
    (c.part == 0 ? s.position : c.part == 1 ? s.velocity : s.acceleration)[c.index] = c.value;
    const std::string message = mbk::check_state(model, s);
    EXPECT_NE(message.find(c.fragment), std::string::npos) << message;
  }
  mbk::JointState<double> tiny(model);
  for (int i = 4; i < 8; ++i) tiny.position[i] = 0.49e-6;  // |e|^2 = 0.96e-12
  EXPECT_NE(mbk::check_state(model, tiny).find("below 1e-12"), std::string::npos);
}

}  // namespace
