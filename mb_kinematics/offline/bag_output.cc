#include "mb_kinematics/offline/bag_output.h"

#include <stdexcept>

namespace mbk_offline {

BagOutput::BagOutput(const std::string& path, const mbk::Model& model, const std::string& prefix)
    : model_(model), path_(path), frames_(model, prefix) {
  try {
    bag_.open(path, rosbag::bagmode::Write);
  } catch (const rosbag::BagException& e) {
    throw std::invalid_argument(path + ": cannot write the bag (" + e.what() + ")");
  }
  init_kinematics_msg(model, frames_.root(), kinematics_);
}

void BagOutput::write(double stamp, const mbk::JointState<double>& state,
                      const mbk::Data<double>& data) {
  const ros::Time time(stamp);
  if (!static_written_) {
    tf2_msgs::TFMessage fixed;
    fixed.transforms = frames_.fixed();
    for (auto& t : fixed.transforms) t.header.stamp = time;
    if (!fixed.transforms.empty()) bag_.write("/tf_static", time, fixed);
    static_written_ = true;
  }
  kinematics_.header.stamp = time;
  fill_kinematics_msg(model_, data, kinematics_);
  bag_.write("/body_kinematics", time, kinematics_);
  tf_.transforms = frames_.moving(state);
  for (auto& t : tf_.transforms) t.header.stamp = time;
  if (!tf_.transforms.empty()) bag_.write("/tf", time, tf_);
}

void BagOutput::close() {
  try {
    bag_.close();
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error(path_ + ": write failed (" + e.what() + ")");
  }
}

}  // namespace mbk_offline
