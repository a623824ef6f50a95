// The picture of body_kinematics shared by the rviz display and the node's MarkerArray
// (mb_kinematics/ros/kinematics_markers.h): arrows where and as long as they should be, arcs
// that turn the right-hand way, the body filter, the skeleton, and invalid floats skipped; the
// bodies left out by mass (masses from a URDF) and by the exclusion regex.
#include "mb_kinematics/ros/kinematics_markers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "mb_kinematics/io/text_file.h"
#include "mb_kinematics/io/urdf_masses.h"

namespace {

using mbk::Vec3;
using mbk_ros::Glyphs;
using mbk_ros::GlyphStyle;

template <typename V>
Vec3<double> vec(const V& v) {
  return Vec3<double>(v.x, v.y, v.z);
}
template <typename V>
void set(V& out, double x, double y, double z) {
  out.x = x, out.y = y, out.z = z;
}

mb_kinematics_msgs::BodyKinematics body(const std::string& name, uint32_t k, uint32_t lower,
                                        double offset) {
  mb_kinematics_msgs::BodyKinematics b;
  b.name = name;
  b.index = k;
  b.lower_body = lower;
  set(b.pose.position, 0, 0, offset);
  b.pose.orientation.w = 1;
  set(b.mass_center, 0.1, 0, offset);
  set(b.twist.linear, 1, 0, 0);
  set(b.accel.linear, 0, 2, 0);
  set(b.twist.angular, 0, 0, 3);
  set(b.accel.angular, 4, 0, 0);
  return b;
}

// Bodies a (on R), a__alpha (an intermediate link of a ball joint), b (on a__alpha).
mb_kinematics_msgs::BodyKinematicsArray message() {
  mb_kinematics_msgs::BodyKinematicsArray msg;
  msg.header.frame_id = "world";
  msg.bodies = {body("a", 1, 0, 0.0), body("a__alpha", 2, 1, 0.5), body("b", 3, 2, 0.5)};
  return msg;
}

TEST(KinematicsMarkers, ArrowsAtMassCentersScaledPerQuantity) {
  GlyphStyle style;
  style.scale = {{0.1, 0.2, 0.3, 0.4}};
  const Glyphs g = mbk_ros::make_glyphs(message(), style);
  ASSERT_EQ(g.arrows.size(), 8u);  // 4 per drawn body; a__alpha left out
  const Vec3<double> expected[4] = {{0.1, 0, 0}, {0, 0.4, 0}, {0, 0, 0.9}, {1.6, 0, 0}};
  for (size_t i = 0; i < g.arrows.size(); ++i) {
    const auto& a = g.arrows[i];
    const Vec3<double> g_k(0.1, 0, i < 4 ? 0.0 : 0.5);
    EXPECT_LT((a.start - g_k).norm(), 1e-12) << i;
    EXPECT_LT((a.vector - expected[a.quantity]).norm(), 1e-12) << i;
  }
  EXPECT_EQ(g.arcs.size(), 4u);  // omega and alpha of both
  EXPECT_EQ(g.mass_centers.size(), 2u);
  EXPECT_TRUE(g.skipped.empty());
}

// An arc's radius is Arc Radius, or its arrow's length / 3 when that is less.
TEST(KinematicsMarkers, ArcsTurnTheRightHandWay) {
  GlyphStyle style;
  const Glyphs g = mbk_ros::make_glyphs(message(), style);
  auto radius = [&](const mbk_ros::GlyphArrow& a) {
    return std::min(style.arc_radius, a.vector.norm() / 3);
  };
  for (const auto& arc : g.arcs) {
    const mbk_ros::GlyphArrow* arrow = nullptr;  // the arrow the arc is centred on
    for (const auto& a : g.arrows) {
      const Vec3<double> d = arc.points[0] - (a.start + 0.5 * a.vector);
      if (a.quantity == arc.quantity && std::abs(d.norm() - radius(a)) < 1e-12 &&
          std::abs(d.dot(a.vector.normalized())) < 1e-12)
        arrow = &a;
    }
    ASSERT_NE(arrow, nullptr);
    const Vec3<double> n = arrow->vector.normalized();
    const Vec3<double> c = arrow->start + 0.5 * arrow->vector;
    ASSERT_GT(arc.points.size(), 10u);
    for (size_t i = 0; i + 1 < arc.points.size(); ++i) {
      const Vec3<double> p = arc.points[i] - c, q = arc.points[i + 1] - c;
      EXPECT_NEAR(p.norm(), radius(*arrow), 1e-12);
      EXPECT_NEAR(p.dot(n), 0, 1e-12);
      EXPECT_GT(p.cross(q).dot(n), 0) << "arc " << arc.quantity << " turns the wrong way";
    }
    const Vec3<double> last = arc.points.back() - c;
    EXPECT_GT(last.cross(arc.head_dir).dot(n), 0) << "head of arc " << arc.quantity;
  }
}

TEST(KinematicsMarkers, FilterAndSkeletonSkipIntermediateLinks) {
  GlyphStyle style;
  style.skeleton = true;
  Glyphs g = mbk_ros::make_glyphs(message(), style);
  ASSERT_EQ(g.skeleton.size(), 1u);  // O_a to O_b, across a__alpha
  EXPECT_LT((g.skeleton[0].first - Vec3<double>(0, 0, 0)).norm(), 1e-12);
  EXPECT_LT((g.skeleton[0].second - Vec3<double>(0, 0, 0.5)).norm(), 1e-12);
  style.filter = mbk::BodyFilter("^b$");
  g = mbk_ros::make_glyphs(message(), style);
  EXPECT_EQ(g.arrows.size(), 4u);
  EXPECT_TRUE(g.skeleton.empty());
  style.show[mbk_ros::GlyphQuantity::kOmega] = false;
  EXPECT_EQ(mbk_ros::make_glyphs(message(), style).arrows.size(), 3u);
}

// Indices are the message's, any uint32: the largest ones are looked up as any other (they
// once sized a table by index + 1, which wrapped to 0 and wrote past its end).
TEST(KinematicsMarkers, SkeletonOfIndicesUpToTheLargestUint32) {
  constexpr uint32_t kMax = std::numeric_limits<uint32_t>::max();
  auto msg = message();
  msg.bodies.push_back(body("big", kMax, 1, 1.0));
  msg.bodies.push_back(body("c", 4, kMax, 2.0));
  GlyphStyle style;
  style.skeleton = true;
  const Glyphs g = mbk_ros::make_glyphs(msg, style);
  ASSERT_EQ(g.skeleton.size(), 3u);  // a-b (across a__alpha), a-big, big-c
  EXPECT_LT((g.skeleton[1].second - Vec3<double>(0, 0, 1.0)).norm(), 1e-12);
  EXPECT_LT((g.skeleton[2].first - Vec3<double>(0, 0, 1.0)).norm(), 1e-12);
  EXPECT_LT((g.skeleton[2].second - Vec3<double>(0, 0, 2.0)).norm(), 1e-12);
}

TEST(KinematicsMarkers, InvalidFloatsSkippedAndNamed) {
  auto msg = message();
  msg.bodies[0].accel.angular.y = std::numeric_limits<double>::quiet_NaN();
  msg.bodies[2].pose.orientation.w = std::numeric_limits<double>::infinity();
  msg.bodies.push_back(body("c", 4, 1, 1.0));
  const GlyphStyle style;
  const Glyphs g = mbk_ros::make_glyphs(msg, style);
  EXPECT_EQ(g.skipped, std::vector<std::string>({"a", "b"}));
  EXPECT_EQ(g.arrows.size(), 4u);  // c only
  EXPECT_NEAR(mbk_ros::max_norm(msg, style, mbk_ros::GlyphQuantity::kAlpha), 4, 1e-12);
  const auto markers = mbk_ros::make_marker_array(g, style, msg.header);
  for (const auto& m : markers.markers)
    for (const auto& p : m.points) EXPECT_TRUE(vec(p).allFinite()) << m.ns;
}

TEST(KinematicsMarkers, MarkerArrayHasArrowsPerQuantity) {
  const GlyphStyle style;
  const auto msg = message();
  const auto markers =
      mbk_ros::make_marker_array(mbk_ros::make_glyphs(msg, style), style, msg.header);
  ASSERT_FALSE(markers.markers.empty());
  EXPECT_EQ(markers.markers[0].action, visualization_msgs::Marker::DELETEALL);
  std::map<std::string, int> arrows;
  for (const auto& m : markers.markers) {
    if (m.action == visualization_msgs::Marker::DELETEALL) continue;
    EXPECT_EQ(m.header.frame_id, "world");
    if (m.type == visualization_msgs::Marker::ARROW) {
      ++arrows[m.ns];
      ASSERT_EQ(m.points.size(), 2u);
      EXPECT_GT(m.scale.x, 0);
    }
  }
  for (const char* ns : {"velocity", "acceleration", "omega", "alpha"}) EXPECT_EQ(arrows[ns], 2);
  EXPECT_EQ(arrows["omega_arc"], 2);  // the heads of the arcs
}

// Bodies heavy (5 kg), finger (0.015 kg), mount (massless), unknown (no mass given), in a
// chain; the finger moves fastest.
std::vector<mbk::GlyphBody> weighed_bodies() {
  auto msg = message();
  msg.bodies = {body("heavy", 1, 0, 0.0), body("finger", 2, 1, 0.5), body("mount", 3, 2, 1.0),
                body("unknown", 4, 3, 1.5)};
  set(msg.bodies[1].twist.linear, 10, 0, 0);
  std::vector<mbk::GlyphBody> bodies = mbk::glyph_bodies(msg);
  mbk::set_masses({{"heavy", 5.0}, {"finger", 0.015}, {"mount", 0.0}, {"other", 9.0}}, bodies);
  return bodies;
}

std::vector<Vec3<double>> mass_centers(const Glyphs& g) { return g.mass_centers; }

TEST(KinematicsMarkers, LightBodiesLeftOutByMassFraction) {
  const std::vector<mbk::GlyphBody> bodies = weighed_bodies();
  GlyphStyle style;  // default: below 0.5 % of the heaviest (25 g) left out
  style.skeleton = true;
  EXPECT_EQ(mbk::selected_bodies(bodies, style), std::vector<char>({1, 0, 0, 1}));
  Glyphs g = mbk::make_glyphs(bodies, style);
  EXPECT_EQ(g.arrows.size(), 8u);    // heavy and unknown
  ASSERT_EQ(g.skeleton.size(), 1u);  // O_heavy to O_unknown, across the two left out
  EXPECT_LT((g.skeleton[0].second - Vec3<double>(0, 0, 1.5)).norm(), 1e-12);
  EXPECT_NEAR(mbk::max_norm(bodies, style, mbk_ros::GlyphQuantity::kVelocity), 1, 1e-12);
  style.min_mass_fraction = 0.001;  // 5 g: the finger is back, the massless mount not
  EXPECT_EQ(mbk::selected_bodies(bodies, style), std::vector<char>({1, 1, 0, 1}));
  EXPECT_NEAR(mbk::max_norm(bodies, style, mbk_ros::GlyphQuantity::kVelocity), 10, 1e-12);
  style.min_mass_fraction = 0;  // every body
  EXPECT_EQ(mbk::make_glyphs(bodies, style).arrows.size(), 16u);
}

// The display's path: the bodies chosen from the message in one pass (masses by name), only
// the drawn ones kept; the same picture as from every body converted.
TEST(KinematicsMarkers, SelectionFromTheMessageKeepsOnlyTheBodiesDrawn) {
  auto msg = message();
  msg.bodies = {body("heavy", 1, 0, 0.0),   body("finger", 2, 1, 0.5), body("mount", 3, 2, 1.0),
                body("unknown", 4, 3, 1.5), body("nan", 5, 4, 2.0),    body("last", 6, 5, 2.5)};
  msg.bodies[4].twist.linear.x = std::numeric_limits<double>::quiet_NaN();
  const std::map<std::string, double> masses = {{"heavy", 5.0}, {"finger", 0.015}, {"mount", 0.0}};
  GlyphStyle style;
  style.skeleton = true;
  style.max_bodies = 2;
  const mbk::BodySelection selection = mbk::select_bodies(msg, masses, style);
  ASSERT_EQ(selection.drawn().size(), 2u);
  EXPECT_EQ(selection.drawn()[1].name, "unknown");
  EXPECT_EQ(selection.report().skipped, std::vector<std::string>({"nan"}));
  EXPECT_EQ(selection.report().over_max_bodies, 1u);  // "last"
  std::vector<mbk::GlyphBody> bodies = mbk::glyph_bodies(msg);
  mbk::set_masses(masses, bodies);
  const Glyphs from_message = mbk::make_glyphs(selection, style);
  const Glyphs from_bodies = mbk::make_glyphs(bodies, style);
  EXPECT_EQ(from_message.mass_centers, from_bodies.mass_centers);
  EXPECT_EQ(from_message.arrows.size(), from_bodies.arrows.size());
  EXPECT_EQ(from_message.skeleton, from_bodies.skeleton);
  ASSERT_EQ(from_message.skeleton.size(), 1u);  // O_heavy to O_unknown, across those left out
  EXPECT_EQ(from_message.skeleton[0].second, Vec3<double>(0, 0, 1.5));
  EXPECT_EQ(mbk::max_norm(selection, mbk_ros::GlyphQuantity::kAlpha),
            mbk::max_norm(bodies, style, mbk_ros::GlyphQuantity::kAlpha));
}

TEST(KinematicsMarkers, ExcludedNamesLeftOut) {
  const std::vector<mbk::GlyphBody> bodies = weighed_bodies();
  GlyphStyle style;
  style.min_mass_fraction = 0;
  style.filter = mbk::BodyFilter(mbk::kDefaultBodyFilter, "^(finger|unknown)$");
  EXPECT_EQ(mbk::selected_bodies(bodies, style), std::vector<char>({1, 0, 1, 0}));
  EXPECT_EQ(mass_centers(mbk::make_glyphs(bodies, style)).size(), 2u);
  style.filter = mbk::BodyFilter("^(?!unknown)", "heavy|mount");  // the inclusion still applies
  EXPECT_EQ(mbk::selected_bodies(bodies, style), std::vector<char>({0, 1, 0, 0}));
}

// On the Panda (test/robots/): the default leaves out the two 15 g fingers and the massless
// flange and hand frames, and keeps the seven links and the hand.
TEST(KinematicsMarkers, PandaDefaultLeavesOutFingersAndFrames) {
  const auto masses =
      mbk::urdf_link_masses(mbk::read_text_file(MBK_SOURCE_DIR "/test/robots/panda.urdf", "panda"));
  EXPECT_DOUBLE_EQ(masses.at("panda_leftfinger"), 0.015);
  std::vector<mbk::GlyphBody> bodies;
  for (const auto& [name, mass] : masses) {
    bodies.emplace_back();
    bodies.back().name = name;
    bodies.back().mass = mass;
  }
  const std::vector<char> selected = mbk::selected_bodies(bodies, GlyphStyle());
  std::vector<std::string> left_out;
  for (size_t i = 0; i < bodies.size(); ++i)
    if (!selected[i]) left_out.push_back(bodies[i].name);
  EXPECT_EQ(left_out, std::vector<std::string>({"panda_hand_tcp", "panda_leftfinger", "panda_link8",
                                                "panda_rightfinger"}));
}

TEST(KinematicsMarkers, UrdfMassesRefuseWhatIsNotAUrdf) {
  EXPECT_THROW(mbk::urdf_link_masses("<robot name='r'><link></robot>"), std::runtime_error);
  EXPECT_EQ(mbk::urdf_link_masses("<robot name='r'><link name='a'/></robot>").at("a"), 0.0);
}

}  // namespace
