// rviz display `mb_kinematics/BodyKinematics` for mb_kinematics_msgs/BodyKinematicsArray (in the
// manner of rviz's own screw_display): per body arrows for the mass-center velocity and
// acceleration at G_k, omega and alpha as arrows with a circular arc for the sense of rotation,
// a sphere at each mass center, optionally the skeleton. Bodies with invalid floats are skipped
// with a status warning; bodies lighter than a fraction of the heaviest (masses from the
// robot_description URDF) or named by a regex are left out. Auto Frame: on the first message,
// a Fixed Frame that tf does not know becomes the message's frame, and the camera frames the
// bodies. The whole system (the message's `system`, when filled): a larger sphere
// at its mass center G, G's velocity and acceleration, G's projection on R's x-y plane.
// Bounded whatever the messages hold (doc/rviz.md#limits): at most Max Bodies bodies drawn per
// message; bodies beyond mbk::kMaxGlyphDistance, and names too long for a user's pattern, left
// out; each with a status warning.
#pragma once

#ifndef Q_MOC_RUN
#include <OgreQuaternion.h>
#include <OgreVector3.h>
#include <mb_kinematics_msgs/BodyKinematicsArray.h>
#include <message_filters/connection.h>
#include <ros/time.h>
#include <rviz/message_filter_display.h>

#include <array>
#include <boost/circular_buffer.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "mb_kinematics/viz/auto_lengths.h"
#include "mb_kinematics/viz/glyphs.h"
#endif

namespace rviz {
class BoolProperty;
class ColorProperty;
class FloatProperty;
class IntProperty;
class StringProperty;
}  // namespace rviz

namespace mbk_rviz {

class BodyKinematicsVisual;
class SystemKinematicsVisual;

class BodyKinematicsDisplay
    : public rviz::MessageFilterDisplay<mb_kinematics_msgs::BodyKinematicsArray> {
  Q_OBJECT
 public:
  BodyKinematicsDisplay();
  ~BodyKinematicsDisplay() override;

 protected:
  void onInitialize() override;
  void reset() override;
  void onEnable() override;
  void update(float wall_dt, float ros_dt) override;

 private Q_SLOTS:
  void updateStyle();
  void updateFilter();
  void updateHistoryLength();
  void updateMasses();
  void updateAutoFrame();

 private:
  struct QuantityProperties {
    rviz::BoolProperty* show;
    rviz::FloatProperty* scale;
    rviz::ColorProperty* color;
  };
  // Messages are kept as they come and drawn once per frame (only the newest History Length
  // of them), so a fast topic does not queue up drawing work and lag behind tf.
  void processMessage(const mb_kinematics_msgs::BodyKinematicsArray::ConstPtr& msg) override;
  void draw(const mb_kinematics_msgs::BodyKinematicsArray& msg);
  void makeQuantityProperties(int q, const QColor& color, double scale, const QString& unit);
  // Auto Scale: the scales of the message stamped `time` (s), mbk::AutoLengths' rule.
  void autoScale(double time, const mbk::BodySelection& drawn);
  void reportSkipped(const mbk::Glyphs& glyphs);  // bodies left out, a status per reason
  void reportLeftOut(const char* status, size_t count, const QString& what);
  void showLegend();
  std::shared_ptr<BodyKinematicsVisual> nextVisual();
  void makeSystemProperties();
  void makeSelectionProperties();
  // Auto Frame: the Fixed Frame becomes the message's frame when tf does not know it. Every
  // message, before the tf filter (which holds back those it cannot transform to the Fixed Frame).
  void adoptFrame(const mb_kinematics_msgs::BodyKinematicsArray::ConstPtr& msg);
  // `drawn`: the bodies drawn (BodySelection::drawn); the view then follows followFrame(msg).
  void frameCamera(const std::vector<mbk::GlyphBody>& drawn,
                   const mb_kinematics_msgs::BodyKinematicsArray& msg);
  // The frame Auto Frame's view follows: rviz's ~follow_frame (mb_kinematics.launch's
  // follow_frame), else, while the view's Target Frame is the Fixed Frame (the config names
  // none), the message's first body (the base, on a floating one), as tf names it (with the
  // node's ~frame_prefix); "" for none or a frame tf does not know.
  std::string followFrame(const mb_kinematics_msgs::BodyKinematicsArray& msg,
                          const QString& target) const;
  // The whole system's visual, placed at G (in double, as the bodies' anchor).
  void drawSystem(const mb_kinematics_msgs::BodyKinematicsArray& msg);

  std::array<QuantityProperties, mbk::GlyphQuantity::kCount> quantity_;
  rviz::BoolProperty *auto_scale_, *mass_centers_, *skeleton_;
  rviz::FloatProperty *length_fraction_, *alpha_, *width_, *arc_radius_, *sphere_radius_;
  rviz::ColorProperty *mass_center_color_, *skeleton_color_;
  rviz::StringProperty *filter_, *exclude_, *robot_description_;
  rviz::FloatProperty* min_mass_fraction_;
  rviz::BoolProperty* auto_frame_;
  rviz::IntProperty *history_length_, *max_bodies_;

  std::map<std::string, double> masses_;  // link name -> kg, from Robot Description
  ros::WallTime masses_tried_;
  bool framed_ = false;  // the camera has framed the bodies since Auto Frame was turned on
  std::vector<QString> legend_rows_;  // the legend's status names (showLegend)
  message_filters::Connection frame_connection_;

  mbk::GlyphStyle style_;
  bool filter_ok_ = true;
  mbk::AutoLengths auto_lengths_;
  boost::circular_buffer<std::shared_ptr<BodyKinematicsVisual>> visuals_;
  std::vector<mb_kinematics_msgs::BodyKinematicsArray::ConstPtr> pending_;

  // The whole system (doc/method.md 9): the newest message's, one visual.
  rviz::BoolProperty *system_, *system_sphere_, *system_velocity_, *system_acceleration_,
      *system_projection_;
  rviz::ColorProperty* system_color_;
  rviz::FloatProperty* system_radius_;
  std::unique_ptr<SystemKinematicsVisual> system_visual_;
};

}  // namespace mbk_rviz
