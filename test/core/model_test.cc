// finalize_model (doc/method.md 8: validated once, errors name the body and the field),
// coordinate and speed names (doc/method.md 8), the initial state and mimics.
#include "mb_kinematics/core/model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "mb_kinematics/core/state.h"
#include "test/support/test_models.h"

namespace {

using V = mbk::Vec3<double>;
using M = mbk::Mat3<double>;
using mbk::JointType;
using Names = std::vector<std::string>;

mbk::Body body(const std::string& name, int lower, JointType type,
               const std::string& joint_name = "") {
  mbk::Body b;
  b.name = name;
  b.lower = lower;
  b.joint.name = joint_name;
  b.joint.type = type;
  b.mass = 1.0;
  return b;
}

// A valid three-body model (base on R, arm on base, hand on arm); `edit` breaks it.
mbk::Model three_bodies() {
  mbk::Model model;
  model.bodies = {mbk::Body(), body("base", 0, JointType::kFree123),
                  body("arm", 1, JointType::kRevolute), body("hand", 2, JointType::kBall123)};
  return model;
}

// Expects finalize_model to throw std::invalid_argument whose message contains every fragment.
void expect_error(mbk::Model model, const Names& fragments) {
  try {
    mbk::finalize_model(model);
    ADD_FAILURE() << "accepted an invalid model; expected: " << fragments.front();
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    for (const std::string& f : fragments)
      EXPECT_NE(what.find(f), std::string::npos) << "'" << f << "' not in: " << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "not one line: " << what;
  }
}

// A mimic's error names its coordinate and what is wrong.
TEST(FinalizeModel, MimicErrorsNameTheCoordinate) {
  mbk::Model self = three_bodies();
  self.bodies[2].joint.name = "elbow";
  self.mimics.push_back({6, 6, 1.0, 0.0});  // the arm's coordinate, after base's six
  expect_error(self, {"mimic 'elbow': it mimics itself"});
  mbk::Model infinite = three_bodies();
  infinite.bodies[2].joint.name = "elbow";
  infinite.mimics.push_back({6, 0, std::numeric_limits<double>::infinity(), 0.0});
  expect_error(infinite, {"mimic 'elbow': multiplier or offset not finite"});
}

TEST(FinalizeModel, AcceptsTheValidModel) {
  mbk::Model model = three_bodies();
  EXPECT_NO_THROW(mbk::finalize_model(model));
  EXPECT_EQ(model.body_count(), 3);
  EXPECT_EQ(model.bodies[0].name, "R");
  EXPECT_EQ(model.lower_body_array(), (std::vector<int>{0, 1, 2}));
}

TEST(FinalizeModel, BadLowerBodyNamesBodyAndL) {
  mbk::Model model = three_bodies();
  model.bodies[3].lower = 3;  // L(k) must be < k (doc/method.md 1)
  expect_error(model, {"body 3", "L(3) = 3"});
  model.bodies[3].lower = -1;
  expect_error(model, {"body 3", "L(3) = -1"});
}

TEST(FinalizeModel, DuplicateNames) {
  mbk::Model model = three_bodies();
  model.bodies[3].name = "arm";
  expect_error(model, {"body 3 'arm'", "name"});
  model = three_bodies();
  model.bodies[2].name = "R";  // the inertial frame's name
  expect_error(model, {"body 2 'R'", "name"});
  model = three_bodies();
  model.bodies[2].joint.name = "shoulder";
  model.bodies[3].joint.name = "shoulder";
  expect_error(model, {"body 3 'hand'", "joint name 'shoulder'"});
}

TEST(FinalizeModel, ZeroAxis) {
  for (JointType type : {JointType::kRevolute, JointType::kPrismatic, JointType::kPlanar}) {
    mbk::Model model = three_bodies();
    model.bodies[2].joint.type = type;
    model.bodies[2].joint.axis = V::Zero();
    expect_error(model, {"body 2 'arm'", "axis"});
  }
}

TEST(FinalizeModel, NonFiniteFields) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  mbk::Model model = three_bodies();
  model.bodies[2].joint.offset = V(0, nan, 0);
  expect_error(model, {"body 2 'arm'", "origin (q_k)", "not finite"});
  model = three_bodies();
  model.bodies[3].mass_center = V(inf, 0, 0);
  expect_error(model, {"body 3 'hand'", "mass_center"});
  model = three_bodies();
  model.bodies[2].joint.axis = V(0, 0, nan);
  expect_error(model, {"body 2 'arm'", "axis"});
  model = three_bodies();
  model.bodies[1].joint.rotation(1, 1) = nan;
  expect_error(model, {"body 1 'base'", "C_k"});
  model = three_bodies();
  model.bodies[1].mass = nan;
  expect_error(model, {"body 1 'base'", "mass"});
}

TEST(FinalizeModel, NonRotationOffsetOrientation) {
  mbk::Model model = three_bodies();
  model.bodies[2].joint.rotation = M::Identity() * 1.01;  // not orthogonal
  expect_error(model, {"body 2 'arm'", "C_k", "rotation"});
  model.bodies[2].joint.rotation = V(1, 1, -1).asDiagonal();  // orthogonal, a reflection
  expect_error(model, {"body 2 'arm'", "C_k", "rotation"});
  model.bodies[2].joint.rotation = Eigen::AngleAxisd(2.0, V(1, -2, 0.5).normalized()).matrix();
  EXPECT_NO_THROW(mbk::finalize_model(model));
}

TEST(FinalizeModel, NegativeMass) {
  mbk::Model model = three_bodies();
  model.bodies[3].mass = -0.5;
  expect_error(model, {"body 3 'hand'", "mass"});
  model.bodies[3].mass = 0.0;  // massless frames are allowed
  EXPECT_NO_THROW(mbk::finalize_model(model));
}

TEST(FinalizeModel, EmptyNameAndNoBodies) {
  mbk::Model model = three_bodies();
  model.bodies[2].name = "";
  expect_error(model, {"body 2", "name"});
  mbk::Model empty;
  EXPECT_THROW(mbk::finalize_model(empty), std::invalid_argument);
}

TEST(FinalizeModel, NormalizesAxes) {
  mbk::Model model = three_bodies();
  model.bodies[2].joint.axis = V(0, 0, 2.5);
  mbk::finalize_model(model);
  EXPECT_EQ(model.bodies[2].joint.axis, V(0, 0, 1));
}

// The shapes of q_k and r_k that forward_kinematics uses to skip zero terms (body_step.h).
TEST(FinalizeModel, ClassifiesOffsetsAndMassCenters) {
  using mbk::VectorShape;
  mbk::Model model = three_bodies();
  model.bodies[1].joint.offset = V(0, 0, 0);
  model.bodies[1].mass_center = V(0, -0.5, 0);
  model.bodies[2].joint.offset = V(0, 0, 2);
  model.bodies[2].mass_center = V(1e-300, 0, 0);
  model.bodies[3].joint.offset = V(1, 0, 1);
  model.bodies[3].mass_center = V(0, 0, 0);
  mbk::finalize_model(model);
  const auto& steps = model.steps.steps;
  EXPECT_EQ(steps[1].offset_shape, VectorShape::kZero);
  EXPECT_EQ(steps[1].mass_center_shape, VectorShape::kY);
  EXPECT_EQ(steps[2].offset_shape, VectorShape::kZ);
  EXPECT_EQ(steps[2].mass_center_shape, VectorShape::kX);
  EXPECT_EQ(steps[3].offset_shape, VectorShape::kDense);
  EXPECT_EQ(steps[3].mass_center_shape, VectorShape::kZero);
}

// ---- Coordinate and speed names (doc/method.md 8).

mbk::Model every_joint_type(mbk::SpeedKind speeds) {
  mbk::Model model;
  model.speeds = speeds;
  model.bodies = {mbk::Body(),
                  body("b1", 0, JointType::kFreeEuler, "float"),
                  body("b2", 1, JointType::kRevolute, "hinge"),
                  body("b3", 2, JointType::kFixed, "weld"),
                  body("b4", 3, JointType::kPrismatic, "slide"),
                  body("b5", 4, JointType::kBall123, "shoulder"),
                  body("b6", 1, JointType::kBallEuler, "hip"),
                  body("b7", 6, JointType::kFree123, "free"),
                  body("b8", 7, JointType::kPlanar, "plane"),
                  body("b9", 8, JointType::kRevolute)};  // joint named after the body
  mbk::finalize_model(model);
  return model;
}

const Names kCoordinates = {
    "float/x",     "float/y",    "float/z",   "float/e1",       "float/e2",      "float/e3",
    "float/e4",    "hinge",      "slide",     "shoulder/alpha", "shoulder/beta", "shoulder/gamma",
    "hip/e1",      "hip/e2",     "hip/e3",    "hip/e4",         "free/x",        "free/y",
    "free/z",      "free/alpha", "free/beta", "free/gamma",     "plane/x",       "plane/y",
    "plane/gamma", "b9_joint"};

TEST(CoordinateNames, CoordinateDerivativeSpeeds) {
  const mbk::Model model = every_joint_type(mbk::SpeedKind::kCoordinateDerivatives);
  EXPECT_EQ(model.coordinate_names, kCoordinates);
  EXPECT_EQ(model.speed_names, kCoordinates);
  EXPECT_EQ(model.nq, 26);
  EXPECT_EQ(model.nv, 26);
  // Index bookkeeping: each joint's coordinates start at q_index, its speeds at v_index.
  const int q_index[] = {0, 0, 7, 8, 8, 9, 12, 16, 22, 25};
  for (int k = 1; k <= 9; ++k) {
    EXPECT_EQ(model.bodies[k].q_index, q_index[k]) << "body " << k;
    EXPECT_EQ(model.bodies[k].v_index, q_index[k]) << "body " << k;
  }
  EXPECT_EQ(model.coordinate_index("shoulder/beta"), 10);
  EXPECT_EQ(model.speed_index("plane/gamma"), 24);
  EXPECT_EQ(model.coordinate_index("weld"), -1);
  EXPECT_EQ(model.body_index("b8"), 8);
  EXPECT_EQ(model.body_index("R"), -1);
}

// Euler joints with angular velocity speeds: translations keep their names, the rotation speeds
// are "<joint>/wx", "/wy", "/wz"; every other joint's speeds are its coordinates' derivatives.
TEST(CoordinateNames, AngularVelocitySpeeds) {
  const mbk::Model model = every_joint_type(mbk::SpeedKind::kAngularVelocity);
  EXPECT_EQ(model.coordinate_names, kCoordinates);
  const Names speeds = {
      "float/x",   "float/y",    "float/z",        "float/wx",      "float/wy",       "float/wz",
      "hinge",     "slide",      "shoulder/alpha", "shoulder/beta", "shoulder/gamma", "hip/wx",
      "hip/wy",    "hip/wz",     "free/x",         "free/y",        "free/z",         "free/alpha",
      "free/beta", "free/gamma", "plane/x",        "plane/y",       "plane/gamma",    "b9_joint"};
  EXPECT_EQ(model.speed_names, speeds);
  EXPECT_EQ(model.nq, 26);
  EXPECT_EQ(model.nv, 24);
  const int v_index[] = {0, 0, 6, 7, 7, 8, 11, 14, 20, 23};
  for (int k = 1; k <= 9; ++k) EXPECT_EQ(model.bodies[k].v_index, v_index[k]) << "body " << k;
  EXPECT_EQ(model.speed_index("hip/wy"), 12);
  EXPECT_EQ(model.speed_index("hip/e2"), -1);
}

TEST(CoordinateNames, BareModel) {
  const mbk::Model model = mbk::make_bare_model({0, 1, 1}, JointType::kBall123);
  EXPECT_EQ(model.coordinate_names, (Names{"J1/alpha", "J1/beta", "J1/gamma", "J2/alpha", "J2/beta",
                                           "J2/gamma", "J3/alpha", "J3/beta", "J3/gamma"}));
  EXPECT_EQ(model.bodies[2].name, "B2");
  EXPECT_EQ(model.bodies[1].joint.offset, V::Zero());  // on R: no offset
  EXPECT_EQ(model.bodies[3].joint.offset, V(1, 0, 0));
}

// ---- The initial state: zero everywhere except e4 = 1 (identity) for Euler parameters.
TEST(JointState, StartsAtTheIdentity) {
  const mbk::Model model = every_joint_type(mbk::SpeedKind::kCoordinateDerivatives);
  const mbk::JointState<double> state(model);
  ASSERT_EQ(state.position.size(), model.nq);
  ASSERT_EQ(state.velocity.size(), model.nv);
  ASSERT_EQ(state.acceleration.size(), model.nv);
  for (int i = 0; i < model.nq; ++i) {
    const std::string& name = model.coordinate_names[i];
    const bool e4 = name.size() >= 3 && name.compare(name.size() - 3, 3, "/e4") == 0;
    EXPECT_EQ(state.position[i], e4 ? 1.0 : 0.0) << name;
  }
  EXPECT_TRUE(state.velocity.isZero());
  EXPECT_TRUE(state.acceleration.isZero());
}

// ---- Mimics: q = multiplier * q_source + offset; speeds and accelerations scale by multiplier.
mbk::Model two_hinges_and_a_mimic() {
  mbk::Model model;
  model.bodies = {mbk::Body(), body("a", 0, JointType::kRevolute),
                  body("b", 1, JointType::kPrismatic), body("c", 2, JointType::kRevolute)};
  model.mimics.push_back({2, 0, -2.0, 0.25});  // c follows a
  mbk::finalize_model(model);
  return model;
}

TEST(Mimics, ApplyMimics) {
  const mbk::Model model = two_hinges_and_a_mimic();
  mbk::JointState<double> state(model);
  state.position << 0.5, 0.7, 99.0;
  state.velocity << -1.5, 0.3, 99.0;
  state.acceleration << 4.0, -0.2, 99.0;
  mbk::apply_mimics(model, state);
  EXPECT_EQ(state.position, Eigen::Vector3d(0.5, 0.7, -2.0 * 0.5 + 0.25));
  EXPECT_EQ(state.velocity, Eigen::Vector3d(-1.5, 0.3, 3.0));
  EXPECT_EQ(state.acceleration, Eigen::Vector3d(4.0, -0.2, -8.0));
}

TEST(Mimics, Validation) {
  mbk::Model model = two_hinges_and_a_mimic();
  model.mimics[0].source = 3;  // out of range
  expect_error(model, {"mimic"});
  model.mimics[0] = {2, 2, 1.0, 0.0};  // follows itself
  expect_error(model, {"mimic"});
  model.mimics[0] = {2, 0, std::numeric_limits<double>::infinity(), 0.0};
  expect_error(model, {"mimic"});
  model.mimics[0] = {-1, 0, 1.0, 0.0};
  expect_error(model, {"mimic"});
  // A mimic needs speeds that are coordinate derivatives.
  model.mimics[0] = {2, 0, 1.0, 0.0};
  model.bodies.push_back(body("d", 3, JointType::kBallEuler));
  model.speeds = mbk::SpeedKind::kAngularVelocity;
  expect_error(model, {"mimic", "coordinate-derivative speeds"});
}

// A mimic of a mimic, listed before its source (URDF mimics were once applied in joint name
// order): d = 3 c + 1 where c = -2 a + 0.25; evaluated in list order, d read c's stale value.
TEST(Mimics, MimicOfAMimicReadsTheUpdatedSource) {
  mbk::Model model = two_hinges_and_a_mimic();
  model.bodies.push_back(body("d", 3, JointType::kRevolute));
  model.mimics.insert(model.mimics.begin(), {3, 2, 3.0, 1.0});
  mbk::finalize_model(model);
  mbk::JointState<double> state(model);
  state.position << 0.5, 0.7, 99.0, 99.0;
  state.velocity << -1.5, 0.3, 99.0, 99.0;
  mbk::apply_mimics(model, state);
  const double c = -2.0 * 0.5 + 0.25;
  EXPECT_EQ(state.position, Eigen::Vector4d(0.5, 0.7, c, 3.0 * c + 1.0));
  EXPECT_EQ(state.velocity, Eigen::Vector4d(-1.5, 0.3, 3.0, 9.0));
}

TEST(Mimics, CyclesAndTwoSourcesAreRefusedNamingTheJoints) {
  mbk::Model model = two_hinges_and_a_mimic();  // joints a_joint, b_joint, c_joint
  model.mimics.push_back({0, 2, 1.0, 0.0});     // a follows c, c follows a
  expect_error(model, {"mimic joints form a cycle", "c_joint -> a_joint -> c_joint"});
  model.mimics.back() = {1, 2, 1.0, 0.0};  // b follows c: a chain, accepted
  EXPECT_NO_THROW(mbk::finalize_model(model));
  model.mimics.push_back({2, 1, 1.0, 0.0});  // c follows a and b
  expect_error(model, {"c_joint", "mimics two joints"});
}

// A ball joint `s` has the coordinates s/alpha, s/beta, s/gamma; a joint named `s/beta`
// beside it would share one, and a state could set only one of the two.
TEST(FinalizeModel, DuplicateCoordinateNamesNameBothJoints) {
  mbk::Model model = three_bodies();
  model.bodies[3].joint.name = "s";
  model.bodies.push_back(body("finger", 3, JointType::kRevolute, "s/beta"));
  expect_error(model, {"body 4 'finger'", "coordinate name 's/beta'", "joint 's/beta'",
                       "joint 's' (body 3 'hand')"});
  model.bodies[4].joint.type = JointType::kFixed;  // no coordinate: no clash
  EXPECT_NO_THROW(mbk::finalize_model(model));
  // Angular velocity speeds of an Euler joint `e` are e/wx, e/wy, e/wz.
  model.speeds = mbk::SpeedKind::kAngularVelocity;
  model.bodies[3].joint = {};
  model.bodies[3].joint.name = "e";
  model.bodies[3].joint.type = JointType::kBallEuler;
  model.bodies[4].joint.type = JointType::kRevolute;
  model.bodies[4].joint.name = "e/wy";
  expect_error(model, {"speed name 'e/wy'", "joint 'e'"});
}

}  // namespace

// Finalizing a finalized model changes nothing (model variants such as Euler-parameter twins
// are finalized again): unit axes are kept bit for bit, others normalized.
TEST(ModelTest, FinalizeIsIdempotentOnAxes) {
  mbk::Model model = mbk_test::random_tree(30, 2);
  const mbk::Model once = model;
  mbk::finalize_model(model);
  for (int k = 1; k <= model.body_count(); ++k)
    EXPECT_EQ(model.bodies[k].joint.axis, once.bodies[k].joint.axis) << "body " << k;
}
