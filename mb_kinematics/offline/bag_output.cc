#include "mb_kinematics/offline/bag_output.h"

#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "mb_kinematics/ros/body_kinematics_fill.h"

namespace mbk_offline {

BagOutput::BagOutput(const std::string& path, const mbk::Model& model, const std::string& prefix,
                     const std::string& base_frame)
    : model_(model),
      path_(path),
      bag_(std::make_unique<rosbag::Bag>()),
      frames_(model, prefix),
      base_frame_(base_frame) {
  try {
    bag_->open(path, rosbag::bagmode::Write);
  } catch (const rosbag::BagException& e) {
    abandon();
    throw std::invalid_argument(path + ": cannot write the bag (" + e.what() + ")");
  }
  mbk_ros::init_body_kinematics(model, base_frame.empty() ? frames_.root() : base_frame,
                                kinematics_);
}

BagOutput::~BagOutput() = default;

// A bag whose file refused a write cannot be closed or destroyed without writing (its index)
// and throwing again: it is kept aside, unclosed, for the rest of the process (reachable, so
// not reported as a leak); the caller removes or leaves the file (output_file.h).
void BagOutput::abandon() {
  static auto* abandoned = new std::vector<std::unique_ptr<rosbag::Bag>>;
  abandoned->push_back(std::move(bag_));
}

void BagOutput::fail(const rosbag::BagException& e) {
  abandon();
  throw std::runtime_error(path_ + ": write failed (" + e.what() + ")");
}

void BagOutput::write(double stamp, const mbk::JointState<double>& state,
                      const mbk::Data<double>& data, const mbk::BaseMotion* base) {
  if (!bag_) throw std::runtime_error(path_ + ": write after a failed write");
  try {
    write_sample(stamp, state, data, base);
  } catch (const rosbag::BagException& e) {
    fail(e);
  }
}

void BagOutput::write_sample(double stamp, const mbk::JointState<double>& state,
                             const mbk::Data<double>& data, const mbk::BaseMotion* base) {
  const ros::Time time(stamp);
  if (!static_written_) {
    tf2_msgs::TFMessage fixed;
    fixed.transforms = frames_.fixed();
    for (auto& t : fixed.transforms) t.header.stamp = time;
    if (!fixed.transforms.empty()) bag_->write("/tf_static", time, fixed);
    static_written_ = true;
  }
  mbk_ros::fill_body_kinematics(time, data, kinematics_);
  bag_->write("/body_kinematics", time, kinematics_);
  tf_.transforms = frames_.moving(state);
  if (base) {  // R -> the model's root frame
    geometry_msgs::TransformStamped t;
    t.header.frame_id = base_frame_;
    t.child_frame_id = frames_.root();
    t.transform.translation.x = base->position.x();
    t.transform.translation.y = base->position.y();
    t.transform.translation.z = base->position.z();
    const Eigen::Quaterniond q(base->rotation);
    t.transform.rotation.x = q.x();
    t.transform.rotation.y = q.y();
    t.transform.rotation.z = q.z();
    t.transform.rotation.w = q.w();
    tf_.transforms.push_back(t);
  }
  for (auto& t : tf_.transforms) t.header.stamp = time;
  if (!tf_.transforms.empty()) bag_->write("/tf", time, tf_);
}

void BagOutput::close() {
  if (!bag_) return;
  try {
    bag_->close();
  } catch (const rosbag::BagException& e) {
    fail(e);
  }
}

}  // namespace mbk_offline
