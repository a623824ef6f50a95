#include "mb_kinematics/ros/outputs/tf_output.h"

#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/messages/fields.h"

namespace mbk_ros {
namespace {

// The joint's relative transform: q_k + s_k in Bj, and SJK.
void set_transform(const mbk::Body& body, const mbk::JointMotion<double>& m,
                   geometry_msgs::Transform& out) {
  set_vector(body.joint.offset + m.translation, out.translation);
  set_quaternion(m.rotation, out.rotation);
}

}  // namespace

TfJoint tf_joint(const mbk::Model& model, int body) {
  const mbk::Joint& joint = model.bodies[body].joint;
  return {body, Eigen::Quaterniond(joint.rotation), mbk::translation_count(joint.type) > 0};
}

TfOutput::TfOutput(const OutputSetup& setup)
    : shown_(setup.model.body_count() + 1, 0),
      publisher_(setup.nh.advertise<tf2_msgs::TFMessage>("/tf", kSampleQueueSize)) {
  const mbk::Model& model = setup.model;
  // With ~base_odometry, body 1 is the base: R -> base comes from the odometry's source.
  const bool base_tf = setup.params.base_odometry.empty() || setup.params.publish_base_tf;
  for (int k = base_tf ? 1 : 2; k <= model.body_count(); ++k) {
    if (mbk::coordinate_count(model.bodies[k].joint.type) == 0) continue;
    moving_all_.push_back(k);
    parent_.push_back(setup.lower_frame(k));
    child_.push_back(setup.body_frame(k));
  }
  select(model, std::vector<char>(shown_.size(), 1), msg_.next());
}

// The transforms of the published bodies, their frames set (~missing_coordinates skip).
void TfOutput::select(const mbk::Model& model, const std::vector<char>& published,
                      tf2_msgs::TFMessage& msg) {
  moving_.clear();
  msg.transforms.clear();
  for (size_t i = 0; i < moving_all_.size(); ++i) {
    if (!published[moving_all_[i]]) continue;
    moving_.push_back(tf_joint(model, moving_all_[i]));
    msg.transforms.emplace_back();
    msg.transforms.back().header.frame_id = parent_[i];
    msg.transforms.back().child_frame_id = child_[i];
  }
  shown_ = published;
}

void fill_transforms(const mbk::Model& model, const mbk::JointState<double>& state,
                     const std::vector<TfJoint>& moving, const ros::Time& stamp,
                     std::vector<geometry_msgs::TransformStamped>& transforms) {
  mbk::JointMotion<double> m;
  for (size_t i = 0; i < moving.size(); ++i) {
    const mbk::Body& body = model.bodies[moving[i].body];
    const double* q = state.position.data() + body.q_index;
    geometry_msgs::Transform& out = transforms[i].transform;
    transforms[i].header.stamp = stamp;
    set_quaternion(mbk::joint_quaternion(body.joint, moving[i].offset, q), out.rotation);
    if (!moving[i].translates) {
      set_vector(body.joint.offset, out.translation);
      continue;
    }
    mbk::joint_motion<double>(body.joint, model.speeds, q, nullptr, m);
    set_vector(body.joint.offset + m.translation, out.translation);
  }
}

void TfOutput::publish(const ros::Time& stamp, const Sample& sample) {
  if (stamp == last_stamp_) return;  // tf2 rejects repeated stamps
  tf2_msgs::TFMessage& msg = msg_.next();
  if (sample.published != shown_) select(sample.model, sample.published, msg);
  if (moving_.empty()) return;
  last_stamp_ = stamp;
  fill_transforms(sample.model, sample.state, moving_, stamp, msg.transforms);
  msg_.publish(publisher_);
}

TfStaticOutput::TfStaticOutput(const OutputSetup& setup) {
  const mbk::Model& model = setup.model;
  std::vector<geometry_msgs::TransformStamped> fixed;
  mbk::JointMotion<double> m;
  for (int k = 1; k <= model.body_count(); ++k) {
    const mbk::Body& body = model.bodies[k];
    if (mbk::coordinate_count(body.joint.type) > 0) continue;
    mbk::joint_motion<double>(body.joint, model.speeds, nullptr, nullptr, m);
    geometry_msgs::TransformStamped t;
    t.header.stamp = ros::Time::now();
    t.header.frame_id = setup.lower_frame(k);
    t.child_frame_id = setup.body_frame(k);
    set_transform(body, m, t.transform);
    fixed.push_back(t);
  }
  if (!fixed.empty()) broadcaster_.sendTransform(fixed);
}

}  // namespace mbk_ros
