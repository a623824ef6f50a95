#include "mb_kinematics/rviz/system_kinematics_visual.h"

#include <OgreSceneManager.h>
#include <OgreSceneNode.h>
#include <rviz/ogre_helpers/arrow.h>
#include <rviz/ogre_helpers/billboard_line.h>
#include <rviz/ogre_helpers/shape.h>

#include <algorithm>
#include <cmath>

#include "mb_kinematics/viz/glyphs.h"

namespace mbk_rviz {
namespace {

Ogre::Vector3 ogre(const geometry_msgs::Vector3& v) { return Ogre::Vector3(v.x, v.y, v.z); }

bool finite(const Ogre::Vector3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// An arrow `vector * scale` from `from`, its length and direction computed in double; hidden
// when shorter than 1 mm or longer than mbk::kMaxGlyphDistance.
void placeArrow(rviz::Arrow& arrow, const Ogre::Vector3& from, const geometry_msgs::Vector3& vector,
                double scale, float width, const Ogre::ColourValue& color, bool show) {
  const double d[3] = {vector.x * scale, vector.y * scale, vector.z * scale};
  const double length = std::hypot(d[0], d[1], d[2]);
  const bool visible = show && length > 1e-3 && length <= mbk::kMaxGlyphDistance;
  arrow.getSceneNode()->setVisible(visible);
  if (!visible) return;
  const float head = std::min(3 * width, 0.5f * static_cast<float>(length));
  arrow.set(std::max(static_cast<float>(length) - head, 1e-4f), width, head, 2 * width);
  arrow.setPosition(from);
  arrow.setDirection(Ogre::Vector3(d[0] / length, d[1] / length, d[2] / length));
  arrow.setColor(color);
}

}  // namespace

SystemKinematicsVisual::SystemKinematicsVisual(Ogre::SceneManager* scene_manager,
                                               Ogre::SceneNode* parent)
    : scene_manager_(scene_manager), node_(parent->createChildSceneNode()) {
  sphere_.reset(new rviz::Shape(rviz::Shape::Sphere, scene_manager_, node_));
  disc_.reset(new rviz::Shape(rviz::Shape::Cylinder, scene_manager_, node_));
  velocity_.reset(new rviz::Arrow(scene_manager_, node_));
  acceleration_.reset(new rviz::Arrow(scene_manager_, node_));
  drop_.reset(new rviz::BillboardLine(scene_manager_, node_));
  hide();
}

SystemKinematicsVisual::~SystemKinematicsVisual() {
  sphere_.reset();
  disc_.reset();
  velocity_.reset();
  acceleration_.reset();
  drop_.reset();
  scene_manager_->destroySceneNode(node_);
}

void SystemKinematicsVisual::setCenterPose(const Ogre::Vector3& position,
                                           const Ogre::Quaternion& orientation) {
  node_->setPosition(position);
  node_->setOrientation(orientation);
}

void SystemKinematicsVisual::hide() { node_->setVisible(false); }

bool SystemKinematicsVisual::set(const mb_kinematics_msgs::SystemKinematics& system,
                                 const SystemStyle& style) {
  const Ogre::Vector3 g(system.mass_center.x, system.mass_center.y, system.mass_center.z);
  const Ogre::Vector3 v = ogre(system.velocity), a = ogre(system.acceleration);
  const bool valid = finite(g) && finite(v) && finite(a);
  const bool near = std::max({std::abs(g.x), std::abs(g.y), std::abs(g.z)}) <=
                    static_cast<float>(mbk::kMaxGlyphDistance);
  if (!style.show || !system.filled || !(system.mass > 0) || !valid || !near) {
    hide();
    return valid || !system.filled;
  }
  node_->setVisible(true);
  const float d = 2 * style.radius;
  const Ogre::Vector3 here = Ogre::Vector3::ZERO;  // G: the node is there
  sphere_->getRootNode()->setVisible(style.sphere);
  sphere_->setPosition(here);
  sphere_->setScale(Ogre::Vector3(d, d, d));
  sphere_->setColor(style.color);
  placeArrow(*velocity_, here, system.velocity, style.velocity_scale, style.width,
             style.velocity_color, style.velocity);
  placeArrow(*acceleration_, here, system.acceleration, style.acceleration_scale, style.width,
             style.acceleration_color, style.acceleration);
  // The projection on R's x-y plane: a flat disc (rviz's cylinder shape stands along its z)
  // and a line from G down to it.
  const Ogre::Vector3 foot(0, 0, -g.z);
  disc_->getRootNode()->setVisible(style.projection);
  disc_->setPosition(foot);
  disc_->setScale(Ogre::Vector3(2 * d, 2 * d, 0.1f * d));
  disc_->setColor(style.color);
  drop_->clear();
  drop_->setLineWidth(0.25f * style.width);
  if (style.projection) {
    drop_->addPoint(here, style.color);
    drop_->addPoint(foot, style.color);
  }
  return true;
}

}  // namespace mbk_rviz
