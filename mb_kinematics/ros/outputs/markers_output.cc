#include "mb_kinematics/ros/outputs/markers_output.h"

#include <ros/console.h>

#include "mb_kinematics/messages/body_kinematics.h"

namespace mbk_ros {

MarkersOutput::MarkersOutput(const OutputSetup& setup)
    : publisher_(
          setup.nh.advertise<visualization_msgs::MarkerArray>("body_kinematics/markers", 10)),
      shown_(setup.model.body_count() + 1, 1) {
  mbk_messages::init_body_kinematics(setup.model, setup.frame, kinematics_);
}

void MarkersOutput::publish(const ros::Time& stamp, const Sample& sample) {
  if (sample.published != shown_) {  // the bodies of body_kinematics
    mbk_messages::select_body_kinematics(sample.model, sample.published, kinematics_);
    shown_ = sample.published;
  }
  mbk_messages::fill_body_kinematics(stamp, sample.data, kinematics_);
  const mbk::BodySelection drawn = mbk::select_bodies(kinematics_, {}, style_);
  lengths_.update(stamp.toSec(), drawn, mbk::kDefaultLengthFraction, style_);
  const Glyphs glyphs = mbk::make_glyphs(drawn, style_);
  if (glyphs.over_max_bodies > 0)
    ROS_WARN_STREAM_ONCE("body_kinematics/markers: " << glyphs.over_max_bodies
                                                     << " bodies not drawn: at most "
                                                     << style_.max_bodies << " per message");
  publisher_.publish(make_marker_array(glyphs, style_, kinematics_.header));
}

}  // namespace mbk_ros
