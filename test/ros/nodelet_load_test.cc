// A second KinematicsNodelet loaded into the manager while the first takes joint_states at
// 2 kHz (nodelet_load.test): every load call returns (no lock-order deadlock between an input
// callback and the loading thread's subscribe), the new instance advertises
// ~get_partial_velocities under its own name (not the manager's), and the first
// instance keeps publishing.
#include <gtest/gtest.h>
#include <mb_kinematics_msgs/BodyKinematicsArray.h>
#include <nodelet/NodeletLoad.h>
#include <nodelet/NodeletUnload.h>
#include <ros/ros.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <future>
#include <memory>
#include <string>
#include <thread>

namespace {

constexpr int kLoads = 5;
constexpr auto kCallLimit = std::chrono::seconds(15);  // a load takes well under a second

// Calls `service` off this thread; false if it did not answer within kCallLimit (the call is
// left hanging: main ends the process with _Exit).
template <typename S>
bool call_within_limit(const std::string& service, S& srv, bool& ok) {
  auto done = std::make_shared<std::promise<bool>>();
  std::future<bool> answer = done->get_future();
  std::thread([done, service, srv]() mutable {
    const bool called = ros::service::call(service, srv);
    done->set_value(called && srv.response.success);
  }).detach();
  if (answer.wait_for(kCallLimit) != std::future_status::ready) return false;
  ok = answer.get();
  return true;
}

class NodeletLoadTest : public ::testing::Test {
 protected:
  void SetUp() override {
    sub_ = nh_.subscribe<mb_kinematics_msgs::BodyKinematicsArray>(
        "body_kinematics", 1000, [this](const auto&) { ++received_; });
    ASSERT_TRUE(ros::service::waitForService(kLoad, ros::Duration(20)));
    ASSERT_TRUE(flowing()) << "the first nodelet publishes nothing";
  }
  // Some body_kinematics arrives within two seconds.
  bool flowing() {
    const int before = received_;
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while (std::chrono::steady_clock::now() < end && received_ == before)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return received_ > before;
  }

  static constexpr const char* kLoad = "/mb_kinematics_manager/load_nodelet";
  static constexpr const char* kUnload = "/mb_kinematics_manager/unload_nodelet";
  ros::NodeHandle nh_;
  ros::Subscriber sub_;
  std::atomic<int> received_{0};
};

TEST_F(NodeletLoadTest, SecondInstanceLoadsUnderLoad) {
  for (int i = 0; i < kLoads; ++i) {
    const std::string name = "/mb_kinematics_" + std::to_string(i);
    nodelet::NodeletLoad load;
    load.request.name = name;
    load.request.type = "mb_kinematics/KinematicsNodelet";
    bool ok = false;
    ASSERT_TRUE(call_within_limit(kLoad, load, ok)) << "load " << i << " never returned";
    ASSERT_TRUE(ok) << "load " << i << " failed";
    EXPECT_TRUE(ros::service::exists(name + "/get_partial_velocities", false));
    ASSERT_TRUE(flowing()) << "no output after load " << i;
    nodelet::NodeletUnload unload;
    unload.request.name = name;
    ASSERT_TRUE(call_within_limit(kUnload, unload, ok)) << "unload " << i << " never returned";
    ASSERT_TRUE(ok) << "unload " << i << " failed";
  }
  EXPECT_TRUE(ros::service::exists("/mb_kinematics/get_partial_velocities", false));
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "nodelet_load_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  std::_Exit(result);  // a deadlocked call's thread would keep the process alive
}
