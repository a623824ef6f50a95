#include "mb_kinematics/offline/bag_output.h"

#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "mb_kinematics/messages/body_kinematics.h"

namespace mbk_offline {
BagOutput::BagOutput(const std::string& path, const mbk::Model& model, const std::string& prefix,
                     const std::string& base_frame, const mbk::Model& kinematics_model)
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
                                     base_frame.empty() ? names_.root() : base_frame, kinematics_);
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
  const ros::Time time(stamp);
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

void with_base_body(const mbk::Model& base_model, const mbk::Data<double>& data,
                    mbk::Data<double>& out) {
  for (size_t k = 0; k < data.rotation.size(); ++k) {  // index 0: the root frame's motion
    out.rotation[k + 1] = data.rotation[k];
    out.origin[k + 1] = data.origin[k];
    out.omega[k + 1] = data.omega[k];
    out.alpha[k + 1] = data.alpha[k];
    out.origin_velocity[k + 1] = data.origin_velocity[k];
    out.origin_acceleration[k + 1] = data.origin_acceleration[k];
    out.mass_center[k + 1] = data.mass_center[k];
    out.mass_center_velocity[k + 1] = data.mass_center_velocity[k];
    out.mass_center_acceleration[k + 1] = data.mass_center_acceleration[k];
  }
  const mbk::Vec3<double> r = out.rotation[1] * base_model.bodies[1].mass_center;
  const mbk::Vec3<double>&w = out.omega[1], &alpha = out.alpha[1];
  out.mass_center[1] = out.origin[1] + r;  // p = O + S0K r
  out.mass_center_velocity[1] = out.origin_velocity[1] + w.cross(r);
  out.mass_center_acceleration[1] =
      out.origin_acceleration[1] + alpha.cross(r) + w.cross(w.cross(r));
}

}  // namespace mbk_offline
