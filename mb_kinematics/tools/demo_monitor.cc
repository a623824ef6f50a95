// demo_monitor: prints a short live summary of body_kinematics per body every ~period seconds
// (mass center position, |omega|, |alpha|, |v_G|, |a_G|, all in R) and exits after ~duration
// seconds (0: until Ctrl-C). Used by scripts/demo.sh.
#include <mb_kinematics_msgs/BodyKinematicsArray.h>
#include <ros/ros.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace {

template <typename V>
double norm(const V& v) {
  return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

mb_kinematics_msgs::BodyKinematicsArray::ConstPtr latest;
long received = 0;

void on_kinematics(const mb_kinematics_msgs::BodyKinematicsArray::ConstPtr& msg) {
  latest = msg;
  ++received;
}

void print(double elapsed, double period) {
  if (!latest) {
    std::printf("[%5.1f s] waiting for body_kinematics ...\n", elapsed);
    std::fflush(stdout);
    return;
  }
  std::printf("[%5.1f s] body_kinematics at %.1f Hz, frame %s, stamp %.3f\n", elapsed,
              received / period, latest->header.frame_id.c_str(), latest->header.stamp.toSec());
  std::printf("  %3s %-16s %3s %26s %9s %9s %9s %9s\n", "k", "body", "L", "mass center in R (m)",
              "|w| 1/s", "|al| 1/s2", "|v| m/s", "|a| m/s2");
  int hidden = 0;
  for (const auto& b : latest->bodies) {
    if (b.name.find("__") != std::string::npos) {  // links inside a ball/free joint (mbk urdf)
      ++hidden;
      continue;
    }
    std::printf("  %3u %-16s %3u %8.3f %8.3f %8.3f %9.3f %9.3f %9.3f %9.3f\n", b.index,
                b.name.c_str(), b.lower_body, b.mass_center.x, b.mass_center.y, b.mass_center.z,
                norm(b.twist.angular), norm(b.accel.angular), norm(b.twist.linear),
                norm(b.accel.linear));
  }
  if (hidden)
    std::printf("  (%d massless links inside ball and free joints, named B__x, not shown)\n",
                hidden);
  std::fflush(stdout);
  received = 0;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "demo_monitor");
  ros::NodeHandle nh, pnh("~");
  const double period = pnh.param("period", 1.0), duration = pnh.param("duration", 0.0);
  ros::Subscriber sub = nh.subscribe("body_kinematics", 10, on_kinematics);
  const ros::WallTime start = ros::WallTime::now();
  ros::WallTimer timer =
      nh.createWallTimer(ros::WallDuration(period), [&](const ros::WallTimerEvent&) {
        const double elapsed = (ros::WallTime::now() - start).toSec();
        print(elapsed, period);
        if (duration > 0 && elapsed >= duration - 1e-3) ros::shutdown();
      });
  ros::spin();
  return 0;
}
