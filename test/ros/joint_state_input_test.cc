// JointStateInput without a ROS master: name matching, validation, merging, mimics, estimates,
// the pairing with joint_accelerations.
#include "mb_kinematics/ros/joint_state_input.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <boost/make_shared.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "mb_kinematics/core/state_check.h"
#include "mb_kinematics/io/urdf_model.h"
#include "mb_kinematics/offline/recording.h"

namespace {

using mbk::Level;

mbk::Model model() {
  return mbk::load_urdf_file(std::string(MBK_SOURCE_DIR) + "/test/ros/test_robot.urdf");
}

const std::vector<std::string> kAll = {"slider_joint",      "float_joint/x",     "float_joint/y",
                                       "float_joint/z",     "float_joint/alpha", "float_joint/beta",
                                       "float_joint/gamma", "arm1_joint",        "arm2_joint"};

sensor_msgs::JointState msg(const std::vector<std::string>& names, double value,
                            bool velocities = false) {
  sensor_msgs::JointState m;
  m.name = names;
  m.position.assign(names.size(), value);
  if (velocities) m.velocity.assign(names.size(), 2 * value);
  return m;
}

class JointStateInputTest : public ::testing::Test {
 protected:
  mbk::Model model_ = model();
  std::unique_ptr<mbk::DerivativeEstimator> estimator_ =
      mbk::make_derivative_estimator("backward_difference");
  mbk_ros::JointStateInput input_{model_, *estimator_, 1.0};
  mbk::JointState<double> state_{model_};
};

TEST_F(JointStateInputTest, RejectsBadMessagesWhole) {
  sensor_msgs::JointState m = msg(kAll, 0.1);
  m.position.pop_back();
  EXPECT_NE(input_.add(m, 1).error.find("positions"), std::string::npos);
  m = msg(kAll, 0.1, true);
  m.velocity.pop_back();
  EXPECT_NE(input_.add(m, 1).error.find("velocities"), std::string::npos);
  m = msg(kAll, 0.1);
  m.name[2] = m.name[0];
  EXPECT_NE(input_.add(m, 1).error.find("named twice"), std::string::npos);
  m = msg(kAll, 0.1);
  m.position[3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(input_.add(m, 1).error.find("NaN"), std::string::npos);
  m = msg(kAll, 0.1, true);
  m.velocity[4] = -std::numeric_limits<double>::infinity();
  EXPECT_NE(input_.add(m, 1).error.find("Inf"), std::string::npos);
  EXPECT_EQ(input_.missing().size(), kAll.size()) << "a rejected message changed the state";
}

// The node and mbk bag's recordings take joint states through one intake
// (core/joint_state_intake.h): each bad sample is refused with the same words by both.
TEST_F(JointStateInputTest, TheSameWordsAsARecording) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<sensor_msgs::JointState> bad(5, msg(kAll, 0.1, true));
  bad[0].position.pop_back();
  bad[1].velocity.pop_back();
  bad[2].name[2] = bad[2].name[0];
  bad[3].position[3] = nan;
  bad[4].velocity[4] = -std::numeric_limits<double>::infinity();
  const std::string kBad = "bad sample (lengths, duplicates, NaN/Inf)";
  for (const sensor_msgs::JointState& m : bad) {
    mbk::RecordingBuilder recording(model_);
    recording.add(1, m.name, m.position, m.velocity, "s");
    const std::string error = input_.add(m, 1).error;
    ASSERT_FALSE(error.empty());
    ASSERT_EQ(recording.log().drops.at(kBad), 1);
    EXPECT_EQ(recording.log().example.at(kBad), "s: " + error);
  }
}

// A published mimic value wins over the mimic rule, as in robot_state_publisher: the
// finger (2 * arm2 + 0.1) published at 9 is placed at 9; unpublished, the rule places it.
TEST_F(JointStateInputTest, UnknownNamesIgnoredPublishedMimicsWin) {
  input_.add(msg(kAll, 0.25), 1);
  EXPECT_EQ(input_.fill(Level::kPose, nullptr, state_), Level::kPose);
  const int finger = model_.coordinate_index("finger_joint");
  EXPECT_DOUBLE_EQ(state_.position[finger], 2 * 0.25 + 0.1);  // not published: the rule
  sensor_msgs::JointState m = msg(kAll, 0.25);
  m.name.push_back("gripper");
  m.position.push_back(std::numeric_limits<double>::quiet_NaN());
  m.name.push_back("finger_joint");
  m.position.push_back(9.0);
  const auto update = input_.add(m, 2);
  EXPECT_EQ(update.error, "");
  EXPECT_EQ(update.unknown, std::vector<std::string>({"gripper"}));
  EXPECT_EQ(update.used, static_cast<int>(kAll.size()) + 1);
  EXPECT_TRUE(input_.missing().empty());
  EXPECT_EQ(input_.fill(Level::kPose, nullptr, state_), Level::kPose);
  EXPECT_EQ(state_.position[finger], 9.0);
}

TEST_F(JointStateInputTest, MergesPartialMessages) {
  const std::vector<std::string> arm = {"arm1_joint", "arm2_joint"};
  input_.add(msg(arm, 0.5), 1);
  EXPECT_EQ(input_.missing().size(), kAll.size() - 2);
  std::vector<std::string> rest(kAll.begin(), kAll.end() - 2);
  input_.add(msg(rest, -0.5), 2);
  EXPECT_TRUE(input_.missing().empty());
  input_.fill(Level::kPose, nullptr, state_);
  EXPECT_EQ(state_.position[model_.coordinate_index("arm2_joint")], 0.5);
  EXPECT_EQ(state_.position[model_.coordinate_index("slider_joint")], -0.5);
}

// The names are looked up again when they change (the input keeps the previous message's
// lookup): the same names in another order, then one of them replaced by an unknown one.
TEST_F(JointStateInputTest, NamesInAnotherOrderOrReplacedAreLookedUpAgain) {
  sensor_msgs::JointState m = msg(kAll, 0);
  for (size_t i = 0; i < kAll.size(); ++i) m.position[i] = 0.1 * i;
  ASSERT_EQ(input_.add(m, 1).error, "");
  std::reverse(m.name.begin(), m.name.end());
  ASSERT_EQ(input_.add(m, 2).error, "");
  input_.fill(Level::kPose, nullptr, state_);
  for (size_t i = 0; i < kAll.size(); ++i)
    EXPECT_DOUBLE_EQ(state_.position[model_.coordinate_index(kAll[i])], 0.1 * (kAll.size() - 1 - i))
        << kAll[i];
  m.name[0] = "gripper";  // was arm2_joint: it keeps its value
  m.position.assign(kAll.size(), 0.3);
  const auto update = input_.add(m, 3);
  EXPECT_EQ(update.unknown, std::vector<std::string>({"gripper"}));
  EXPECT_EQ(update.used, static_cast<int>(kAll.size()) - 1);
  input_.fill(Level::kPose, nullptr, state_);
  EXPECT_DOUBLE_EQ(state_.position[model_.coordinate_index("arm2_joint")], 0.0);
  EXPECT_DOUBLE_EQ(state_.position[model_.coordinate_index("arm1_joint")], 0.3);
}

// q = t^2 sampled at irregular times: the 3-point estimates are exact.
TEST_F(JointStateInputTest, EstimatesDerivativesAndRestartsOnBackwardsStamps) {
  const double times[] = {10.0, 10.03, 10.04};
  const Level reached[] = {Level::kPose, Level::kVelocity, Level::kAcceleration};
  for (int i = 0; i < 3; ++i) {
    input_.add(msg(kAll, times[i] * times[i]), times[i]);
    EXPECT_EQ(input_.fill(Level::kAcceleration, nullptr, state_), reached[i]) << i;
  }
  EXPECT_NEAR(state_.velocity[0], 2 * 10.04, 1e-8);
  EXPECT_NEAR(state_.acceleration[0], 2.0, 1e-6);
  const auto update = input_.add(msg(kAll, 1.0), 5.0);  // a bag looping
  EXPECT_EQ(update.reset.size(), kAll.size());
  EXPECT_EQ(input_.fill(Level::kVelocity, nullptr, state_), Level::kPose);
  input_.add(msg(kAll, 1.1), 5.1);
  input_.add(msg(kAll, 1.2), 6.5);  // a pause longer than max_gap: no difference across it
  EXPECT_EQ(input_.fill(Level::kVelocity, nullptr, state_), Level::kPose);
}

// ~missing_coordinates: a coordinate is never set, fresh, or stale (older than max_gap = 1 s);
// settled once it has the samples fill() needs for accelerations.
TEST_F(JointStateInputTest, FreshnessAndSettling) {
  using F = mbk_ros::JointStateInput::Freshness;
  std::vector<std::string> all_but_arm2(kAll.begin(), kAll.end() - 1);
  const int slider = model_.coordinate_index("slider_joint");
  const int arm2 = model_.coordinate_index("arm2_joint");
  EXPECT_EQ(input_.freshness(slider, 10.0), F::kNever);
  input_.add(msg(all_but_arm2, 0.1), 10.0);
  EXPECT_EQ(input_.freshness(slider, 10.0), F::kFresh);
  EXPECT_EQ(input_.freshness(arm2, 10.0), F::kNever);
  EXPECT_FALSE(input_.settled(slider));
  input_.add(msg(all_but_arm2, 0.2), 10.1);
  EXPECT_FALSE(input_.settled(slider));
  input_.add(msg(all_but_arm2, 0.3), 10.2);
  EXPECT_TRUE(input_.settled(slider));
  EXPECT_EQ(input_.freshness(slider, 11.2), F::kFresh);
  EXPECT_EQ(input_.freshness(slider, 11.3), F::kStale);
}

// The coordinates not taken from the input get the zero configuration and zero derivatives,
// and do not hold the level back; the others are as without the flags.
TEST_F(JointStateInputTest, FillLeavesOutTheCoordinatesNotFromTheInput) {
  std::vector<std::string> all_but_arm2(kAll.begin(), kAll.end() - 1);
  const int arm2 = model_.coordinate_index("arm2_joint");
  const int finger = model_.coordinate_index("finger_joint");
  std::vector<char> from_input(model_.nq, 1);
  from_input[arm2] = 0;
  const double times[] = {10.0, 10.03, 10.04};
  for (double t : times) input_.add(msg(all_but_arm2, t * t), t);
  state_.position[arm2] = state_.velocity[arm2] = state_.acceleration[arm2] = 7;  // overwritten
  EXPECT_EQ(input_.fill(Level::kAcceleration, nullptr, state_, &from_input), Level::kAcceleration);
  EXPECT_EQ(state_.position[arm2], 0);
  EXPECT_EQ(state_.velocity[arm2], 0);
  EXPECT_EQ(state_.acceleration[arm2], 0);
  EXPECT_DOUBLE_EQ(state_.position[finger], 0.1);  // its mimic: 2 * 0 + 0.1
  EXPECT_NEAR(state_.velocity[0], 2 * 10.04, 1e-8);
  EXPECT_NEAR(state_.acceleration[0], 2.0, 1e-6);
  // Without the flags arm2_joint, never set, has no estimate: positions only.
  EXPECT_EQ(input_.fill(Level::kAcceleration, nullptr, state_), Level::kPose);
}

TEST_F(JointStateInputTest, GivenVelocitiesAndPairedAccelerations) {
  input_.add(msg(kAll, 1.0, true), 1.0);  // velocity 2
  EXPECT_EQ(input_.fill(Level::kAcceleration, nullptr, state_), Level::kVelocity);
  EXPECT_EQ(state_.velocity[0], 2.0);
  mb_kinematics_msgs::JointAccelerations a;
  a.name = kAll;
  a.acceleration.assign(kAll.size(), 7.0);
  mbk_ros::AccelerationSample sample;
  EXPECT_EQ(input_.convert(a, 1.0, sample), "");
  EXPECT_EQ(input_.fill(Level::kAcceleration, &sample, state_), Level::kAcceleration);
  EXPECT_EQ(state_.acceleration[0], 7.0);
  EXPECT_EQ(state_.acceleration[model_.coordinate_index("finger_joint")], 14.0);  // mimic
  input_.add(msg(kAll, 1.5, true), 1.5);  // velocity 3: acceleration 2 from the velocities
  EXPECT_EQ(input_.fill(Level::kAcceleration, nullptr, state_), Level::kAcceleration);
  EXPECT_NEAR(state_.acceleration[0], 2.0, 1e-12);
  a.name[0] = "nope";
  EXPECT_NE(input_.convert(a, 1.0, sample).find("not in the model"), std::string::npos);
}

// The pairing with joint_accelerations (acceleration_pairing.h), owned by the input: a sample
// waits for the accelerations of its stamp while a publisher of them is there, and goes on
// unpaired when the next sample comes first; without one it goes on at once.
TEST_F(JointStateInputTest, PairsSamplesWithTheAccelerationsOfTheirStamp) {
  auto sample = [](double t) {
    auto m = boost::make_shared<sensor_msgs::JointState>(msg(kAll, t, true));
    m->header.stamp = ros::Time(t);
    return sensor_msgs::JointStateConstPtr(m);
  };
  mb_kinematics_msgs::JointAccelerations a;
  a.header.stamp = ros::Time(2.0);
  a.name = kAll;
  a.acceleration.assign(kAll.size(), 7.0);
  const sensor_msgs::JointStateConstPtr one = sample(1.0), two = sample(2.0), three = sample(3.0);

  ASSERT_EQ(input_.pair(one, false).size(), 1u);  // nobody publishes accelerations: at once
  EXPECT_EQ(input_.pair(one, false)[0].sample, one);
  EXPECT_FALSE(input_.pair(one, false)[0].unpaired);
  EXPECT_TRUE(input_.pair(two, true).empty());  // waits for its accelerations
  std::string error;
  const auto& completed = input_.pair(a, 2.0, error);
  EXPECT_EQ(error, "");
  ASSERT_EQ(completed.size(), 1u);
  EXPECT_EQ(completed[0].sample, two);
  EXPECT_FALSE(completed[0].unpaired);
  ASSERT_NE(input_.paired(2.0), nullptr);
  EXPECT_EQ(input_.paired(2.0)->value[0], 7.0);
  EXPECT_EQ(input_.paired(3.0), nullptr);
  input_.add(*two, 2.0);
  EXPECT_EQ(input_.fill(Level::kAcceleration, input_.paired(2.0), state_), Level::kAcceleration);
  EXPECT_EQ(state_.acceleration[0], 7.0);

  EXPECT_TRUE(input_.pair(three, true).empty());
  const auto& released = input_.pair(sample(4.0), true);  // 3's accelerations did not come
  ASSERT_EQ(released.size(), 1u);
  EXPECT_EQ(released[0].sample, three);
  EXPECT_TRUE(released[0].unpaired);

  a.name[0] = "nope";  // refused: nothing kept, nothing completed
  a.header.stamp = ros::Time(4.0);
  EXPECT_TRUE(input_.pair(a, 4.0, error).empty());
  EXPECT_NE(error.find("not in the model"), std::string::npos);
  EXPECT_EQ(input_.paired(4.0), nullptr);
}

// A publisher that flips the sign of its Euler parameters between samples (same rotation):
// the input keeps e continuous, so the estimated derivatives stay those of the motion.
TEST(JointStateInputEuler, SignFlipsKeepEContinuous) {
  const mbk::Model model = mbk::make_bare_model({0}, mbk::JointType::kBallEuler);
  const auto estimator = mbk::make_derivative_estimator("backward_difference");
  mbk_ros::JointStateInput input(model, *estimator, 1.0);
  const std::vector<std::string> names = {"J1/e1", "J1/e2", "J1/e3", "J1/e4"};
  for (int i = 0; i < 4; ++i) {  // rotation about z at 1 rad/s; every other sample negated
    const double t = 0.01 * i, sign = i % 2 ? -1.0 : 1.0;
    sensor_msgs::JointState m;
    m.name = names;
    m.position = {0.0, 0.0, sign * std::sin(t / 2), sign * std::cos(t / 2)};
    ASSERT_TRUE(input.add(m, t).error.empty());
  }
  mbk::JointState<double> state(model);
  ASSERT_EQ(input.fill(Level::kVelocity, nullptr, state), Level::kVelocity);
  // e3' = cos(t/2) / 2 at t = 0.03, to the 3-point difference's O(h^2) error (~1e-6 here).
  EXPECT_NEAR(state.velocity[2], std::cos(0.015) / 2, 1e-5);
  EXPECT_NEAR(state.velocity[3], -std::sin(0.015) / 2, 1e-5);
  EXPECT_GT(state.position[3], 0.0);  // the last sample was negated back: continuous with e4 > 0
}

// The same samples in a recording: the same continuous e, and velocities negated with it.
TEST(JointStateInputEuler, ARecordingFlipsTheSame) {
  const mbk::Model model = mbk::make_bare_model({0}, mbk::JointType::kBallEuler);
  const auto estimator = mbk::make_derivative_estimator("backward_difference");
  mbk_ros::JointStateInput input(model, *estimator, 1.0);
  mbk::RecordingBuilder recording(model);
  for (int i = 0; i < 4; ++i) {
    const double t = 0.01 * i, sign = i % 2 ? -1.0 : 1.0;
    sensor_msgs::JointState m;
    m.name = model.coordinate_names;
    m.position = {0.0, sign * 0.1, sign * std::sin(t / 2), sign * std::cos(t / 2)};
    m.velocity = {sign * 1, sign * 2, sign * 3, sign * 4};
    ASSERT_EQ(input.add(m, t).flipped, i % 2);
    recording.add(t, m.name, m.position, m.velocity, "s");
    mbk::JointState<double> state(model);
    ASSERT_EQ(input.fill(Level::kPose, nullptr, state), Level::kPose);
    for (int c = 0; c < 4; ++c) EXPECT_EQ(state.position[c], sign * m.position[c]) << i;
  }
  const mbk::Recording r = recording.finish();
  ASSERT_EQ(r.rows(), 4);
  for (int row = 0; row < 4; ++row)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(r.velocity[row * 4 + c], c + 1.0) << row;
  EXPECT_GT(r.position[3 * 4 + 3], 0.0);
}

}  // namespace

// One finite sample must not poison the estimators. A positions-only stream
// of the quadratic q_i = c_i + 0.5 t + 0.2 t^2 at 100 Hz through kalman_smooth (the node's
// default); `clean` sees the stream, `hit` the same stream and the hostile samples.
class PoisonTest : public ::testing::Test {
 protected:
  static double q(int i, double t) { return 0.1 * i + 0.5 * t + 0.2 * t * t; }
  static sensor_msgs::JointState sample(double t) {
    sensor_msgs::JointState m;
    m.name = kAll;
    for (size_t i = 0; i < kAll.size(); ++i) m.position.push_back(q(i, t));
    return m;
  }
  // Feeds samples n0..n1-1 (t = n / 100) to both inputs.
  void feed(int n0, int n1) {
    for (int n = n0; n < n1; ++n) {
      ASSERT_EQ(clean_.add(sample(n / 100.0), n / 100.0).error, "");
      ASSERT_EQ(hit_.add(sample(n / 100.0), n / 100.0).error, "");
    }
  }
  int index(const std::string& name) const { return model_.coordinate_index(name); }
  static size_t slot(const std::string& name) {  // in sample()'s message
    return std::find(kAll.begin(), kAll.end(), name) - kAll.begin();
  }

  mbk::Model model_ = model();
  std::unique_ptr<mbk::DerivativeEstimator> estimator_ =
      mbk::make_derivative_estimator("kalman_smooth");
  mbk_ros::JointStateInput clean_{model_, *estimator_, 1.0}, hit_{model_, *estimator_, 1.0};
  mbk::JointState<double> clean_state_{model_}, hit_state_{model_};
};

// A value mbk::check_state refuses (a translation beyond 1e50) is refused before it reaches an
// estimator: the message changes nothing, and every later estimate is bit for bit the one of
// the stream without it.
TEST_F(PoisonTest, RefusedSampleNeverReachesTheEstimators) {
  feed(0, 10);
  int n = 10;
  for (double huge : {1.7e308, 1e300, 1e51}) {
    for (const char* name : {"slider_joint", "float_joint/x"}) {
      sensor_msgs::JointState m = sample(n / 100.0);
      m.position[slot(name)] = huge;
      const auto update = hit_.add(m, n / 100.0);
      EXPECT_NE(update.error.find("above the limit"), std::string::npos) << update.error;
      EXPECT_NE(update.error.find(name), std::string::npos) << update.error;
      n += 1;  // neither input gets a valid sample at the refused one's stamp
      feed(n, n + 1);
      ++n;
      ASSERT_EQ(clean_.fill(Level::kAcceleration, nullptr, clean_state_), Level::kAcceleration);
      ASSERT_EQ(hit_.fill(Level::kAcceleration, nullptr, hit_state_), Level::kAcceleration);
      EXPECT_EQ(hit_state_.position, clean_state_.position) << name << " " << huge;
      EXPECT_EQ(hit_state_.velocity, clean_state_.velocity) << name << " " << huge;
      EXPECT_EQ(hit_state_.acceleration, clean_state_.acceleration) << name << " " << huge;
    }
  }
  // A speed beyond the limit, given with the positions: refused the same way.
  sensor_msgs::JointState m = sample(n / 100.0);
  m.velocity.assign(kAll.size(), 0.0);
  m.velocity[slot("arm1_joint")] = 1e60;
  EXPECT_NE(hit_.add(m, n / 100.0).error.find("arm1_joint"), std::string::npos);
}

// An angle may be any finite value (check_state accepts it), but its estimates then overflow
// or exceed 1e50: that coordinate's estimator restarts (named in the update) instead of
// stopping every later sample. Within a few samples the estimates are back, at the motion's
// own scale, and the other coordinates never noticed.
TEST_F(PoisonTest, AngleSpikeRestartsThatCoordinateOnly) {
  const int arm = index("arm1_joint");
  feed(0, 10);
  int n = 10;
  for (double huge : {1.7e308, 1e300, 1e60}) {
    sensor_msgs::JointState m = sample(n / 100.0);
    m.position[slot("arm1_joint")] = huge;
    ASSERT_EQ(clean_.add(sample(n / 100.0), n / 100.0).error, "");
    const auto update = hit_.add(m, n / 100.0);
    ASSERT_EQ(update.error, "") << "an angle of " << huge << " is a valid angle";
    EXPECT_EQ(update.estimator_reset, std::vector<std::string>{"arm1_joint"}) << huge;
    ++n;
    int back = 0;  // samples until full estimates again
    for (int i = 1; i <= 10; ++i, ++n) {
      feed(n, n + 1);
      // What the node would publish passes check_state: no Inf, nothing beyond 1e50.
      const Level level = hit_.fill(Level::kAcceleration, nullptr, hit_state_);
      EXPECT_EQ(mbk::check_state(model_, hit_state_), "") << huge << ", sample " << i;
      if (level == Level::kAcceleration && back == 0) back = i;
    }
    ASSERT_GT(back, 0) << "no estimates within 10 samples after an angle of " << huge;
    EXPECT_LE(back, 6) << huge;
    // Back on the motion: 10 samples after the spike the restarted estimator has the quadratic's
    // own q' and q'' (measured: 3e-12 and 3e-10 off; a poisoned one gives NaN or 1e95).
    const double t = (n - 1) / 100.0;
    EXPECT_NEAR(hit_state_.velocity[arm], 0.5 + 0.4 * t, 1e-6) << huge;
    EXPECT_NEAR(hit_state_.acceleration[arm], 0.4, 1e-6) << huge;
    ASSERT_EQ(clean_.fill(Level::kAcceleration, nullptr, clean_state_), Level::kAcceleration);
    for (int i = 0; i < model_.nq; ++i) {
      if (i == arm) continue;
      EXPECT_EQ(hit_state_.velocity[i], clean_state_.velocity[i]) << model_.coordinate_names[i];
      EXPECT_EQ(hit_state_.acceleration[i], clean_state_.acceleration[i])
          << model_.coordinate_names[i];
    }
  }
}

// A model without mimics or Euler parameters (its messages checked without a trial state when
// every value is within 1e50): the same verdicts as check_state's. A translation or a speed
// beyond 1e50 is refused, named, and changes nothing; an angle of any finite size is taken.
TEST(JointStateInputPlain, BoundsAsCheckState) {
  const mbk::Model model = mbk::load_urdf_string(R"(<robot name="plain">
    <link name="base"/><link name="arm"/><link name="slide"/>
    <joint name="turn" type="revolute"><parent link="base"/><child link="arm"/>
      <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
    <joint name="push" type="prismatic"><parent link="arm"/><child link="slide"/>
      <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  </robot>)");
  const auto estimator = mbk::make_derivative_estimator("backward_difference");
  mbk_ros::JointStateInput input(model, *estimator);
  mbk::JointState<double> state(model);
  const std::vector<std::string> names = {"turn", "push"};
  sensor_msgs::JointState m = msg(names, 0.25, true);
  ASSERT_EQ(input.add(m, 1.0).error, "");
  for (double huge : {1e51, 1e300}) {
    m = msg(names, 0.5, true);
    m.position[1] = huge;
    std::string error = input.add(m, 2.0).error;
    EXPECT_NE(error.find("'push': magnitude"), std::string::npos) << error;
    m = msg(names, 0.5, true);
    m.velocity[0] = -huge;
    error = input.add(m, 2.0).error;
    EXPECT_NE(error.find("speed 'turn': magnitude"), std::string::npos) << error;
    input.fill(Level::kPose, nullptr, state);
    EXPECT_EQ(state.position[1], 0.25) << "a refused message changed nothing";
  }
  m = msg(names, 0.5, true);
  m.position[0] = 1e300;  // a valid angle
  EXPECT_EQ(input.add(m, 3.0).error, "");
  input.fill(Level::kPose, nullptr, state);
  EXPECT_EQ(state.position[0], 1e300);
  EXPECT_EQ(state.position[1], 0.5);
}

// fill's `checked` (NodeInput then skips mbk::check_state; the proof in fill): whenever it is
// true, check_state accepts the state filled. Messages of random values naming every coordinate
// of a plain model, with and without velocities: mostly small, now and then at the bound 1e50,
// beyond it (a translation's refused; an angle's taken, not plainly bounded), or jumps of 1e49
// whose estimates go beyond the bound (their histories restart); and on a model with a mimic,
// never checked. The node's Kalman bank and a bank of other estimators (estimator_bank.h).
TEST(JointStateInputPlain, CheckedAsCheckState) {
  const mbk::Model plain = mbk::load_urdf_string(R"(<robot name="plain">
    <link name="base"/><link name="arm"/><link name="slide"/>
    <joint name="turn" type="continuous"><parent link="base"/><child link="arm"/>
      <axis xyz="0 0 1"/></joint>
    <joint name="push" type="prismatic"><parent link="arm"/><child link="slide"/>
      <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  </robot>)");
  const mbk::Model mimic = model();
  for (const char* name : {"kalman_smooth", "backward_difference"})  // KalmanBank, ClonedBank
    for (const mbk::Model* m : {&plain, &mimic}) {
      SCOPED_TRACE(name);
      std::vector<std::string> names = m->coordinate_names;
      const auto estimator = mbk::make_derivative_estimator(name);
      mbk_ros::JointStateInput input(*m, *estimator, 0.5);
      mbk::JointState<double> state(*m);
      std::mt19937 rng(5);
      std::uniform_real_distribution<double> u(-1, 1);
      const auto value = [&] {
        const double r = u(rng);
        return r > 0.98 ? 1e50 : r > 0.96 ? -1e49 : r > 0.95 ? 3e50 : r > 0.94 ? -1e300 : u(rng);
      };
      int checked_count = 0, restarted = 0;
      double t = 1.0;
      for (int k = 0; k < 3000; ++k) {
        t += 0.01;
        sensor_msgs::JointState msg;
        msg.name = names;
        const bool velocities = (k / 200) % 4 != 3;
        for (size_t i = 0; i < names.size(); ++i) {
          msg.position.push_back(value());
          if (velocities) msg.velocity.push_back(value());
        }
        const mbk_ros::JointStateInput::Update update = input.add(msg, t);
        if (!update.error.empty()) continue;
        bool checked = true;
        input.fill(Level::kAcceleration, nullptr, state, nullptr, &checked);
        if (checked) {
          EXPECT_EQ(mbk::check_state(*m, state), "") << k;
        }
        checked_count += checked;
        mbk::JointState<double> lower(*m);
        input.fill(Level::kVelocity, nullptr, lower, nullptr, &checked);
        EXPECT_FALSE(checked) << k;  // accelerations not written: not known
        if (update.estimator_reset.empty()) continue;
        EXPECT_FALSE(checked) << k;  // estimates beyond the bound: restarted, not all estimated
        ++restarted;
      }
      if (m == &mimic) {
        EXPECT_EQ(checked_count, 0);
        continue;
      }
      EXPECT_GT(checked_count, 1000);
      EXPECT_GT(restarted, 10);  // estimates beyond the bound were there to be told apart
    }
}

// Messages of one layout (the same names, one publisher) take the steady path: each sample's
// values and estimates must be those of one KalmanEstimator per coordinate fed that
// coordinate's given velocities since its last restart, bit for bit, through the events that
// leave the path: a pause beyond max_gap, stamps going back, a refused message, messages without
// velocities, names in another order. Every coordinate named (the mimic too): fill and the
// coverage copy them whole (every_coordinate_at).
TEST(JointStateInputSteady, AsOneFilterPerCoordinate) {
  const mbk::Model model = ::model();
  std::vector<std::string> names = kAll;
  names.push_back("finger_joint");  // the mimic, published
  const auto prototype = mbk::make_derivative_estimator("kalman_smooth");
  mbk_ros::JointStateInput input(model, *prototype, 0.5);
  mbk::JointState<double> state(model);
  std::vector<std::unique_ptr<mbk::DerivativeEstimator>> reference;
  for (int j = 0; j < model.nq; ++j) reference.push_back(prototype->clone());
  const auto restart = [&] {
    for (auto& r : reference) r->reset();
  };
  double t = 1.0;
  int checked = 0;
  for (int k = 0; k < 300; ++k) {
    t += k == 100 ? 0.6 : k == 150 ? -0.05 : 0.01;  // a pause; stamps back
    if (k == 100 || k == 150) restart();
    if (k == 200) std::reverse(names.begin(), names.end());  // looked up again
    sensor_msgs::JointState m;
    m.name = names;
    for (size_t i = 0; i < names.size(); ++i) {
      m.position.push_back(std::sin(t + i));
      m.velocity.push_back(std::cos(t + i) + 1e-3 * std::sin(40 * t * (i + 1)));
    }
    if (k == 120) {  // refused: changes nothing
      m.position[3] = std::numeric_limits<double>::quiet_NaN();
      ASSERT_NE(input.add(m, t).error, "");
      EXPECT_FALSE(input.every_coordinate_at(t));
      continue;
    }
    if (k == 250) {  // positions only: the velocities' histories start again after it
      m.velocity.clear();
      ASSERT_EQ(input.add(m, t).error, "");
      restart();
      continue;
    }
    const auto update = input.add(m, t);
    ASSERT_EQ(update.error, "") << k;
    EXPECT_EQ(update.reset.size(), k == 150 ? names.size() : 0u) << k;
    EXPECT_EQ(update.used, model.nq);
    EXPECT_TRUE(input.every_coordinate_at(t));
    EXPECT_FALSE(input.every_coordinate_at(t + 0.01));
    bool estimated = true;
    for (size_t i = 0; i < names.size(); ++i) {
      auto& r = *reference[model.coordinate_index(names[i])];
      r.add(t, m.velocity[i]);
      double first = 0, second = 0;
      estimated = estimated && r.estimate(first, second) >= 1;
    }
    ASSERT_EQ(input.fill(Level::kAcceleration, nullptr, state),
              estimated ? Level::kAcceleration : Level::kVelocity)
        << k;
    for (size_t i = 0; i < names.size() && estimated; ++i) {
      const int j = model.coordinate_index(names[i]);
      double first = 0, second = 0;
      reference[j]->estimate(first, second);
      ASSERT_EQ(state.position[j], m.position[i]) << k << " " << names[i];
      ASSERT_EQ(state.velocity[j], m.velocity[i]) << k << " " << names[i];
      ASSERT_EQ(state.acceleration[j], first) << k << " " << names[i];
      ++checked;
    }
  }
  EXPECT_GT(checked, 250 * model.nq);
}
