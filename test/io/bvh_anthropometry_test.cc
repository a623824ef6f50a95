// Segment parameters of BVH skeletons from de Leva (1996) (mb_kinematics/io/bvh_anthropometry.h):
// the table's fractions, the whole-body mass, a segment's mass center and inertia placed as the
// table says, the CMU, Biovision and Mixamo names, the one note for what is not mapped.
#include "mb_kinematics/io/bvh_anthropometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/bvh_model.h"
#include "test/support/test_models.h"

namespace {

constexpr double kMass = 73.0;

mbk::BvhFile cmu_walk() {
  return mbk::read_bvh(mbk_test::source_path("test/io/data/cmu_walk.bvh"));
}

double total_mass(const mbk::Model& model) {
  double sum = 0;
  for (const mbk::Body& body : model.bodies) sum += body.mass;
  return sum;
}

const mbk::Body& body(const mbk::Model& model, const std::string& name) {
  const int k = model.body_index(name);
  if (k < 0) throw std::invalid_argument("no body " + name);
  return model.bodies[k];
}

TEST(DeLeva, MassFractionsSumToOneUpToTheTablesRounding) {
  // Table 4 prints percent to two decimals: the male column sums to 100.00, the female to 99.99.
  EXPECT_NEAR(mbk::de_leva_mass_sum(mbk::Sex::kMale), 1.0, 1e-12);
  EXPECT_NEAR(mbk::de_leva_mass_sum(mbk::Sex::kFemale), 0.9999, 1e-12);
  // The trunk's three parts make the whole trunk's 43.46 % (male) and 42.57 % (female).
  const auto& t = mbk::de_leva_table();
  EXPECT_NEAR(t[1].mass[0] + t[2].mass[0] + t[3].mass[0], 43.46, 1e-12);
  EXPECT_NEAR(t[1].mass[1] + t[2].mass[1] + t[3].mass[1], 42.57, 1e-12);
}

TEST(DeLeva, TheWholeBodyMassIsTheGivenMassForEitherSex) {
  for (const char* sex : {"male", "female"}) {
    const mbk::Model model = mbk::model_from_bvh(cmu_walk(), {0.01, kMass, sex});
    EXPECT_NEAR(total_mass(model), kMass, 1e-12 * kMass) << sex;
    EXPECT_TRUE(model.warnings.empty()) << model.warnings.front();
    mbk::Data<double> data(model);
    mbk::forward_kinematics(model, mbk::JointState<double>(model), data);
    mbk::SystemKinematics<double> system;
    mbk::system_kinematics(model, data, system);
    EXPECT_NEAR(system.mass, kMass, 1e-12 * kMass);
    EXPECT_TRUE(system.angular_momentum_known);
  }
}

TEST(DeLeva, ASegmentsMassCenterAndInertiaAreTheTables) {
  const mbk::Model model = mbk::model_from_bvh(cmu_walk(), {0.01, kMass, "male"});
  // Male shank: 4.33 %, mass center 44.59 % of knee to ankle (0.42 m straight down, -y) from the
  // knee; radii of gyration 25.5 % (sagittal: about the forward axis, here z), 24.9 % (transverse:
  // about the lateral axis, x), 10.3 % (longitudinal, y).
  const mbk::Body& shank = body(model, "LeftLeg");
  const double m = 0.0433 * kMass, length = 0.42;
  EXPECT_NEAR(shank.mass, m, 1e-12);
  EXPECT_TRUE(shank.mass_center.isApprox(Eigen::Vector3d(0, -0.4459 * length, 0), 1e-12));
  const Eigen::Vector3d moments(m * std::pow(0.249 * length, 2), m * std::pow(0.103 * length, 2),
                                m * std::pow(0.255 * length, 2));
  EXPECT_TRUE(shank.inertia.isApprox(Eigen::Matrix3d(moments.asDiagonal()), 1e-12))
      << shank.inertia;
  // Both sides alike; the toes, fingers, hip joints, clavicles and neck carry nothing of their own.
  EXPECT_EQ(body(model, "RightLeg").mass, shank.mass);
  for (const char* name : {"LeftToeBase", "LThumb", "LHipJoint", "RightShoulder", "Neck1"})
    EXPECT_EQ(body(model, name).mass, 0.0) << name;
  // The head and neck from the vertex (18 cm above Head) to CERV (Neck, 10 cm below Head), its
  // mass center 50.02 % of the way down from the vertex.
  EXPECT_TRUE(
      body(model, "Head").mass_center.isApprox(Eigen::Vector3d(0, 0.18 - 0.5002 * 0.28, 0), 1e-12));
}

// The same skeleton with the bones renamed as Biovision (LeftHip, LeftKnee, LeftAnkle, Chest,
// LeftCollar, LeftShoulder, LeftElbow, LeftWrist) and Mixamo (mixamorig:...) name them.
std::string renamed(const std::string& path,
                    const std::vector<std::pair<std::string, std::string>>& names) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  for (const auto& [from, to] : names)
    for (size_t at = text.find(" " + from + "\n"); at != std::string::npos;
         at = text.find(" " + from + "\n", at + 1))
      text.replace(at + 1, from.size(), to);
  return text;
}

TEST(DeLeva, BiovisionAndMixamoNamesMapAsCmus) {
  const std::string path = mbk_test::source_path("test/io/data/cmu_walk.bvh");
  const mbk::Model cmu = mbk::model_from_bvh(cmu_walk(), {0.01, kMass, "female"});
  std::vector<std::pair<std::string, std::string>> biovision, mixamo;
  for (const std::string side : {"Left", "Right"}) {
    for (const auto& [from, to] :
         std::vector<std::pair<std::string, std::string>>{{"UpLeg", "Hip"},
                                                          {"Leg", "Knee"},
                                                          {"Foot", "Ankle"},
                                                          {"Shoulder", "Collar"},
                                                          {"Arm", "Shoulder"},
                                                          {"ForeArm", "Elbow"},
                                                          {"Hand", "Wrist"}})
      biovision.push_back({side + from, side + to});
  }
  biovision.push_back({"Spine1", "Chest"});
  const std::string bio_text = renamed(path, biovision);
  const mbk::Model bio =
      mbk::model_from_bvh(mbk::parse_bvh(bio_text, "bio.bvh"), {0.01, kMass, "female"});
  for (const std::string name : {"Hips", "LowerBack", "Spine", "Spine1", "Head", "LeftUpLeg",
                                 "LeftLeg", "LeftFoot", "RightArm", "RightForeArm", "RightHand"})
    mixamo.push_back({name, "mixamorig:" + name});
  const mbk::Model mix = mbk::model_from_bvh(mbk::parse_bvh(renamed(path, mixamo), "mix.bvh"),
                                             {0.01, kMass, "female"});
  ASSERT_EQ(bio.body_count(), cmu.body_count());
  for (int k = 1; k <= cmu.body_count(); ++k) {
    EXPECT_EQ(bio.bodies[k].mass, cmu.bodies[k].mass) << cmu.bodies[k].name;
    EXPECT_EQ(mix.bodies[k].mass, cmu.bodies[k].mass) << cmu.bodies[k].name;
    EXPECT_EQ(mix.bodies[k].mass_center, cmu.bodies[k].mass_center) << cmu.bodies[k].name;
  }
  EXPECT_EQ(body(bio, "LeftElbow").mass, body(cmu, "LeftForeArm").mass);
  EXPECT_GT(body(cmu, "LeftForeArm").mass, 0);
}

// CMU's cgspeed conversions name the neck lowerneck, Neck: CERV is the lowest *neck* joint.
TEST(DeLeva, TheHeadReachesDownToTheLowestNeckJoint) {
  const std::string text = renamed(mbk_test::source_path("test/io/data/cmu_walk.bvh"),
                                   {{"Neck", "lowerneck"}, {"Neck1", "Neck"}});
  const mbk::Model model =
      mbk::model_from_bvh(mbk::parse_bvh(text, "cgspeed.bvh"), {0.01, kMass, "male"});
  EXPECT_TRUE(
      body(model, "Head").mass_center.isApprox(Eigen::Vector3d(0, 0.18 - 0.5002 * 0.28, 0), 1e-12));
  EXPECT_TRUE(model.warnings.empty()) << model.warnings.front();
}

TEST(DeLeva, WhatIsNotMappedIsMasslessAndNamedInOneNote) {
  // Paws, not hands: they and their fingers are massless, the hands' fractions go to the others.
  const std::string text = renamed(mbk_test::source_path("test/io/data/cmu_walk.bvh"),
                                   {{"LeftHand", "LeftPaw"}, {"RightHand", "RightPaw"}});
  const mbk::Model model =
      mbk::model_from_bvh(mbk::parse_bvh(text, "cat.bvh"), {0.01, kMass, "male"});
  EXPECT_NEAR(total_mass(model), kMass, 1e-12 * kMass);
  ASSERT_EQ(model.warnings.size(), 1u);
  EXPECT_EQ(model.warnings[0],
            "cat.bvh: segment parameters (de Leva 1996): massless, in no table segment: LeftPaw, "
            "LeftFingerBase, LThumb, RightPaw, RightFingerBase, RThumb; not found (their mass "
            "spread over the others): left hand, right hand");
  EXPECT_EQ(body(model, "LeftPaw").mass, 0.0);
  EXPECT_NEAR(body(model, "LeftUpLeg").mass, kMass * 0.1416 / (1 - 2 * 0.0061), 1e-12);
  // With no hand the forearm ends at its own tip, the paw's joint (25 cm along +x): its mass
  // center 45.74 % of the way and its inertia finite (it once read past the skeleton's start).
  const mbk::Body& forearm = body(model, "LeftForeArm");
  EXPECT_TRUE(forearm.mass_center.isApprox(Eigen::Vector3d(0.4574 * 0.25, 0, 0), 1e-12))
      << forearm.mass_center.transpose();
  EXPECT_TRUE(forearm.inertia.allFinite());
  EXPECT_GT(forearm.inertia(1, 1), 0.0);
}

// A skeleton whose root is the neck has no spine below it for the trunk: the trunk is not found
// (its mass spread over the head) rather than put on the first body of an empty spine (it once
// read past the end of an empty list).
TEST(DeLeva, ANeckAtTheRootLeavesTheTrunkOut) {
  const std::string text =
      "HIERARCHY\nROOT Neck\n{\n  OFFSET 0 0 0\n"
      "  CHANNELS 6 Xposition Yposition Zposition Xrotation Yrotation Zrotation\n"
      "  JOINT Head\n  {\n    OFFSET 0 100 0\n    CHANNELS 3 Xrotation Yrotation Zrotation\n"
      "    End Site\n    {\n      OFFSET 0 50 0\n    }\n  }\n}\n"
      "MOTION\nFrames: 1\nFrame Time: 0.01\n0 0 0 0 0 0 0 0 0\n";
  const mbk::Model model =
      mbk::model_from_bvh(mbk::parse_bvh(text, "neck.bvh"), {0.01, kMass, "male"});
  EXPECT_NEAR(total_mass(model), kMass, 1e-12 * kMass);
  EXPECT_EQ(body(model, "Head").mass, kMass);
  EXPECT_EQ(body(model, "Neck").mass, 0.0);
  ASSERT_EQ(model.warnings.size(), 1u);
  EXPECT_NE(model.warnings[0].find("not found (their mass spread over the others): upper trunk, "
                                   "middle trunk, lower trunk, left upper arm"),
            std::string::npos)
      << model.warnings[0];
}

}  // namespace
