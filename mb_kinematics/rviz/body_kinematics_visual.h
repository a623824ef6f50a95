// One message's picture in Ogre (the glyphs of mb_kinematics/viz/glyphs.h): arrows,
// arcs with their heads, mass-center spheres and skeleton lines under a scene node of its own.
// Kept and refilled message after message (no Ogre objects made per message once sized).
#pragma once

#include <OgrePrerequisites.h>

#include <memory>
#include <vector>

#include "mb_kinematics/viz/glyphs.h"

namespace rviz {
class Arrow;
class BillboardLine;
class Shape;
}  // namespace rviz

namespace mbk_rviz {

class BodyKinematicsVisual {
 public:
  BodyKinematicsVisual(Ogre::SceneManager* scene_manager, Ogre::SceneNode* parent);
  ~BodyKinematicsVisual();
  BodyKinematicsVisual(const BodyKinematicsVisual&) = delete;
  BodyKinematicsVisual& operator=(const BodyKinematicsVisual&) = delete;

  void set(const mbk::Glyphs& glyphs, const mbk::GlyphStyle& style, float alpha);
  void setFramePose(const Ogre::Vector3& position, const Ogre::Quaternion& orientation);

 private:
  void setArrows(const mbk::Glyphs& glyphs, const mbk::GlyphStyle& style, float alpha);
  void setArcs(const mbk::Glyphs& glyphs, const mbk::GlyphStyle& style, float alpha);
  void setSpheres(const mbk::Glyphs& glyphs, const mbk::GlyphStyle& style, float alpha);
  void setSkeleton(const mbk::Glyphs& glyphs, const mbk::GlyphStyle& style, float alpha);
  void resizeArrows(std::vector<std::unique_ptr<rviz::Arrow>>& arrows, size_t n);

  Ogre::SceneManager* scene_manager_;
  Ogre::SceneNode* node_;
  std::vector<std::unique_ptr<rviz::Arrow>> arrows_, arc_heads_;
  std::vector<std::unique_ptr<rviz::Shape>> spheres_;
  std::unique_ptr<rviz::BillboardLine> arcs_, skeleton_;
};

}  // namespace mbk_rviz
