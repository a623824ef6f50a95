#include "mb_kinematics/rviz/body_kinematics_visual.h"

#include <OgreSceneManager.h>
#include <OgreSceneNode.h>
#include <rviz/ogre_helpers/arrow.h>
#include <rviz/ogre_helpers/billboard_line.h>
#include <rviz/ogre_helpers/shape.h>

#include <algorithm>
#include <optional>

#include "mb_kinematics/viz/local_glyphs.h"

namespace mbk_rviz {
namespace {

using mbk::Glyphs;
using mbk::GlyphStyle;

Ogre::Vector3 ogre(const Eigen::Vector3f& v) { return Ogre::Vector3(v.x(), v.y(), v.z()); }

Ogre::ColourValue colour(const mbk::Rgba& c, float alpha) {
  return Ogre::ColourValue(c.r, c.g, c.b, c.a * alpha);
}

// An arrow from `start` along `vector` (relative to `anchor`): the head 3 shaft widths long (at
// most half the arrow); hidden when it has no length a float holds.
void placeArrow(rviz::Arrow& arrow, const mbk::Vec3<double>& start, const mbk::Vec3<double>& vector,
                const mbk::Vec3<double>& anchor, float width, const Ogre::ColourValue& c) {
  const std::optional<mbk::LocalArrow> a = mbk::local_arrow(start, vector, anchor);
  arrow.getSceneNode()->setVisible(a.has_value());
  if (!a) return;
  const float head = std::min(3 * width, 0.5f * a->length);
  arrow.set(std::max(a->length - head, 1e-4f), width, head, 2 * width);
  arrow.setPosition(ogre(a->start));
  arrow.setDirection(ogre(a->direction));
  arrow.setColor(c);
}

}  // namespace

BodyKinematicsVisual::BodyKinematicsVisual(Ogre::SceneManager* scene_manager,
                                           Ogre::SceneNode* parent)
    : scene_manager_(scene_manager), node_(parent->createChildSceneNode()) {
  arcs_.reset(new rviz::BillboardLine(scene_manager_, node_));
  skeleton_.reset(new rviz::BillboardLine(scene_manager_, node_));
}

BodyKinematicsVisual::~BodyKinematicsVisual() {
  arrows_.clear();
  arc_heads_.clear();
  spheres_.clear();
  arcs_.reset();
  skeleton_.reset();
  scene_manager_->destroySceneNode(node_);
}

void BodyKinematicsVisual::setAnchorPose(const Ogre::Vector3& position,
                                         const Ogre::Quaternion& orientation) {
  node_->setPosition(position);
  node_->setOrientation(orientation);
}

void BodyKinematicsVisual::set(const Glyphs& glyphs, const mbk::Vec3<double>& anchor,
                               const GlyphStyle& style, float alpha) {
  anchor_ = anchor;
  setArrows(glyphs, style, alpha);
  setArcs(glyphs, style, alpha);
  setSpheres(glyphs, style, alpha);
  setSkeleton(glyphs, style, alpha);
}

Ogre::Vector3 BodyKinematicsVisual::local(const mbk::Vec3<double>& p) const {
  return ogre(mbk::local_point(p, anchor_));
}

void BodyKinematicsVisual::resizeArrows(std::vector<std::unique_ptr<rviz::Arrow>>& arrows,
                                        size_t n) {
  if (arrows.size() > n) arrows.resize(n);
  while (arrows.size() < n) arrows.emplace_back(new rviz::Arrow(scene_manager_, node_));
}

void BodyKinematicsVisual::setArrows(const Glyphs& glyphs, const GlyphStyle& style, float alpha) {
  resizeArrows(arrows_, glyphs.arrows.size());
  for (size_t i = 0; i < glyphs.arrows.size(); ++i) {
    const mbk::GlyphArrow& a = glyphs.arrows[i];
    placeArrow(*arrows_[i], a.start, a.vector, anchor_, style.width,
               colour(style.color[a.quantity], alpha));
  }
}

void BodyKinematicsVisual::setArcs(const Glyphs& glyphs, const GlyphStyle& style, float alpha) {
  resizeArrows(arc_heads_, glyphs.arcs.size());
  arcs_->clear();
  arcs_->setLineWidth(0.5 * style.width);
  if (glyphs.arcs.empty()) return;
  arcs_->setMaxPointsPerLine(glyphs.arcs.front().points.size());
  arcs_->setNumLines(glyphs.arcs.size());
  for (size_t i = 0; i < glyphs.arcs.size(); ++i) {
    const mbk::GlyphArc& arc = glyphs.arcs[i];
    const Ogre::ColourValue c = colour(style.color[arc.quantity], alpha);
    if (i > 0) arcs_->newLine();
    for (const mbk::Vec3<double>& p : arc.points) arcs_->addPoint(local(p), c);
    placeArrow(*arc_heads_[i], arc.head_start, arc.head_dir, anchor_, 0.5 * style.width, c);
  }
}

void BodyKinematicsVisual::setSpheres(const Glyphs& glyphs, const GlyphStyle& style, float alpha) {
  const size_t n = glyphs.mass_centers.size();
  if (spheres_.size() > n) spheres_.resize(n);
  while (spheres_.size() < n)
    spheres_.emplace_back(new rviz::Shape(rviz::Shape::Sphere, scene_manager_, node_));
  const float d = 2 * style.sphere_radius;
  for (size_t i = 0; i < n; ++i) {
    spheres_[i]->setPosition(local(glyphs.mass_centers[i]));
    spheres_[i]->setScale(Ogre::Vector3(d, d, d));
    spheres_[i]->setColor(colour(style.mass_center_color, alpha));
  }
}

void BodyKinematicsVisual::setSkeleton(const Glyphs& glyphs, const GlyphStyle& style, float alpha) {
  skeleton_->clear();
  skeleton_->setLineWidth(0.5 * style.width);
  if (glyphs.skeleton.empty()) return;
  skeleton_->setMaxPointsPerLine(2);
  skeleton_->setNumLines(glyphs.skeleton.size());
  const Ogre::ColourValue c = colour(style.skeleton_color, alpha);
  for (size_t i = 0; i < glyphs.skeleton.size(); ++i) {
    if (i > 0) skeleton_->newLine();
    skeleton_->addPoint(local(glyphs.skeleton[i].first), c);
    skeleton_->addPoint(local(glyphs.skeleton[i].second), c);
  }
}

}  // namespace mbk_rviz
