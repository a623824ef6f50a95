// load_monitor: counts the messages on joint_states, body_kinematics and /tf (per publishing
// node; not with ~tf false) whose stamp lies in a wall-clock window [~start, ~end] (seconds since
// the epoch), read from the serialized message without deserializing it; prints one line per
// count and exits ~grace seconds after ~end (for the samples of the window still on their way).
// Counted by stamp, not by time of arrival, a sample delayed more on one topic than on another
// at the window's edges is not taken for a lost one.
// scripts/node_load.sh's listener: it keeps body_kinematics and /tf subscribed, as a consumer
// would.
#include <ros/ros.h>
#include <topic_tools/shape_shifter.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace {

struct Window {
  double start = 0, end = 0;
  bool inside(double t) const { return t >= start && t <= end; }
};

// The stamp (std_msgs/Header: seq, then stamp) at byte `offset` of the message as serialized:
// 0 for a message that starts with a Header, 4 for tf2_msgs/TFMessage (the length of its
// array of stamped transforms first); 0 if there is none.
double stamp(const topic_tools::ShapeShifter& msg, size_t offset) {
  static std::vector<uint8_t> buffer;
  buffer.resize(msg.size());
  ros::serialization::OStream out(buffer.data(), buffer.size());
  msg.write(out);
  if (buffer.size() < offset + 12) return 0;
  uint32_t sec = 0, nsec = 0;  // little endian, as ROS serializes
  std::memcpy(&sec, buffer.data() + offset + 4, 4);
  std::memcpy(&nsec, buffer.data() + offset + 8, 4);
  return ros::Time(sec, nsec).toSec();
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "load_monitor");
  ros::NodeHandle nh, pnh("~");
  Window window;
  pnh.getParam("start", window.start);
  pnh.getParam("end", window.end);
  std::map<std::string, long> counts;  // topic (and publisher, for /tf) -> messages
  using Event = ros::MessageEvent<const topic_tools::ShapeShifter>;
  const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
  auto subscribe = [&](const std::string& topic, bool per_publisher, size_t offset) {
    ros::SubscribeOptions options;
    options.initByFullCallbackType<const Event&>(
        topic, 1000, [&, topic, per_publisher, offset](const Event& event) {
          if (window.inside(stamp(*event.getConstMessage(), offset)))
            ++counts[per_publisher ? topic + " from " + event.getPublisherName() : topic];
        });
    options.transport_hints = hints;
    return nh.subscribe(options);
  };
  const double grace = pnh.param("grace", 1.0);
  ros::Subscriber js = subscribe("joint_states", false, 0);
  ros::Subscriber bk = subscribe("body_kinematics", false, 0);
  ros::Subscriber tf = pnh.param("tf", true) ? subscribe("/tf", true, 4) : ros::Subscriber();
  ros::WallTimer stop = nh.createWallTimer(
      ros::WallDuration(std::max(0.1, window.end - ros::WallTime::now().toSec() + grace)),
      [](const ros::WallTimerEvent&) { ros::shutdown(); }, true);
  ros::spin();
  for (const auto& c : counts)
    std::printf("%s: %ld messages, %.1f Hz\n", c.first.c_str(), c.second,
                c.second / (window.end - window.start));
  return 0;
}
