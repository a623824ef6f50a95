// ~get_partial_velocities on a 2,000-link chain (deep_partials.test): the call is
// served off the input's thread, so /tf keeps arriving while a heavy call runs (it stalled for
// over a second: every body's arrays were computed under the node's lock); the tip's columns are
// its chain's; a request over ~partial_velocities_max_entries is refused with a message naming
// the limit and what was asked; a ~reload during a call neither hangs nor crashes the node.
#include <mb_kinematics_msgs/GetPartialVelocities.h>
#include <std_srvs/Trigger.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>

#include "mb_kinematics/core/chain_partial_velocity.h"
#include "test/ros/ros_test_support.h"

using namespace mbk_ros_test;

namespace {

constexpr int kLinks = 2000;
constexpr long kLimit = 1000000;  // ~partial_velocities_max_entries in deep_partials.test
using Clock = std::chrono::steady_clock;
using Srv = mb_kinematics_msgs::GetPartialVelocities;

// q_i(t) = 0.3 sin(0.1 i + t): the state of the chain at time t.
mbk::JointState<double> chain_state(const mbk::Model& model, double t) {
  mbk::JointState<double> s(model);
  for (int i = 0; i < model.nq; ++i) {
    s.position[i] = 0.3 * std::sin(0.1 * i + t);
    s.velocity[i] = 0.3 * std::cos(0.1 * i + t);
  }
  return s;
}

// joint_states of the chain at `stamp` (the bare model's joints J1 ... JN).
sensor_msgs::JointState chain_msg(const mbk::Model& model, const ros::Time& stamp) {
  const mbk::JointState<double> s = chain_state(model, stamp.toSec());
  sensor_msgs::JointState msg;
  msg.header.stamp = stamp;
  msg.name = model.coordinate_names;
  msg.position.assign(s.position.data(), s.position.data() + model.nq);
  msg.velocity.assign(s.velocity.data(), s.velocity.data() + model.nq);
  return msg;
}

class DeepPartialsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    spinner_.start();
    ASSERT_TRUE(ros::service::waitForService("/mb_kinematics/reload", ros::Duration(10)));
    std::vector<int> lower(kLinks);
    std::iota(lower.begin(), lower.end(), 0);
    nh_.setParam("/mb_kinematics/lower_body_array", lower);
    std_srvs::Trigger reload;
    ASSERT_TRUE(ros::service::call("/mb_kinematics/reload", reload));
    ASSERT_TRUE(reload.response.success) << reload.response.message;
    tf_sub_ = nh_.subscribe<tf2_msgs::TFMessage>("/tf", 100, [this](const auto&) {
      std::lock_guard<std::mutex> lock(mutex_);
      arrivals_.push_back(Clock::now());
    });
    states_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 10);
    publisher_ = std::thread([this] {
      while (running_) {  // 200 Hz, stamped now
        states_.publish(chain_msg(model_, ros::Time::now()));
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
    });
    ASSERT_TRUE(wait_until([this] { return tf_count() > 5; }, 20)) << "no /tf from the chain";
  }
  void TearDown() override {
    running_ = false;
    if (publisher_.joinable()) publisher_.join();
    spinner_.stop();  // no /tf callback runs on once arrivals_ is destroyed
    tf_sub_.shutdown();
  }
  size_t tf_count() {
    std::lock_guard<std::mutex> lock(mutex_);
    return arrivals_.size();
  }
  // /tf arrivals strictly between `from` and `to`, and the longest time without one there.
  size_t tf_between(Clock::time_point from, Clock::time_point to, double& longest_gap) {
    std::lock_guard<std::mutex> lock(mutex_);
    size_t n = 0;
    Clock::time_point last = from;
    longest_gap = 0;
    for (const Clock::time_point& t : arrivals_) {
      if (t <= from || t >= to) continue;
      longest_gap = std::max(longest_gap, std::chrono::duration<double>(t - last).count());
      last = t;
      ++n;
    }
    longest_gap = std::max(longest_gap, std::chrono::duration<double>(to - last).count());
    return n;
  }
  bool call(Srv& srv) { return ros::service::call("/mb_kinematics/get_partial_velocities", srv); }

  ros::NodeHandle nh_;
  ros::AsyncSpinner spinner_{1};
  const mbk::Model model_ = mbk::make_bare_model(
      [] {
        std::vector<int> lower(kLinks);
        std::iota(lower.begin(), lower.end(), 0);
        return lower;
      }(),
      mbk::JointType::kRevolute);
  ros::Subscriber tf_sub_;
  ros::Publisher states_;
  std::thread publisher_;
  std::atomic<bool> running_{true};
  std::mutex mutex_;
  std::vector<Clock::time_point> arrivals_;
};

TEST_F(DeepPartialsTest, TheTipsColumnsAreItsChains) {
  Srv srv;
  srv.request.bodies = {"B" + std::to_string(kLinks)};
  ASSERT_TRUE(call(srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  ASSERT_EQ(srv.response.partials.size(), 1u);
  const auto& got = srv.response.partials[0];
  ASSERT_EQ(got.speeds.size(), static_cast<size_t>(kLinks));
  const mbk::JointState<double> state = chain_state(model_, srv.response.header.stamp.toSec());
  const auto want = mbk::chain_partial_velocities(model_, state, {kLinks})[0];
  for (int i = 0; i < kLinks; i += 97) {
    EXPECT_EQ(got.speeds[i], model_.speed_names[want[i].speed]);
    expect_near(vec(got.partial_omega[i]), want[i].omega, 1e-9, "omega_kr");
    expect_near(vec(got.partial_velocity[i]), want[i].velocity, 1e-9, "v_kr");
    expect_near(vec(got.partial_velocity_dot[i]), want[i].velocity_dot, 1e-9, "v_kr'");
  }
  std::printf("tip of %d links: %zu entries, response %u bytes\n", kLinks, got.speeds.size(),
              ros::serialization::serializationLength(srv.response));
}

TEST_F(DeepPartialsTest, OverTheLimitIsRefusedNamingIt) {
  Srv srv;  // every body: 2,001,000 entries
  const auto start = Clock::now();
  ASSERT_TRUE(call(srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_TRUE(srv.response.partials.empty());
  const std::string& m = srv.response.message;
  EXPECT_NE(m.find("~partial_velocities_max_entries = " + std::to_string(kLimit)),
            std::string::npos)
      << m;
  EXPECT_NE(m.find(std::to_string(kLinks) + " bodies (every body)"), std::string::npos) << m;
  EXPECT_NE(m.find(std::to_string(kLinks * (kLinks + 1L) / 2) + " entries"), std::string::npos)
      << m;
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 1.0);  // nothing computed
}

// The tip 500 times: 1,000,000 entries, the test's limit, a 104 MB response. /tf keeps arriving
// at about 200 Hz meanwhile: the longest gap is a small part of the call. When the call ran under
// the node's lock, /tf stopped for its computation and fill, 40% of the call.
TEST_F(DeepPartialsTest, TfKeepsFlowingDuringAHeavyCall) {
  Srv srv;
  srv.request.bodies.assign(kLimit / kLinks, "B" + std::to_string(kLinks));
  const auto start = Clock::now();
  ASSERT_TRUE(call(srv));
  const auto end = Clock::now();
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  double gap = 0;
  const size_t during = tf_between(start, end, gap);
  const double seconds = std::chrono::duration<double>(end - start).count();
  std::printf("call of %zu entries: %.3f s, %zu /tf during it, longest gap %.3f s\n",
              srv.request.bodies.size() * kLinks, seconds, during, gap);
  ASSERT_GT(seconds, 0.1) << "too short a call to show a stall";
  EXPECT_GE(during, 5u);
  EXPECT_LT(gap, seconds / 4);
}

// ~reload during a heavy call: the reload returns, the call returns (answered, cancelled by the
// reload, or failed by the closed connection), and the node serves again. In a nodelet the reload
// waited for the whole call holding the input, i.e. the manager's network thread: its bond with
// the loader broke after 4 s, the loader exited and the nodelet was unloaded (3 failures in 4).
TEST_F(DeepPartialsTest, ReloadDuringACall) {
  std::atomic<bool> returned{false};
  std::string refusal;  // the answer's message when the call was answered but not served
  std::thread caller([&] {
    Srv srv;
    srv.request.bodies.assign(kLimit / kLinks, "B" + std::to_string(kLinks));
    const bool answered = call(srv);
    if (answered && !srv.response.success) refusal = srv.response.message;
    std::printf("the call during ~reload: %s\n", !answered         ? "failed (connection closed)"
                                                 : refusal.empty() ? "served"
                                                                   : refusal.c_str());
    returned = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std_srvs::Trigger reload;
  EXPECT_TRUE(ros::service::call("/mb_kinematics/reload", reload));
  EXPECT_TRUE(reload.response.success) << reload.response.message;
  caller.join();
  EXPECT_TRUE(returned);
  if (!refusal.empty()) {
    EXPECT_NE(refusal.find("~reload"), std::string::npos) << refusal;
  }
  ASSERT_TRUE(
      ros::service::waitForService("/mb_kinematics/get_partial_velocities", ros::Duration(10)));
  const size_t before = tf_count();
  EXPECT_TRUE(wait_until([&] { return tf_count() > before + 3; }, 10)) << "no /tf after";
  Srv srv;
  srv.request.bodies = {"B1"};
  ASSERT_TRUE(call(srv));
  EXPECT_TRUE(srv.response.success) << srv.response.message;
}

// A negative limit ends the node at start, naming the parameter (a test without the fixture).
TEST(DeepPartialsStartup, NegativeLimitExitsNonZero) {
  ros::NodeHandle nh;
  nh.setParam("/limit/limit_node/lower_body_array", std::vector<int>{0, 1});
  std::string output;
  EXPECT_GT(run_node("__ns:=/limit __name:=limit_node _partial_velocities_max_entries:=-1", output),
            0);
  EXPECT_NE(output.find("partial_velocities_max_entries must be >= 0"), std::string::npos)
      << output;
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "deep_partials_test");
  return RUN_ALL_TESTS();
}
