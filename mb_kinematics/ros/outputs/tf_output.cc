#include "mb_kinematics/ros/outputs/tf_output.h"

namespace mbk_ros {

TfOutput::TfOutput(const OutputSetup& setup)
    : prefix_(setup.params.frame_prefix),
      frame_(setup.frame),
      shown_(setup.model.body_count() + 1, 0),
      publisher_(setup.nh.advertise<tf2_msgs::TFMessage>("/tf", kSampleQueueSize)) {
  // With ~base_odometry, body 1 is the base: R -> base comes from the odometry's source.
  const bool base_tf = setup.params.base_odometry.empty() || setup.params.publish_base_tf;
  moving_all_ = mbk_messages::moving_bodies(setup.model, base_tf ? 1 : 2);
  select(setup.model, std::vector<char>(shown_.size(), 1), msg_.reshape());
  const mbk_messages::FrameNames names(setup.model, prefix_, frame_);
  std::vector<std::string> frames;
  for (const int k : moving_all_) frames.push_back(names.body(k));
  watch_ = std::make_unique<TfDuplicateWatch>(setup.nh, frames);
}

// The transforms of the published bodies, their frames set (~missing_coordinates skip).
void TfOutput::select(const mbk::Model& model, const std::vector<char>& published,
                      tf2_msgs::TFMessage& msg) {
  std::vector<int> bodies;
  for (const int k : moving_all_)
    if (published[k]) bodies.push_back(k);
  mbk_messages::init_transforms(model, mbk_messages::FrameNames(model, prefix_, frame_), bodies,
                                moving_, msg.transforms);
  shown_ = published;
}

void TfOutput::publish(const ros::Time& stamp, const Sample& sample) {
  if (stamp == last_stamp_) return;  // tf2 rejects repeated stamps
  if (sample.published != shown_) select(sample.model, sample.published, msg_.reshape());
  tf2_msgs::TFMessage& msg = msg_.next();
  if (moving_.empty()) return;
  last_stamp_ = stamp;
  mbk_messages::fill_transforms(sample.model, sample.state, moving_, stamp, msg.transforms);
  msg_.publish(publisher_);
}

TfStaticOutput::TfStaticOutput(const OutputSetup& setup) {
  const std::vector<geometry_msgs::TransformStamped> fixed =
      mbk_messages::fixed_transforms(setup.model, setup.frames(), ros::Time::now());
  if (!fixed.empty()) broadcaster_.sendTransform(fixed);
}

}  // namespace mbk_ros
