// load_monitor: counts, over a wall-clock window [~start, ~end] (seconds since the epoch), the
// messages on joint_states, body_kinematics and /tf (per publishing node; not with ~tf false),
// without deserializing them; prints one line per count and exits after ~end.
// scripts/node_load.sh's listener: it keeps body_kinematics and /tf subscribed, as a consumer
// would.
#include <ros/ros.h>
#include <topic_tools/shape_shifter.h>

#include <cstdio>
#include <map>
#include <string>

namespace {

struct Window {
  double start = 0, end = 0;
  bool inside() const {
    const double now = ros::WallTime::now().toSec();
    return now >= start && now <= end;
  }
};

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
  auto subscribe = [&](const std::string& topic, bool per_publisher) {
    ros::SubscribeOptions options;
    options.initByFullCallbackType<const Event&>(
        topic, 1000, [&, topic, per_publisher](const Event& event) {
          if (window.inside())
            ++counts[per_publisher ? topic + " from " + event.getPublisherName() : topic];
        });
    options.transport_hints = hints;
    return nh.subscribe(options);
  };
  ros::Subscriber js = subscribe("joint_states", false);
  ros::Subscriber bk = subscribe("body_kinematics", false);
  ros::Subscriber tf = pnh.param("tf", true) ? subscribe("/tf", true) : ros::Subscriber();
  ros::WallTimer stop = nh.createWallTimer(
      ros::WallDuration(std::max(0.1, window.end - ros::WallTime::now().toSec() + 0.2)),
      [](const ros::WallTimerEvent&) { ros::shutdown(); }, true);
  ros::spin();
  for (const auto& c : counts)
    std::printf("%s: %ld messages, %.1f Hz\n", c.first.c_str(), c.second,
                c.second / (window.end - window.start));
  return 0;
}
