#include "mb_kinematics/offline/bag_input.h"

#include <mb_kinematics_msgs/JointAccelerations.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/JointState.h>

#include <cmath>
#include <fstream>
#include <map>
#include <stdexcept>

namespace mbk_offline {
namespace {

// topic -> type of every connection in the bag.
std::map<std::string, std::string> bag_topics(const rosbag::Bag& bag) {
  std::map<std::string, std::string> topics;
  rosbag::View all(bag);
  for (const rosbag::ConnectionInfo* c : all.getConnections()) topics[c->topic] = c->datatype;
  return topics;
}

std::string list(const std::map<std::string, std::string>& topics) {
  if (topics.empty()) return "the bag has no topics";
  std::string out = "the bag has ";
  bool first = true;
  for (const auto& t : topics)
    out += (first ? "" : ", ") + t.first + " (" + t.second + ")", first = false;
  return out;
}

void require(const std::map<std::string, std::string>& topics, const std::string& path,
             const std::string& topic, const std::string& type) {
  auto it = topics.find(topic);
  if (it == topics.end())
    throw std::invalid_argument(path + ": no topic '" + topic + "'; " + list(topics));
  if (it->second != type)
    throw std::invalid_argument(path + ": topic '" + topic + "' is " + it->second + ", not " +
                                type);
}

double stamp_of(const std_msgs::Header& header, const rosbag::MessageInstance& m) {
  return header.stamp.isZero() ? m.getTime().toSec() : header.stamp.toSec();  // as the node
}

void add_odometry(const nav_msgs::Odometry& o, double t, const std::string& where,
                  BaseOdometry& base, mbk::DropLog& log) {
  mbk::BaseSample s;
  s.t = t;
  const auto& p = o.pose.pose;
  s.position << p.position.x, p.position.y, p.position.z;
  s.orientation =
      Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
  s.linear << o.twist.twist.linear.x, o.twist.twist.linear.y, o.twist.twist.linear.z;
  s.angular << o.twist.twist.angular.x, o.twist.twist.angular.y, o.twist.twist.angular.z;
  const double norm = s.orientation.norm();
  if (!std::isfinite(t) || !s.position.allFinite() || !s.linear.allFinite() ||
      !s.angular.allFinite() || !std::isfinite(norm) || norm < 1e-6)
    return log.note("base odometry ignored", where + ": NaN/Inf or a zero quaternion");
  if (!base.samples.empty() && t <= base.samples.back().t)
    return log.note("base odometry ignored", where + ": stamp not after the previous one");
  s.orientation.normalize();
  if (base.frame.empty()) base.frame = o.header.frame_id;
  base.samples.push_back(s);
}

}  // namespace

void read_bag(const std::string& path, const BagTopics& topics, mbk::RecordingBuilder& builder,
              BaseOdometry& base, const std::function<void(long, long)>& progress) {
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagUnindexedException&) {
    throw std::invalid_argument(path +
                                ": the bag has no index (truncated, or its recording was "
                                "cut short): run `rosbag reindex " +
                                path + "` first");
  } catch (const rosbag::BagException& e) {
    std::ifstream in(path, std::ios::binary);
    char magic[13] = {};
    in.read(magic, sizeof magic);
    if (std::string(magic, sizeof magic) == "#ROSBAG V2.0\n")  // a bag, damaged or cut short
      throw std::invalid_argument(path + ": not a readable bag (" + e.what() +
                                  "): truncated or corrupt; `rosbag reindex " + path +
                                  "` may recover it");
    throw std::invalid_argument(path + ": not a readable bag (" + e.what() + ")");
  }
  const std::map<std::string, std::string> present = bag_topics(bag);
  require(present, path, topics.joint_states, "sensor_msgs/JointState");
  std::vector<std::string> wanted = {topics.joint_states};
  if (!topics.joint_accelerations.empty()) {
    require(present, path, topics.joint_accelerations, "mb_kinematics_msgs/JointAccelerations");
    wanted.push_back(topics.joint_accelerations);
  }
  if (!topics.base_odometry.empty()) {
    require(present, path, topics.base_odometry, "nav_msgs/Odometry");
    wanted.push_back(topics.base_odometry);
  }
  rosbag::View view(bag, rosbag::TopicQuery(wanted));
  const long total = view.size();
  long done = 0;
  try {
    for (const rosbag::MessageInstance& m : view) {
      if (++done % 1024 == 0) progress(done, total);
      const std::string where = m.getTopic() + " message " + std::to_string(done);
      if (m.getTopic() == topics.joint_states) {
        const auto js = m.instantiate<sensor_msgs::JointState>();
        builder.add(stamp_of(js->header, m), js->name, js->position, js->velocity, where);
      } else if (m.getTopic() == topics.base_odometry) {
        const auto o = m.instantiate<nav_msgs::Odometry>();
        add_odometry(*o, stamp_of(o->header, m), where, base, builder.log());
      } else {
        const auto a = m.instantiate<mb_kinematics_msgs::JointAccelerations>();
        builder.add_accelerations(stamp_of(a->header, m), a->name, a->acceleration, where);
      }
    }
  } catch (const std::exception& e) {  // rosbag's and roscpp's serialization exceptions
    builder.log().drop("rest of the bag unreadable", path + ": after message " +
                                                         std::to_string(done) + " of " +
                                                         std::to_string(total) + ": " + e.what());
  }
  progress(total, total);
}

}  // namespace mbk_offline
