#include "mb_kinematics/rviz/body_kinematics_display.h"

#include <OgreCamera.h>
#include <OgreSceneNode.h>
#include <ros/console.h>
#include <ros/init.h>
#include <ros/node_handle.h>
#include <rviz/frame_manager.h>
#include <rviz/properties/bool_property.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/int_property.h>
#include <rviz/properties/string_property.h>
#include <rviz/properties/tf_frame_property.h>
#include <rviz/view_controller.h>
#include <rviz/view_manager.h>
#include <rviz/visualization_manager.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <pluginlib/class_list_macros.hpp>
#include <stdexcept>

#include "mb_kinematics/io/urdf_masses.h"
#include "mb_kinematics/rviz/body_kinematics_visual.h"
#include "mb_kinematics/rviz/system_kinematics_visual.h"
#include "mb_kinematics/viz/glyph_bodies.h"
#include "mb_kinematics/viz/legend.h"
#include "mb_kinematics/viz/local_glyphs.h"

namespace mbk_rviz {
namespace {

QColor qcolor(const mbk::Rgba& c) { return QColor::fromRgbF(c.r, c.g, c.b); }

mbk::Rgba rgba(const QColor& c) {
  return {static_cast<float>(c.redF()), static_cast<float>(c.greenF()),
          static_cast<float>(c.blueF()), 1.0f};
}

const char* const kTitles[mbk::GlyphQuantity::kCount] = {
    "Velocity", "Acceleration", "Angular Velocity", "Angular Acceleration"};
const char* const kWhat[mbk::GlyphQuantity::kCount] = {
    "velocity of each mass center G_k", "acceleration of each mass center G_k",
    "angular velocity omega_k of each body (arrow and arc)",
    "angular acceleration alpha_k of each body (arrow and arc)"};

constexpr double kMinCameraDistance = 1.0;  // m, for a robot of a single point

// A pose at `p` (in R), R's orientation: what FrameManager::transform composes with R's pose in
// the Fixed Frame in double, as rviz's own displays place their scene nodes.
geometry_msgs::Pose pose(const mbk::Vec3<double>& p) {
  geometry_msgs::Pose out;
  out.position.x = p.x();
  out.position.y = p.y();
  out.position.z = p.z();
  out.orientation.w = 1;
  return out;
}

}  // namespace

BodyKinematicsDisplay::BodyKinematicsDisplay() {
  const mbk::GlyphStyle d;
  const char* units[mbk::GlyphQuantity::kCount] = {"m per m/s", "m per m/s^2", "m per rad/s",
                                                   "m per rad/s^2"};
  for (int q = 0; q < mbk::GlyphQuantity::kCount; ++q)
    makeQuantityProperties(q, qcolor(d.color[q]), d.scale[q], units[q]);
  auto_scale_ = new rviz::BoolProperty(
      "Auto Scale", true,
      "Scale each quantity so that its longest arrow (its largest value over the last seconds, "
      "robustly) is Length Fraction of the robot's size (the Scale properties are then not "
      "used).",
      this, SLOT(updateStyle()));
  length_fraction_ = new rviz::FloatProperty(
      "Length Fraction", mbk::kDefaultLengthFraction,
      "Length of each quantity's longest arrow, as a fraction of the robot's size (the diagonal "
      "of the box around its joint points and mass centers).",
      auto_scale_, SLOT(updateStyle()), this);
  length_fraction_->setMin(0);
  mass_centers_ = new rviz::BoolProperty("Mass Centers", true, "A sphere at each mass center.",
                                         this, SLOT(updateStyle()));
  mass_center_color_ =
      new rviz::ColorProperty("Color", qcolor(d.mass_center_color), "Color of the spheres.",
                              mass_centers_, SLOT(updateStyle()), this);
  sphere_radius_ = new rviz::FloatProperty("Radius", d.sphere_radius, "Sphere radius (m).",
                                           mass_centers_, SLOT(updateStyle()), this);
  skeleton_ = new rviz::BoolProperty(
      "Skeleton", false, "Lines between the joint points O_k of each body and its lower body.",
      this, SLOT(updateStyle()));
  skeleton_color_ =
      new rviz::ColorProperty("Color", qcolor(d.skeleton_color), "Color of the lines.", skeleton_,
                              SLOT(updateStyle()), this);
  width_ = new rviz::FloatProperty("Width", d.width, "Arrow shaft diameter (m).", this,
                                   SLOT(updateStyle()));
  arc_radius_ = new rviz::FloatProperty("Arc Radius", d.arc_radius,
                                        "Radius (m) of the arcs of omega and alpha.", this,
                                        SLOT(updateStyle()));
  alpha_ = new rviz::FloatProperty("Alpha", 1.0, "0 is fully transparent, 1.0 is fully opaque.",
                                   this, SLOT(updateStyle()));
  alpha_->setMin(0);
  alpha_->setMax(1);
  filter_ = new rviz::StringProperty(
      "Body Filter", mbk::kDefaultBodyFilter,
      "Regular expression (ECMAScript); bodies whose name it matches are drawn. The default "
      "leaves out the massless links <body>__<coord> of expanded ball and free joints.",
      this, SLOT(updateFilter()));
  makeSelectionProperties();
  history_length_ = new rviz::IntProperty("History Length", 1, "Number of messages drawn.", this,
                                          SLOT(updateHistoryLength()));
  history_length_->setMin(1);
  history_length_->setMax(100);
  max_bodies_ = new rviz::IntProperty(
      "Max Bodies", static_cast<int>(mbk::kDefaultMaxBodies),
      "At most this many bodies are drawn per message (the first ones of the message that pass "
      "the filters); the others are counted in a status warning. The display holds some ten "
      "objects per body drawn, times History Length.",
      this, SLOT(updateStyle()));
  max_bodies_->setMin(0);
  makeSystemProperties();
}

BodyKinematicsDisplay::~BodyKinematicsDisplay() { frame_connection_.disconnect(); }

void BodyKinematicsDisplay::makeSelectionProperties() {
  exclude_ = new rviz::StringProperty(
      "Exclude Bodies", "",
      "Regular expression (ECMAScript); bodies whose name it matches are left out, e.g. "
      "'finger|_tip$' or a list 'a|b|c'. Empty: none.",
      this, SLOT(updateFilter()));
  min_mass_fraction_ = new rviz::FloatProperty(
      "Min Mass Fraction", mbk::kDefaultMinMassFraction,
      "Bodies lighter than this fraction of the heaviest body are left out (sensor frames, "
      "fingers, dummy links). Masses come from Robot Description; 0 draws every body.",
      this, SLOT(updateStyle()));
  min_mass_fraction_->setMin(0);
  min_mass_fraction_->setMax(1);
  robot_description_ = new rviz::StringProperty(
      "Robot Description", "robot_description",
      "Parameter holding the URDF the masses are read from (as RobotModel's).", this,
      SLOT(updateMasses()));
  auto_frame_ = new rviz::BoolProperty(
      "Auto Frame", true,
      "Whenever tf does not know the Fixed Frame, set it to the messages' frame (the model's "
      "root link with the node's ~frame_prefix, or the odometry frame with ~base_odometry); on "
      "the first message drawn, point the camera at the bodies from a distance that fits them. "
      "Turn off to keep your own Fixed Frame and view.",
      this, SLOT(updateAutoFrame()));
}

void BodyKinematicsDisplay::makeQuantityProperties(int q, const QColor& color, double scale,
                                                   const QString& unit) {
  QuantityProperties& p = quantity_[q];
  p.show = new rviz::BoolProperty(kTitles[q], true, QString("Show the ") + kWhat[q] + ".", this,
                                  SLOT(updateStyle()));
  p.scale = new rviz::FloatProperty("Scale", scale, "Arrow length (" + unit + ").", p.show,
                                    SLOT(updateStyle()), this);
  p.scale->setMin(0);
  p.color = new rviz::ColorProperty("Color", color, "Color of the arrows.", p.show,
                                    SLOT(updateStyle()), this);
}

void BodyKinematicsDisplay::makeSystemProperties() {
  const SystemStyle d;
  system_ = new rviz::BoolProperty(
      "System Mass Center", true,
      "The mass center G of the whole system, its velocity, acceleration and ground projection "
      "(when the node fills the message's system field); each child shows or hides its part.",
      this, SLOT(updateStyle()));
  system_sphere_ =
      new rviz::BoolProperty("Sphere", true, "A sphere at G, larger than the bodies' mass centers.",
                             system_, SLOT(updateStyle()), this);
  system_color_ = new rviz::ColorProperty(
      "Color", QColor::fromRgbF(d.color.r, d.color.g, d.color.b),
      "Color of the sphere and of its projection.", system_, SLOT(updateStyle()), this);
  system_radius_ = new rviz::FloatProperty("Radius", d.radius, "Sphere radius (m).", system_,
                                           SLOT(updateStyle()), this);
  system_radius_->setMin(0);
  system_velocity_ = new rviz::BoolProperty(
      "Velocity", true, "The velocity of G (Velocity's color and scale, twice as wide).", system_,
      SLOT(updateStyle()), this);
  system_acceleration_ = new rviz::BoolProperty(
      "Acceleration", true,
      "The acceleration of G (Acceleration's color and scale, twice as wide).", system_,
      SLOT(updateStyle()), this);
  system_projection_ = new rviz::BoolProperty("Ground Projection", true,
                                              "G's projection on the x-y plane of R (the message's "
                                              "frame): a flat short cylinder at z = 0 and a line "
                                              "down to it.",
                                              system_, SLOT(updateStyle()), this);
}

void BodyKinematicsDisplay::drawSystem(const mb_kinematics_msgs::BodyKinematicsArray& msg) {
  if (!system_visual_)
    system_visual_ =
        std::make_unique<SystemKinematicsVisual>(context_->getSceneManager(), scene_node_);
  SystemStyle s;
  s.show = system_->getBool();
  s.sphere = system_sphere_->getBool();
  s.velocity = system_velocity_->getBool();
  s.acceleration = system_acceleration_->getBool();
  s.projection = system_projection_->getBool();
  const QColor c = system_color_->getColor();
  const float alpha = alpha_->getFloat();
  s.color = Ogre::ColourValue(c.redF(), c.greenF(), c.blueF(), alpha);
  auto colour = [&](const mbk::Rgba& x) { return Ogre::ColourValue(x.r, x.g, x.b, alpha); };
  s.velocity_color = colour(style_.color[mbk::GlyphQuantity::kVelocity]);
  s.acceleration_color = colour(style_.color[mbk::GlyphQuantity::kAcceleration]);
  s.velocity_scale = style_.scale[mbk::GlyphQuantity::kVelocity];
  s.acceleration_scale = style_.scale[mbk::GlyphQuantity::kAcceleration];
  s.radius = system_radius_->getFloat();
  s.width = 2 * style_.width;
  const mbk::Vec3<double> g(msg.system.mass_center.x, msg.system.mass_center.y,
                            msg.system.mass_center.z);
  Ogre::Vector3 at;
  Ogre::Quaternion turn;
  if (g.allFinite() && g.lpNorm<Eigen::Infinity>() <= mbk::kMaxGlyphDistance &&
      context_->getFrameManager()->transform(msg.header, pose(g), at, turn))
    system_visual_->setCenterPose(at, turn);
  if (system_visual_->set(msg.system, s))
    deleteStatus("System");
  else
    setStatus(rviz::StatusProperty::Warn, "System",
              "system quantities with NaN or infinite values");
}

void BodyKinematicsDisplay::onInitialize() {
  MFDClass::onInitialize();
  // The subscriber's callbacks run in rviz's GUI thread (update_nh_'s queue).
  frame_connection_ = sub_.registerCallback(&BodyKinematicsDisplay::adoptFrame, this);
  updateHistoryLength();
  updateStyle();
  updateFilter();
  updateMasses();
}

// rviz's reset (Auto Frame's change of the Fixed Frame, the Reset button) clears the statuses:
// the legend, which depends on the properties alone, is shown again.
void BodyKinematicsDisplay::reset() {
  MFDClass::reset();
  visuals_.clear();
  pending_.clear();
  system_visual_.reset();
  auto_lengths_ = mbk::AutoLengths();
  showLegend();
}

void BodyKinematicsDisplay::onEnable() {
  MFDClass::onEnable();
  framed_ = false;
}

void BodyKinematicsDisplay::updateAutoFrame() { framed_ = false; }

void BodyKinematicsDisplay::adoptFrame(
    const mb_kinematics_msgs::BodyKinematicsArray::ConstPtr& msg) {
  const QString frame = QString::fromStdString(msg->header.frame_id);
  if (!auto_frame_->getBool() || frame.isEmpty() || frame == fixed_frame_) return;
  const auto tf = context_->getTF2BufferPtr();
  const std::string fixed = fixed_frame_.toStdString();
  if (tf->_frameExists(fixed) || !tf->_frameExists(frame.toStdString())) return;
  auto* manager = dynamic_cast<rviz::VisualizationManager*>(context_);
  if (!manager) return;
  ROS_INFO_STREAM("BodyKinematics: Fixed Frame '" << fixed << "' is not in tf; set to '"
                                                  << frame.toStdString()
                                                  << "', the frame of the body kinematics");
  manager->setFixedFrame(frame);
}

std::string BodyKinematicsDisplay::followFrame(const mb_kinematics_msgs::BodyKinematicsArray& msg,
                                               const QString& target) const {
  const auto tf = context_->getTF2BufferPtr();
  std::string frame;
  if (ros::NodeHandle("~").getParam("follow_frame", frame) && !frame.empty())
    return tf->_frameExists(frame) ? frame : "";
  if (msg.bodies.empty() || target != rviz::TfFrameProperty::FIXED_FRAME_STRING) return "";
  const std::string& name = msg.bodies[0].name;
  const std::string& r = msg.header.frame_id;
  const std::string prefixed = r.substr(0, r.rfind('/') + 1) + name;  // ~frame_prefix's
  if (tf->_frameExists(prefixed)) return prefixed;
  return tf->_frameExists(name) ? name : "";
}

// The camera looks at the centre of the box around every O_k and G_k drawn (within
// mbk::kMaxGlyphDistance) from where the box's bounding sphere fills the view's height, and
// follows the robot's base (followFrame): a robot on a moving base stays in view.
void BodyKinematicsDisplay::frameCamera(const std::vector<mbk::GlyphBody>& drawn,
                                        const mb_kinematics_msgs::BodyKinematicsArray& msg) {
  const std_msgs::Header& header = msg.header;
  rviz::ViewController* view = context_->getViewManager()->getCurrent();
  Eigen::AlignedBox3d box;
  for (const mbk::GlyphBody& b : drawn) box.extend(b.origin).extend(b.mass_center);
  Ogre::Vector3 center;
  Ogre::Quaternion orientation;
  if (!view || box.isEmpty() ||
      !context_->getFrameManager()->transform(header, pose(box.center()), center, orientation))
    return;
  const double size = mbk::robot_size(drawn);
  const double radius = 0.5 * size + mbk::auto_longest(length_fraction_->getFloat(),
                                                       size > 0 ? size : mbk::kPointRobotSize,
                                                       style_);
  const double half_fov = 0.5 * view->getCamera()->getFOVy().valueRadians();
  rviz::Property* target = view->subProp("Target Frame");  // Orbit and the other tracking views
  const std::string follow = followFrame(msg, target->getValue().toString());
  if (!follow.empty() && target->getValue().isValid()) {
    // The view keeps its focal point where it was on a change of target (rviz's
    // onTargetFrameChanged); lookAt then places it relative to the new target.
    target->setValue(QString::fromStdString(follow));
    ROS_INFO_STREAM("BodyKinematics: the view follows '" << follow << "'");
  }
  view->lookAt(center);
  view->subProp("Distance")->setValue(std::max(kMinCameraDistance, radius / std::sin(half_fov)));
}

void BodyKinematicsDisplay::updateMasses() {
  masses_.clear();
  masses_tried_ = ros::WallTime::now();
  const std::string param = robot_description_->getStdString();
  std::string urdf;
  if (!update_nh_.getParam(param, urdf)) {
    setStatus(rviz::StatusProperty::Warn, "Masses",
              QString::fromStdString("no parameter '" + param +
                                     "': Min Mass Fraction leaves nothing out"));
    return;
  }
  try {
    masses_ = mbk::urdf_link_masses(urdf);
    setStatus(rviz::StatusProperty::Ok, "Masses",
              QString::number(masses_.size()) + " links from '" + param.c_str() + "'");
  } catch (const std::exception& e) {
    setStatus(rviz::StatusProperty::Warn, "Masses",
              QString::fromStdString("parameter '" + param + "': " + e.what() +
                                     "; Min Mass Fraction leaves nothing out"));
  }
}

// Once ROS shuts down (rviz's SIGINT), nothing more is drawn: rviz closes at its next check,
// after the frames under way, and those are cheap with the glyphs hidden (under software
// rendering a frame of Max Bodies bodies takes seconds on a loaded machine).
void BodyKinematicsDisplay::update(float /*wall_dt*/, float /*ros_dt*/) {
  if (!ros::ok()) {
    scene_node_->setVisible(false);
    pending_.clear();
    return;
  }
  const size_t n = std::min(pending_.size(), visuals_.capacity());
  for (size_t i = pending_.size() - n; i < pending_.size(); ++i) draw(*pending_[i]);
  pending_.clear();
}

void BodyKinematicsDisplay::updateStyle() {
  for (int q = 0; q < mbk::GlyphQuantity::kCount; ++q) {
    style_.show[q] = quantity_[q].show->getBool();
    style_.scale[q] = quantity_[q].scale->getFloat();
    style_.color[q] = rgba(quantity_[q].color->getColor());
  }
  style_.mass_centers = mass_centers_->getBool();
  style_.mass_center_color = rgba(mass_center_color_->getColor());
  style_.sphere_radius = sphere_radius_->getFloat();
  style_.skeleton = skeleton_->getBool();
  style_.skeleton_color = rgba(skeleton_color_->getColor());
  style_.width = width_->getFloat();
  style_.arc_radius = arc_radius_->getFloat();
  style_.max_length = mbk::kMaxGlyphDistance;  // autoScale's when on
  style_.min_mass_fraction = min_mass_fraction_->getFloat();
  style_.max_bodies = static_cast<size_t>(std::max(0, max_bodies_->getInt()));
  showLegend();
}

// The status panel's legend, a row per color named by it ("cyan", "velocity of G_k, m/s"):
// which color is which quantity, as the properties set them; names this short show whole in the
// Displays panel's name column at a status row's depth. Two quantities of one color share a row.
void BodyKinematicsDisplay::showLegend() {
  for (const QString& name : legend_rows_) deleteStatus(name);
  legend_rows_.clear();
  std::map<QString, QString> rows;
  for (const std::string& entry : mbk::glyph_legend(style_)) {
    const std::size_t colon = entry.find(": ");
    QString& text = rows[QString::fromStdString(entry.substr(0, colon))];
    text += (text.isEmpty() ? "" : "; ") + QString::fromStdString(entry.substr(colon + 2));
  }
  if (rows.empty()) rows["Legend"] = "nothing shown";
  for (const auto& row : rows) {
    setStatus(rviz::StatusProperty::Ok, row.first, row.second);
    legend_rows_.push_back(row.first);
  }
}

void BodyKinematicsDisplay::updateFilter() {
  const char* property = "Body Filter";
  try {
    style_.filter = mbk::BodyFilter(filter_->getStdString());
    property = "Exclude Bodies";
    style_.filter = mbk::BodyFilter(filter_->getStdString(), exclude_->getStdString());
    filter_ok_ = true;
    deleteStatus("Body Filter");
  } catch (const std::regex_error& e) {
    filter_ok_ = false;
    setStatus(rviz::StatusProperty::Error, "Body Filter",
              QString(property) + ": not a regular expression: " + e.what());
  }
}

void BodyKinematicsDisplay::updateHistoryLength() {
  visuals_.rset_capacity(history_length_->getInt());
}

void BodyKinematicsDisplay::autoScale(double time, const mbk::BodySelection& drawn) {
  if (auto_scale_->getBool())
    auto_lengths_.update(time, drawn, length_fraction_->getFloat(), style_);
}

namespace {

// The first five names, each cut to 60 characters.
QString someNames(const std::vector<std::string>& names) {
  QString out;
  for (size_t i = 0; i < names.size() && i < 5; ++i) {
    out += (i ? ", " : "") + QString::fromStdString(names[i].substr(0, 60));
    if (names[i].size() > 60) out += "...";
  }
  if (names.size() > 5) out += ", ...";
  return out;
}

}  // namespace

void BodyKinematicsDisplay::reportLeftOut(const char* status, size_t count, const QString& what) {
  if (count == 0)
    deleteStatus(status);
  else
    setStatus(rviz::StatusProperty::Warn, status, QString::number(count) + " bodies " + what);
}

void BodyKinematicsDisplay::reportSkipped(const mbk::Glyphs& glyphs) {
  reportLeftOut("Invalid values", glyphs.skipped.size(),
                "with NaN or infinite values skipped: " + someNames(glyphs.skipped));
  reportLeftOut(
      "Far bodies", glyphs.far.size(),
      QString("farther than %1 m from the frame's origin not drawn: ").arg(mbk::kMaxGlyphDistance) +
          someNames(glyphs.far));
  reportLeftOut("Long names", glyphs.long_names,
                QString("not drawn: names longer than %1 characters are not matched against "
                        "Body Filter or Exclude Bodies")
                    .arg(mbk::kMaxFilteredName));
  reportLeftOut("Max Bodies", glyphs.over_max_bodies,
                QString("not drawn: at most Max Bodies (%1) per message").arg(style_.max_bodies));
}

std::shared_ptr<BodyKinematicsVisual> BodyKinematicsDisplay::nextVisual() {
  if (visuals_.full() && !visuals_.empty()) {  // reuse the oldest
    std::shared_ptr<BodyKinematicsVisual> v = visuals_.front();
    visuals_.pop_front();
    return v;
  }
  return std::make_shared<BodyKinematicsVisual>(context_->getSceneManager(), scene_node_);
}

void BodyKinematicsDisplay::processMessage(
    const mb_kinematics_msgs::BodyKinematicsArray::ConstPtr& msg) {
  pending_.push_back(msg);
  // With the Time panel's sync mode "Exact" on this display (config/mb_kinematics.rviz),
  // RobotModel and TF look tf up at this message's stamp, so the robot is drawn at the same
  // instant as the arrows even though messages reach a display a frame or two after tf does.
  emitTimeSignal(msg->header.stamp);
}

void BodyKinematicsDisplay::draw(const mb_kinematics_msgs::BodyKinematicsArray& msg) {
  Ogre::Quaternion orientation;
  Ogre::Vector3 position;
  if (!context_->getFrameManager()->getTransform(msg.header, position, orientation)) {
    setStatus(rviz::StatusProperty::Error, "Transform",
              QString("no transform from '") + msg.header.frame_id.c_str() + "' to '" +
                  fixed_frame_ + "'");
    return;
  }
  deleteStatus("Transform");
  if (!filter_ok_) return;
  if (masses_.empty() && (ros::WallTime::now() - masses_tried_).toSec() > 1) updateMasses();
  const mbk::BodySelection drawn = mbk::select_bodies(msg, masses_, style_);
  if (auto_frame_->getBool() && !framed_) {
    frameCamera(drawn.drawn(), msg);
    framed_ = true;
  }
  autoScale(msg.header.stamp.toSec(), drawn);
  const mbk::Glyphs glyphs = mbk::make_glyphs(drawn, style_);
  reportSkipped(glyphs);
  const mbk::Vec3<double> anchor = mbk::glyph_anchor(glyphs);
  Ogre::Vector3 at;
  Ogre::Quaternion turn;
  if (!context_->getFrameManager()->transform(msg.header, pose(anchor), at, turn)) return;
  std::shared_ptr<BodyKinematicsVisual> visual = nextVisual();
  visual->setAnchorPose(at, turn);
  visual->set(glyphs, anchor, style_, alpha_->getFloat());
  visuals_.push_back(visual);
  drawSystem(msg);
}

}  // namespace mbk_rviz

PLUGINLIB_EXPORT_CLASS(mbk_rviz::BodyKinematicsDisplay, rviz::Display)
