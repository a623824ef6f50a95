// One message's picture in Ogre (the glyphs of mb_kinematics/viz/glyphs.h): arrows,
// arcs with their heads, mass-center spheres and skeleton lines under a scene node of its own.
// Kept and refilled message after message (no Ogre objects made per message once sized). The
// scene node sits at an anchor near the bodies (its pose composed in double by rviz's
// FrameManager, as rviz's own displays place theirs), the glyphs relative to it
// (viz/local_glyphs.h), so that they stay finite and unrounded far from R's origin.
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

  // The glyphs, drawn relative to `anchor` (a point of R, mbk::glyph_anchor).
  void set(const mbk::Glyphs& glyphs, const mbk::Vec3<double>& anchor, const mbk::GlyphStyle& style,
           float alpha);
  // The anchor's pose in the Fixed Frame (R's orientation).
  void setAnchorPose(const Ogre::Vector3& position, const Ogre::Quaternion& orientation);

 private:
  void setArrows(const mbk::Glyphs& glyphs, const mbk::GlyphStyle& style, float alpha);
  void setArcs(const mbk::Glyphs& glyphs, const mbk::GlyphStyle& style, float alpha);
  void setSpheres(const mbk::Glyphs& glyphs, const mbk::GlyphStyle& style, float alpha);
  void setSkeleton(const mbk::Glyphs& glyphs, const mbk::GlyphStyle& style, float alpha);
  void resizeArrows(std::vector<std::unique_ptr<rviz::Arrow>>& arrows, size_t n);
  Ogre::Vector3 local(const mbk::Vec3<double>& p) const;  // relative to the anchor

  Ogre::SceneManager* scene_manager_;
  Ogre::SceneNode* node_;
  mbk::Vec3<double> anchor_ = mbk::Vec3<double>::Zero();  // in R: where node_ is
  std::vector<std::unique_ptr<rviz::Arrow>> arrows_, arc_heads_;
  std::vector<std::unique_ptr<rviz::Shape>> spheres_;
  std::unique_ptr<rviz::BillboardLine> arcs_, skeleton_;
};

}  // namespace mbk_rviz
