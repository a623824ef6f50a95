// Dempster's segment table (Winter, Table 4.1; io/bvh_anthropometry.h): its fractions sum as
// Winter's do; on CMU 131_01 the masses sum to --body-mass, each segment's mass is the table's,
// and the whole-body mass center's difference from de Leva's over the walk is the figure that
// doc/anthropometry.md states (read from the doc, to its printed precision).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/bvh.h"
#include "mb_kinematics/io/bvh_anthropometry.h"
#include "mb_kinematics/io/bvh_model.h"

namespace {

constexpr double kCmuScale = 0.0254 / 0.45;  // metres per CMU unit (test/mocap/README.md)
const std::string kWalk = std::string(MBK_SOURCE_DIR) + "/test/mocap/131_01.bvh";

// Winter's fractions: hand 0.006, forearm 0.016, upper arm 0.028, foot 0.0145, leg 0.0465,
// thigh 0.100 (twice each), head and neck 0.081, trunk 0.497: 1.000.
TEST(Dempster, FractionsSumAsWintersDo) {
  EXPECT_NEAR(mbk::dempster_mass_sum(), 1.0, 1e-15);
  EXPECT_EQ(mbk::dempster_table().size(), 8u);
  for (const mbk::DempsterRow& row : mbk::dempster_table()) {
    EXPECT_GT(row.mass, 0) << row.name;
    EXPECT_GT(row.mass_center, 0) << row.name;
    EXPECT_LE(row.mass_center, 1) << row.name;
  }
}

TEST(Dempster, NamedTables) {
  EXPECT_EQ(mbk::segment_table_from_string("dempster"), mbk::SegmentTable::kDempster);
  EXPECT_EQ(mbk::segment_table_from_string("de_leva"), mbk::SegmentTable::kDeLeva);
  EXPECT_THROW(mbk::segment_table_from_string("winter"), std::invalid_argument);
  EXPECT_THROW(mbk::bvh_model_options("", "", "", "", "dempster"), std::invalid_argument);
  EXPECT_EQ(mbk::bvh_model_options("", "70", "", "", "dempster").anthropometry, "dempster");
}

mbk::Model walk_model(const mbk::BvhFile& bvh, const char* table) {
  mbk::BvhModelOptions o;
  o.scale = kCmuScale;
  o.body_mass = 68.5;
  o.anthropometry = table;
  return mbk::model_from_bvh(bvh, o);
}

double body_mass(const mbk::Model& model, const std::string& name) {
  for (const mbk::Body& b : model.bodies)
    if (b.name == name) return b.mass;
  ADD_FAILURE() << "no body " << name;
  return 0;
}

// CMU's skeleton has every segment, one per body for the limbs: each thigh, leg, foot, upper arm,
// forearm carries Winter's fraction of 68.5 kg (the hands too: finger and thumb bodies massless).
TEST(Dempster, MassesOnTheCmuWalk) {
  const mbk::BvhFile bvh = mbk::read_bvh(kWalk);
  const mbk::Model model = walk_model(bvh, "dempster");
  double total = 0;
  for (const mbk::Body& b : model.bodies) total += b.mass;
  EXPECT_NEAR(total, 68.5, 1e-12 * 68.5);
  const std::pair<const char*, double> limbs[] = {{"LeftHip", 0.100},    {"LeftKnee", 0.0465},
                                                  {"LeftAnkle", 0.0145}, {"RightHip", 0.100},
                                                  {"RightKnee", 0.0465}, {"RightAnkle", 0.0145}};
  for (const auto& [name, fraction] : limbs)
    EXPECT_NEAR(body_mass(model, name), 68.5 * fraction, 1e-12) << name;
}

// "... 131_01 ...: D mm (mean over the N frames), at most M mm" in doc/anthropometry.md.
struct DocFigure {
  double mean_mm, max_mm, mean_height_mm;
};
DocFigure doc_figure() {
  std::ifstream in(std::string(MBK_SOURCE_DIR) + "/doc/anthropometry.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  std::smatch m;
  std::string pattern =
      "Dempster's whole-body mass center is ([0-9.]+) mm from de Leva's on average over "
      "131_01's 994 frames \\(at most ([0-9.]+) mm\\); its height differs by ([-0-9.]+) mm on "
      "average";
  pattern = std::regex_replace(pattern, std::regex(" "), "\\s+");  // the doc wraps its lines
  const std::regex figure(pattern);
  if (!std::regex_search(doc, m, figure)) {
    ADD_FAILURE() << "doc/anthropometry.md does not state the figure";
    return {};
  }
  return {std::stod(m[1]), std::stod(m[2]), std::stod(m[3])};
}

TEST(Dempster, CmuMassCenterDifferenceIsTheDocs) {
  const mbk::BvhFile bvh = mbk::read_bvh(kWalk);
  const mbk::Model leva = walk_model(bvh, "de_leva"), dempster = walk_model(bvh, "dempster");
  mbk::Data<double> a(leva), b(dempster);
  mbk::JointState<double> state(leva);
  mbk::SystemKinematics<double> sa, sb;
  double sum = 0, most = 0, height = 0;
  for (int f = 0; f < bvh.frame_count; ++f) {
    const std::vector<double> q = mbk::bvh_frame_coordinates(bvh, leva, f, kCmuScale);
    state.position = Eigen::Map<const Eigen::VectorXd>(q.data(), leva.nq);
    mbk::forward_kinematics(leva, state, a, mbk::Level::kPose);
    mbk::forward_kinematics(dempster, state, b, mbk::Level::kPose);
    mbk::system_kinematics(leva, a, sa, mbk::Level::kPose);
    mbk::system_kinematics(dempster, b, sb, mbk::Level::kPose);
    const double d = (sb.mass_center - sa.mass_center).norm() * 1000;
    sum += d;
    most = std::max(most, d);
    height += (sb.mass_center.y() - sa.mass_center.y()) * 1000;  // y up
  }
  const DocFigure doc = doc_figure();
  EXPECT_EQ(bvh.frame_count, 994);
  EXPECT_NEAR(sum / bvh.frame_count, doc.mean_mm, 0.05);  // the doc's one decimal
  EXPECT_NEAR(most, doc.max_mm, 0.05);
  EXPECT_NEAR(height / bvh.frame_count, doc.mean_height_mm, 0.05);
}

}  // namespace
