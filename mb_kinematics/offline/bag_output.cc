#include "mb_kinematics/offline/bag_output.h"

#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "mb_kinematics/messages/body_kinematics.h"

namespace mbk_offline {
BagOutput::BagOutput(const std::string& path, const mbk::Model& model, const std::string& prefix,
                     const std::string& base_frame, const mbk::Model& kinematics_model,
                     const std::vector<std::string>& missing_segments)
    : model_(model),
      kinematics_model_(kinematics_model),
      path_(path),
      bag_(std::make_unique<rosbag::Bag>()),
      names_(model, prefix, mbk_messages::model_frame(model, prefix)) {
  try {
    bag_->open(path, rosbag::bagmode::Write);
  } catch (const rosbag::BagException& e) {
    abandon();
    throw std::invalid_argument(path + ": cannot write the bag (" + e.what() + ")");
  }
  mbk_messages::init_body_kinematics(kinematics_model,
                                     base_frame.empty() ? names_.root() : base_frame, kinematics_,
                                     missing_segments);
  mbk_messages::init_transforms(model, names_, mbk_messages::moving_bodies(model), moving_,
                                tf_.transforms, base_frame);
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
  // origin_ + stamp to the nanosecond (the caller checked it is a bag's: TIME_MIN to TIME_MAX).
  const double whole = std::floor(stamp);
  const long long ns = std::llround((stamp - whole) * 1e9);
  const double seconds = origin_ + whole + (ns == 1000000000);
  const ros::Time time(static_cast<std::uint32_t>(seconds),
                       static_cast<std::uint32_t>(ns == 1000000000 ? 0 : ns));
  if (!static_written_) {
    tf2_msgs::TFMessage fixed;
    fixed.transforms = mbk_messages::fixed_transforms(model_, names_, time);
    if (!fixed.transforms.empty()) bag_->write("/tf_static", time, fixed);
    static_written_ = true;
  }
  mbk_messages::fill_kinematics(time, kinematics_model_, data, true,
                                kinematics_);  // every body: complete
  bag_->write("/body_kinematics", time, kinematics_);
  mbk_messages::fill_transforms(model_, state, moving_, time, tf_.transforms, base);
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
