// The real-robot conformance set: for the published robot description on
// /robot_description (real_robots.test), the node's /tf and /tf_static agree with
// robot_state_publisher's on the same joint_states stream to 1e-12 m and 1e-12 rad (the angle of
// the quaternion difference), mimic joints published off their rule included (the published
// value wins, as in robot_state_publisher), and body_kinematics' system mass is the URDF's sum.
// With ~odometry (odometry:=true) the base floats on ~base_odometry, its odometry half a period
// late: R -> base and every body's pose in R agree with the base's exact pose composed with
// robot_state_publisher's tf. Then mbk bag
// on the stream the node got (joint_states with velocities, joint_accelerations, the odometry)
// gives the node's tf and body_kinematics to 1e-12.
#include <mb_kinematics_msgs/JointAccelerations.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <tf2_msgs/TFMessage.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <map>

#include "mb_kinematics/io/urdf_model.h"
#include "test/ros/ros_test_support.h"
#include "test/support/urdf_facts.h"

using namespace mbk_ros_test;

namespace {

// Largest translation (m) and rotation (rad, 2 asin |vec(q_a^-1 q_b)|) differences.
void compare(const std::map<Key, geometry_msgs::TransformStamped>& ours,
             const std::map<Key, geometry_msgs::TransformStamped>& theirs, double& position,
             double& rotation) {
  for (const auto& [key, t] : theirs) {
    const auto it = ours.find(key);
    ASSERT_NE(it, ours.end()) << "no tf of ours for " << key.first << " at " << key.second;
    EXPECT_EQ(it->second.header.frame_id, t.header.frame_id) << key.first;
    position = std::max(
        position, (vec(it->second.transform.translation) - vec(t.transform.translation)).norm());
    const auto& a = it->second.transform.rotation;
    const auto& b = t.transform.rotation;
    const Eigen::Quaterniond qa(a.w, a.x, a.y, a.z), qb(b.w, b.x, b.y, b.z);
    const Eigen::Quaterniond d = qa.conjugate() * qb;
    rotation = std::max(rotation, 2 * std::asin(std::min(1.0, d.vec().norm())));
  }
}

using Transform = Eigen::Isometry3d;

Transform transform(const geometry_msgs::Transform& t) {
  const auto& r = t.rotation;
  Transform out = Transform::Identity();
  out.linear() = Eigen::Quaterniond(r.w, r.x, r.y, r.z).toRotationMatrix();
  out.translation() = vec(t.translation);
  return out;
}

// The base's motion for ~odometry: a constant twist, in R, from a pose off the identity.
struct BaseMotion {
  nav_msgs::Odometry at(double tau, const ros::Time& stamp) const {
    const Eigen::Vector3d v(0.3, -0.2, 0.05), w(0.2, 0.4, -0.6);
    const Eigen::Quaterniond q =
        Eigen::AngleAxisd(w.norm() * tau, w.normalized()) *
        Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()));
    return odometry_msg("odom", stamp, Eigen::Vector3d(1.0, -0.5, 0.9) + v * tau, q, v, w);
  }
};

// Largest position and rotation differences of `a` to `b` (rotation: quaternion difference).
void pose_difference(const Transform& a, const Transform& b, double& position, double& rotation) {
  position = std::max(position, (a.translation() - b.translation()).norm());
  const Eigen::Quaterniond d =
      Eigen::Quaterniond(a.linear()).conjugate() * Eigen::Quaterniond(b.linear());
  rotation = std::max(rotation, 2 * std::asin(std::min(1.0, d.vec().norm())));
}

// Each link's pose in the frame of `root_pose`: root_pose composed with robot_state_publisher's
// chain of transforms (moving ones at `stamp`, fixed ones), keyed by child frame.
std::map<std::string, Transform> poses_in_r(
    const Transform& root_pose, const std::string& root, double stamp,
    const std::map<Key, geometry_msgs::TransformStamped>& moving,
    const std::map<Key, geometry_msgs::TransformStamped>& fixed) {
  std::map<std::string, const geometry_msgs::TransformStamped*> parent;
  for (const auto& [key, t] : moving)
    if (key.second == stamp) parent[key.first] = &t;
  for (const auto& [key, t] : fixed) parent[key.first] = &t;
  std::map<std::string, Transform> out{{root, root_pose}};
  std::function<Transform(const std::string&)> pose = [&](const std::string& frame) {
    const auto known = out.find(frame);
    if (known != out.end()) return known->second;
    const auto it = parent.find(frame);
    if (it == parent.end()) return Transform(Transform::Identity());  // not reached: reported
    const Transform p = pose(it->second->header.frame_id) * transform(it->second->transform);
    out[frame] = p;
    return p;
  };
  for (const auto& [frame, t] : parent) pose(frame);
  return out;
}

// Largest differences of `a` to `b`: of the poses, mass centers and velocities into `motion`, of
// the accelerations into `acceleration`.
void body_difference(const mb_kinematics_msgs::BodyKinematics& a,
                     const mb_kinematics_msgs::BodyKinematics& b, double& motion,
                     double& acceleration) {
  const auto d = [](const auto& x, const auto& y) { return (vec(x) - vec(y)).norm(); };
  const Eigen::Vector4d qa(a.pose.orientation.w, a.pose.orientation.x, a.pose.orientation.y,
                           a.pose.orientation.z),
      qb(b.pose.orientation.w, b.pose.orientation.x, b.pose.orientation.y, b.pose.orientation.z);
  motion = std::max({motion, d(a.pose.position, b.pose.position), (qa - qb).norm(),
                     d(a.mass_center, b.mass_center), d(a.twist.angular, b.twist.angular),
                     d(a.twist.linear, b.twist.linear)});
  acceleration = std::max(
      {acceleration, d(a.accel.angular, b.accel.angular), d(a.accel.linear, b.accel.linear)});
}

// mbk bag's output (`path`): its /tf by (child, stamp) and its body_kinematics by stamp.
void read_output_bag(const std::string& path, std::map<Key, geometry_msgs::TransformStamped>& tf,
                     std::map<double, mb_kinematics_msgs::BodyKinematicsArray>& kinematics) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/tf"))) {
    const auto msg = m.instantiate<tf2_msgs::TFMessage>();  // kept while its transforms are read
    for (const auto& t : msg->transforms) tf[{t.child_frame_id, t.header.stamp.toSec()}] = t;
  }
  for (const rosbag::MessageInstance& m :
       rosbag::View(bag, rosbag::TopicQuery("/body_kinematics"))) {
    const auto msg = m.instantiate<mb_kinematics_msgs::BodyKinematicsArray>();
    kinematics[msg->header.stamp.toSec()] = *msg;
  }
}

TEST(RealRobots, NodeAgreesWithRobotStatePublisherAndMbkBag) {
  ros::NodeHandle nh, pnh("~");
  std::string xml;
  ASSERT_TRUE(nh.getParam("/robot_description", xml));
  bool floating = false;
  pnh.getParam("odometry", floating);
  const mbk::Model model = mbk::load_urdf_string(xml);
  Transforms ours(nh, "/tf", false), theirs(nh, "/rsp_tf", false),
      ours_static(nh, "/tf_static", true), theirs_static(nh, "/rsp_tf_static", true);
  KinematicsRecorder kinematics(nh, "body_kinematics");
  ros::Publisher states = nh.advertise<sensor_msgs::JointState>("joint_states", 100);
  ros::Publisher accelerations =
      nh.advertise<mb_kinematics_msgs::JointAccelerations>("joint_accelerations", 100);
  ros::Publisher odometry = nh.advertise<nav_msgs::Odometry>("odom", 100);
  const std::string in_bag = "/tmp/real_robots_" + std::to_string(getpid()) + ".bag";
  rosbag::Bag recorded(in_bag, rosbag::bagmode::Write);  // what the node gets, for mbk bag
  const BaseMotion base;
  const ros::Time start(50.0);
  // The odometry at 100 Hz, half a period after each joint sample and sent after it: each
  // sample waits for it and takes the base interpolated, exact on this motion.
  const auto send_odometry = [&](double tau) {
    const ros::Time stamp = start + ros::Duration(tau);
    odometry.publish(base.at(tau, stamp));
    recorded.write("/odom", stamp, base.at(tau, stamp));
  };
  if (floating) {  // R is known: the node advertises its outputs in R
    ASSERT_TRUE(wait_until([&] { return odometry.getNumSubscribers() > 0; }, 20));
    send_odometry(-0.005);
  }
  ASSERT_TRUE(wait_until(
      [&] {
        return states.getNumSubscribers() >= 2 && accelerations.getNumSubscribers() >= 1 &&
               ours.connected() && theirs.connected() && kinematics.connected();
      },
      20));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const Quadratic trajectory(model);
  const int samples = 10;              // 10 ms apart, accelerations given: nothing estimated
  for (int i = 0; i < samples; ++i) {  // every coordinate, the mimics 0.01 off their rule:
    mbk::JointState<double> state = trajectory.at(i * 0.01);  // a published value wins in both
    for (const mbk::Mimic& m : model.mimics) state.position[m.coordinate] += 0.01;
    const ros::Time stamp = start + ros::Duration(i * 0.01);
    const auto js = joint_state_msg(model, state, stamp, true, model.coordinate_names);
    mb_kinematics_msgs::JointAccelerations a;
    a.header.stamp = stamp;
    a.name = model.coordinate_names;
    a.acceleration.assign(state.acceleration.data(), state.acceleration.data() + model.nq);
    states.publish(js);
    accelerations.publish(a);
    recorded.write("/joint_states", stamp, js);
    recorded.write("/joint_accelerations", stamp, a);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (floating) send_odometry(i * 0.01 + 0.005);
    std::this_thread::sleep_for(std::chrono::milliseconds(45));
  }
  recorded.close();
  ASSERT_TRUE(kinematics.wait_for(start + ros::Duration((samples - 1) * 0.01)));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  double position = 0, rotation = 0;
  const auto mine = ours.get(), rsp = theirs.get(), rsp_static = theirs_static.get();
  EXPECT_FALSE(rsp.empty() && ours_static.get().empty());
  compare(mine, rsp, position, rotation);
  compare(ours_static.get(), rsp_static, position, rotation);
  std::printf("  %zu moving and %zu fixed transforms: %.1e m, %.1e rad\n", rsp.size(),
              rsp_static.size(), position, rotation);
  EXPECT_LT(position, 1e-12);
  EXPECT_LT(rotation, 1e-12);
  const double sum = mbk_test::urdf_mass_sum(xml);
  EXPECT_NEAR(kinematics.latest().system.mass, sum, 1e-12 * sum);
  if (floating) {  // R -> base and every body's pose in R: the exact base pose, composed with rsp
    const std::string root = model.frame;  // the root link
    double base_position = 0, base_rotation = 0, body_position = 0, body_rotation = 0;
    size_t bodies = 0;
    for (int i = 0; i < samples; ++i) {
      const ros::Time stamp = start + ros::Duration(i * 0.01);
      const Transform odom = transform([&] {
        const auto p = base.at(i * 0.01, stamp).pose.pose;
        geometry_msgs::Transform t;
        t.translation.x = p.position.x;
        t.translation.y = p.position.y;
        t.translation.z = p.position.z;
        t.rotation = p.orientation;
        return t;
      }());
      const auto it = mine.find({root, stamp.toSec()});
      ASSERT_NE(it, mine.end()) << "no odom -> " << root << " at sample " << i;
      EXPECT_EQ(it->second.header.frame_id, "odom");
      pose_difference(transform(it->second.transform), odom, base_position, base_rotation);
      const auto expected = poses_in_r(odom, root, stamp.toSec(), rsp, rsp_static);
      for (const auto& msg : kinematics.at(stamp))
        for (const auto& b : msg.bodies) {
          const auto e = expected.find(b.name);
          ASSERT_NE(e, expected.end()) << b.name << " not in robot_state_publisher's tf";
          Transform got = Transform::Identity();
          got.translation() = vec(b.pose.position);
          got.linear() = Eigen::Quaterniond(b.pose.orientation.w, b.pose.orientation.x,
                                            b.pose.orientation.y, b.pose.orientation.z)
                             .toRotationMatrix();
          pose_difference(got, e->second, body_position, body_rotation);
          ++bodies;
        }
    }
    std::printf("  odometry: R -> base %.1e m, %.1e rad; %zu body poses in R %.1e m, %.1e rad\n",
                base_position, base_rotation, bodies, body_position, body_rotation);
    EXPECT_GT(bodies, 0u);
    for (const double e : {base_position, base_rotation, body_position, body_rotation})
      EXPECT_LT(e, 1e-12);
  }
  // mbk bag on the same stream: the node's tf and body_kinematics.
  const std::string urdf = "/tmp/real_robots_" + std::to_string(getpid()) + ".urdf",
                    out_bag = "/tmp/real_robots_" + std::to_string(getpid()) + "_out.bag";
  std::ofstream(urdf) << xml;
  const std::string command = std::string(MBK_MBK_PATH) + " bag " + in_bag + " --model " + urdf +
                              " --joint-accelerations /joint_accelerations" +
                              (floating ? " --base-odometry /odom" : "") + " --out " + out_bag +
                              " > /dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::map<Key, geometry_msgs::TransformStamped> bag_tf;
  std::map<double, mb_kinematics_msgs::BodyKinematicsArray> bag_kinematics;
  read_output_bag(out_bag, bag_tf, bag_kinematics);
  double tf_position = 0, tf_rotation = 0, motion = 0, acceleration = 0;
  size_t compared = 0;
  for (int i = 0; i < samples; ++i) {
    const ros::Time stamp = start + ros::Duration(i * 0.01);
    std::map<Key, geometry_msgs::TransformStamped> node_tf, from_bag;
    for (const auto& [key, t] : mine)
      if (key.second == stamp.toSec()) node_tf[key] = t;
    for (const auto& [key, t] : bag_tf)
      if (key.second == stamp.toSec()) from_bag[key] = t;
    EXPECT_EQ(node_tf.size(), from_bag.size()) << "sample " << i;
    compare(from_bag, node_tf, tf_position, tf_rotation);
    const auto node = kinematics.at(stamp);
    const auto bag = bag_kinematics.find(stamp.toSec());
    if (floating && i < 3 && node.empty()) continue;  // the base's acceleration not estimated yet
    ASSERT_EQ(node.size(), 1u) << "sample " << i;
    ASSERT_NE(bag, bag_kinematics.end()) << "sample " << i << " not in mbk bag's output";
    ASSERT_EQ(node[0].bodies.size(), bag->second.bodies.size());
    for (size_t k = 0; k < node[0].bodies.size(); ++k) {
      EXPECT_EQ(node[0].bodies[k].name, bag->second.bodies[k].name);
      body_difference(node[0].bodies[k], bag->second.bodies[k], motion, acceleration);
    }
    const auto& a = node[0].system;
    const auto& b = bag->second.system;
    EXPECT_TRUE(a.filled && b.filled);
    EXPECT_EQ(a.angular_momentum_known, b.angular_momentum_known);
    motion = std::max({motion, std::abs(a.mass - b.mass) / a.mass,
                       (vec(a.mass_center) - vec(b.mass_center)).norm(),
                       (vec(a.velocity) - vec(b.velocity)).norm(),
                       (vec(a.linear_momentum) - vec(b.linear_momentum)).norm() / a.mass,
                       (vec(a.angular_momentum) - vec(b.angular_momentum)).norm() / a.mass});
    acceleration = std::max(acceleration, (vec(a.acceleration) - vec(b.acceleration)).norm());
    ++compared;
  }
  std::printf(
      "  mbk bag vs node, %zu samples: tf %.1e m, %.1e rad; poses, velocities %.1e; "
      "accelerations %.1e\n",
      compared, tf_position, tf_rotation, motion, acceleration);
  EXPECT_GE(compared, static_cast<size_t>(samples - 3));
  for (const double e : {tf_position, tf_rotation, motion}) EXPECT_LT(e, 1e-12);
  // The joints' accelerations are given; a floating base's are estimated from the odometry, by
  // the node's online estimator and mbk bag's offline one (both 0 on this constant twist, up to
  // the rounding of the velocities they differentiate: 4e-12 measured).
  EXPECT_LT(acceleration, floating ? 1e-10 : 1e-12);
  for (const std::string& f : {in_bag, urdf, out_bag}) std::remove(f.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "real_robots_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
