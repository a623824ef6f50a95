// The whole system in rviz (doc/method.md 9): a larger sphere at the system mass center G, arrows
// for its velocity and acceleration, and its projection on R's x-y plane (a flat disc at z = 0 and
// a line down to it), from a BodyKinematicsArray's `system` field; nothing when it is not filled.
#pragma once

#include <OgreColourValue.h>
#include <OgrePrerequisites.h>
#include <mb_kinematics_msgs/SystemKinematics.h>

#include <memory>

namespace rviz {
class Arrow;
class BillboardLine;
class Shape;
}  // namespace rviz

namespace mbk_rviz {

struct SystemStyle {
  bool show = true;  // false hides all four parts below
  bool sphere = true, velocity = true, acceleration = true, projection = true;
  Ogre::ColourValue color{0.2f, 1.0f, 0.2f, 1.0f};  // G and its projection
  Ogre::ColourValue velocity_color, acceleration_color;
  float radius = 0.07f;                                     // of the sphere at G (m)
  float velocity_scale = 0.1f, acceleration_scale = 0.02f;  // m per m/s, per m/s^2
  float width = 0.024f;                                     // arrow shaft diameter (m)
};

class SystemKinematicsVisual {
 public:
  SystemKinematicsVisual(Ogre::SceneManager* scene_manager, Ogre::SceneNode* parent);
  ~SystemKinematicsVisual();
  SystemKinematicsVisual(const SystemKinematicsVisual&) = delete;
  SystemKinematicsVisual& operator=(const SystemKinematicsVisual&) = delete;

  // Draws `system` if filled with a positive mass; false (nothing drawn) if it has a value that
  // is not finite.
  bool set(const mb_kinematics_msgs::SystemKinematics& system, const SystemStyle& style);
  // The pose of G in the Fixed Frame (R's orientation): the picture is drawn relative to G.
  void setCenterPose(const Ogre::Vector3& position, const Ogre::Quaternion& orientation);

 private:
  void hide();

  Ogre::SceneManager* scene_manager_;
  Ogre::SceneNode* node_;
  std::unique_ptr<rviz::Shape> sphere_, disc_;
  std::unique_ptr<rviz::Arrow> velocity_, acceleration_;
  std::unique_ptr<rviz::BillboardLine> drop_;
};

}  // namespace mbk_rviz
