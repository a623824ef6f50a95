// Segment parameters of BVH skeletons from de Leva (1996) (mb_kinematics/io/bvh_anthropometry.h):
// the table's fractions, the whole-body mass, a segment's mass center and inertia placed as the
// table says, the CMU, Biovision and Mixamo names, the one note for what is not mapped.
#include "mb_kinematics/io/bvh_anthropometry.h"

#include <gtest/gtest.h>

#include <algorithm>
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
#include "mb_kinematics/io/bvh_motion_check.h"
#include "test/support/renamed_bvh.h"
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

using mbk_test::renamed;

// The same skeleton with the bones renamed as Biovision (LeftHip, LeftKnee, LeftAnkle, Chest,
// LeftCollar, LeftShoulder, LeftElbow, LeftWrist) and Mixamo (mixamorig:...) name them.
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

// Every body's mass and mass center in `other` as in `cmu` (the same skeleton renamed).
void expect_the_same_masses(const mbk::Model& cmu, const mbk::Model& other) {
  ASSERT_EQ(other.body_count(), cmu.body_count());
  for (int k = 1; k <= cmu.body_count(); ++k) {
    EXPECT_EQ(other.bodies[k].mass, cmu.bodies[k].mass) << other.bodies[k].name;
    EXPECT_EQ(other.bodies[k].mass_center, cmu.bodies[k].mass_center) << other.bodies[k].name;
  }
  EXPECT_TRUE(other.warnings.empty()) << other.warnings.front();
}

// Sides as suffixes and other prefixes: Bandai Namco's UpperArm_L, Blender's upper_arm.L, SMPL's
// L_Shoulder; each finds every segment on the bodies CMU's names give.
TEST(DeLeva, SideSuffixesAndPrefixesOfOtherFamiliesMapAsCmus) {
  const std::string path = mbk_test::source_path("test/io/data/cmu_walk.bvh");
  const mbk::Model cmu = mbk::model_from_bvh(cmu_walk(), {0.01, kMass, "male"});
  using Name = std::string (*)(const std::string& side, const std::string& part);
  struct Family {
    const char* name;
    Name name_of;
    std::vector<std::string> parts;  // for CMU's UpLeg Leg Foot ToeBase Shoulder Arm ForeArm Hand
  };
  const std::vector<Family> families = {
      {"bandai",
       [](const std::string& side, const std::string& part) { return part + "_" + side; },
       {"UpperLeg", "LowerLeg", "Foot", "Toes", "Shoulder", "UpperArm", "LowerArm", "Hand"}},
      {"blender",
       [](const std::string& side, const std::string& part) { return part + "." + side; },
       {"thigh", "shin", "foot", "toe", "shoulder", "upper_arm", "forearm", "hand"}},
      {"smpl",
       [](const std::string& side, const std::string& part) { return side + "_" + part; },
       {"Hip", "Knee", "Ankle", "Foot", "Collar", "Shoulder", "Elbow", "Wrist"}}};
  const std::vector<std::string> cmu_parts = {"UpLeg",    "Leg", "Foot",    "ToeBase",
                                              "Shoulder", "Arm", "ForeArm", "Hand"};
  for (const Family& family : families) {
    std::vector<std::pair<std::string, std::string>> names;
    for (const std::string side : {"Left", "Right"})
      for (size_t i = 0; i < cmu_parts.size(); ++i)
        names.push_back({side + cmu_parts[i], family.name_of(side.substr(0, 1), family.parts[i])});
    SCOPED_TRACE(family.name);
    const mbk::Model other =
        mbk::model_from_bvh(mbk::parse_bvh(renamed(path, names), std::string(family.name) + ".bvh"),
                            {0.01, kMass, "male"});
    EXPECT_GT(body(other, names[1].second).mass, 0);  // the left shank
    expect_the_same_masses(cmu, other);
  }
}

// A skeleton whose names no rule knows: a map of its own (--segments) gives every segment.
TEST(DeLeva, AMapOfJointsToSegmentsGivesWhatTheNamesDoNot) {
  const std::string path = mbk_test::source_path("test/io/data/cmu_walk.bvh");
  const mbk::Model cmu = mbk::model_from_bvh(cmu_walk(), {0.01, kMass, "male"});
  std::vector<std::pair<std::string, std::string>> names;
  std::string yaml;
  const std::vector<std::pair<std::string, std::string>> parts = {
      {"UpLeg", "thigh"},   {"Leg", "shank"},       {"Foot", "foot"},
      {"Arm", "upper_arm"}, {"ForeArm", "forearm"}, {"Hand", "hand"}};
  int n = 0;
  for (const std::string side : {"Left", "Right"})
    for (const auto& [cmu_part, segment] : parts) {
      const std::string bone = "Bone" + std::to_string(++n);
      names.push_back({side + cmu_part, bone});
      yaml += bone + ": " + (side == "Left" ? "left_" : "right_") + segment + "\n";
    }
  names.push_back({"Head", "Skull"});
  yaml += "Skull: head\n";
  const mbk::BvhFile bvh = mbk::parse_bvh(renamed(path, names), "bones.bvh");
  const mbk::Model unmapped = mbk::model_from_bvh(bvh, {0.01, kMass, "male"});
  EXPECT_EQ(body(unmapped, "Bone2").mass, 0.0);  // the rules find no shank
  const std::string map = testing::TempDir() + "bones_segments.yaml";
  std::ofstream(map) << yaml;
  mbk::BvhModelOptions options{0.01, kMass, "male"};
  options.segments = map;
  expect_the_same_masses(cmu, mbk::model_from_bvh(bvh, options));
  // A joint the skeleton does not have is an error naming the map.
  std::ofstream(map) << "Tail: head\n";
  try {
    mbk::model_from_bvh(bvh, options);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), map + ": joint Tail is not in bones.bvh");
  }
}

// The walk under a ROOT that stays at 0 (Bandai Namco's joint_Root) with the pelvis 4.5 m from
// it, the legs named as no rule knows: the trunk's parts go on the moving spine, never on the
// static root (whose origin once stood for the hips' center when no thigh was found).
TEST(DeLeva, AStaticRootCarriesNoMovingSegment) {
  const std::string plain =
      renamed(mbk_test::source_path("test/io/data/cmu_walk.bvh"), {{"LeftUpLeg", "Femur_A"},
                                                                   {"LeftLeg", "Tibia_A"},
                                                                   {"LeftFoot", "Pes_A"},
                                                                   {"RightUpLeg", "Femur_B"},
                                                                   {"RightLeg", "Tibia_B"},
                                                                   {"RightFoot", "Pes_B"}});
  std::string text = plain;
  const std::string root = "ROOT Hips\n{\n  OFFSET 0 0 0\n";
  text.replace(text.find(root), root.size(),
               "ROOT joint_Root\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition "
               "Zrotation Xrotation Yrotation\n  JOINT Hips\n  {\n  OFFSET 0 90 -450\n");
  text.replace(text.find("MOTION"), 0, "}\n");
  for (size_t at = text.find("Frame Time:");
       (at = text.find('\n', at)) != std::string::npos && at + 1 < text.size(); ++at)
    text.insert(at + 1, "0 0 0 0 0 0 ");
  const mbk::Model model =
      mbk::model_from_bvh(mbk::parse_bvh(text, "bandai.bvh"), {0.01, kMass, "male"});
  EXPECT_EQ(body(model, "joint_Root").mass, 0.0);
  // Every body's mass as without the static root.
  const mbk::Model without =
      mbk::model_from_bvh(mbk::parse_bvh(plain, "plain.bvh"), {0.01, kMass, "male"});
  for (int k = 1; k <= without.body_count(); ++k)
    EXPECT_NEAR(body(model, without.bodies[k].name).mass, without.bodies[k].mass, 1e-12 * kMass)
        << without.bodies[k].name;
  EXPECT_NEAR(total_mass(model), kMass, 1e-12 * kMass);
  // The thighs, shanks and feet are not found: one line says the whole body is incomplete.
  const std::string incomplete =
      "bandai.bvh: whole-body outputs incomplete (system_incomplete in the CSV, "
      "system.missing_segments in the bag, \"incomplete\" in mbk eval's JSON; --segments FILE maps "
      "joints to segments): segments not found, their mass spread over the others: left thigh, "
      "right thigh, left shank, right shank, left foot, right foot";
  EXPECT_NE(std::find(model.warnings.begin(), model.warnings.end(), incomplete),
            model.warnings.end())
      << model.warnings.front();
  EXPECT_EQ(mbk::missing_segments(mbk::parse_bvh(text, "bandai.bvh"), 0.01).size(), 6u);
  EXPECT_TRUE(mbk::missing_segments(cmu_walk(), 0.01).empty());
}

// The whole motion against a human's: all the mass on one foot puts the mass center at the
// floor, which the check names with the segments not found as the likely cause.
TEST(DeLeva, AMassCenterNoHumanHasIsWarnedAboutWithTheLikelyCause) {
  const mbk::BvhFile bvh = cmu_walk();
  mbk::Model model = mbk::model_from_bvh(bvh, {0.01, kMass, "male"});
  EXPECT_EQ(mbk::motion_warning(bvh, model, 0.01, ""), "");
  const mbk::MotionFigures human = mbk::motion_figures(bvh, model, 0.01);
  EXPECT_EQ(human.up, 1);
  EXPECT_GT(human.mass_center_height / human.height, 0.35);
  EXPECT_LT(human.mass_center_height / human.height, 0.75);
  for (mbk::Body& b : model.bodies) b.mass = 0;
  model.bodies[model.body_index("LeftFoot")].mass = kMass;
  const std::string warning = mbk::motion_warning(bvh, model, 0.01, "left hand, right hand");
  EXPECT_NE(warning.find("the whole-body mass center is not a human's"), std::string::npos)
      << warning;
  EXPECT_NE(warning.find("likely cause: segments not found, left hand, right hand"),
            std::string::npos)
      << warning;
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
  ASSERT_EQ(model.warnings.size(), 2u);
  EXPECT_EQ(model.warnings[0],
            "cat.bvh: segment parameters (de Leva 1996): massless, in no table segment: LeftPaw, "
            "LeftFingerBase, LThumb, RightPaw, RightFingerBase, RThumb");
  EXPECT_EQ(model.warnings[1],
            "cat.bvh: whole-body outputs incomplete (system_incomplete in the CSV, "
            "system.missing_segments in the bag, \"incomplete\" in mbk eval's JSON; --segments "
            "FILE maps joints to segments): segments not found, their mass spread over the "
            "others: left hand, right hand");
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
  EXPECT_NE(model.warnings[0].find("segments not found, their mass spread over the others: upper "
                                   "trunk, middle trunk, lower trunk, left upper arm"),
            std::string::npos)
      << model.warnings[0];
}

}  // namespace
