// A BVH skeleton as a Model (mb_kinematics/io/bvh_model.h): joint types from the channels,
// offsets as joint origins, frames as coordinates; the model's joint positions against a forward
// kinematics of the BVH written here from the file format's definition.
#include "mb_kinematics/io/bvh_model.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/io/bvh_bones.h"

namespace {

// A 6-channel root, a free non-root joint, one- and two-rotation joints, a fixed one, End Sites;
// every rotation order X Y Z here (kMixed below has others).
const char kSkeleton[] =
    "HIERARCHY\n"                                                                 // 1
    "ROOT Hips\n"                                                                 // 2
    "{\n"                                                                         // 3
    "  OFFSET 10 90 -5\n"                                                         // 4
    "  CHANNELS 6 Xposition Yposition Zposition Xrotation Yrotation Zrotation\n"  // 5
    "  JOINT LeftUpLeg\n"                                                         // 6
    "  {\n"                                                                       // 7
    "    OFFSET 10 -5 0\n"                                                        // 8
    "    CHANNELS 3 Xrotation Yrotation Zrotation\n"                              // 9
    "    JOINT LeftLeg\n"                                                         // 10
    "    {\n"                                                                     // 11
    "      OFFSET 0 -40 1\n"                                                      // 12
    "      CHANNELS 1 Xrotation\n"                                                // 13
    "      End Site\n"                                                            // 14
    "      {\n"                                                                   // 15
    "        OFFSET 0 -42 0\n"                                                    // 16
    "      }\n"                                                                   // 17
    "    }\n"                                                                     // 18
    "  }\n"                                                                       // 19
    "  JOINT Chest\n"                                                             // 20
    "  {\n"                                                                       // 21
    "    OFFSET 0 30 0\n"                                                         // 22
    "    CHANNELS 2 Xrotation Yrotation\n"                                        // 23
    "    JOINT Neck\n"                                                            // 24
    "    {\n"                                                                     // 25
    "      OFFSET 0 25 0\n"                                                       // 26
    "      CHANNELS 4 Zposition Xposition Xrotation Yrotation\n"                  // 27
    "      JOINT Head\n"                                                          // 28
    "      {\n"                                                                   // 29
    "        OFFSET 0 8 2\n"                                                      // 30
    "        CHANNELS 0\n"                                                        // 31
    "        End Site\n"                                                          // 32
    "        {\n"                                                                 // 33
    "          OFFSET 0 20 0\n"                                                   // 34
    "        }\n"                                                                 // 35
    "      }\n"                                                                   // 36
    "    }\n"                                                                     // 37
    "  }\n"                                                                       // 38
    "}\n"                                                                         // 39
    "MOTION\n"                                                                    // 40
    "Frames: 2\n"                                                                 // 41
    "Frame Time: 0.01\n"                                                          // 42
    "0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0\n"                                           // 43
    "1.5 -2 3 10 -20 30 40 -50 60 -70 15 25 3 -4 35 -45\n";                       // 44

// kSkeleton with the orders of real files mixed: the root as CMU's (ZYX), a proper Euler order
// (ZXZ), a pair that is not X Y (Z X: a ball ZXY whose gamma stays 0), a free joint turning about
// Y then Z (YZX).
std::string mixed() {
  std::string text = kSkeleton;
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"Zposition Xrotation Yrotation Zrotation", "Zposition Zrotation Yrotation Xrotation"},
           {"CHANNELS 3 Xrotation Yrotation Zrotation", "CHANNELS 3 Zrotation Xrotation Zrotation"},
           {"CHANNELS 2 Xrotation Yrotation", "CHANNELS 2 Zrotation Xrotation"},
           {"Zposition Xposition Xrotation Yrotation", "Zposition Xposition Yrotation Zrotation"}})
    text.replace(text.find(from), from.size(), to);
  return text;
}

// kSkeleton with Neck's position channels (z, x) in frame 1 as in frame 0: its bone keeps its
// length.
std::string rigid() {
  std::string text = kSkeleton;
  text.replace(text.find("3 -4 35 -45"), 11, "0 0 35 -45");
  return text;
}

constexpr double kScale = 0.01;  // centimetres
constexpr double kDeg = 3.14159265358979323846 / 180.0;

mbk::Model model_of(const std::string& text, const mbk::BvhModelOptions& options = {kScale}) {
  return mbk::model_from_bvh(mbk::parse_bvh(text, "walk.bvh"), options);
}

std::string error_of(const std::string& text) {
  try {
    model_of(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

TEST(BvhModel, EachSegmentIsABodyOnTheJointItsChannelsMake) {
  const mbk::Model model = model_of(kSkeleton);
  ASSERT_EQ(model.body_count(), 6);
  const std::vector<std::string> names = {"Hips", "LeftUpLeg", "LeftLeg", "Chest", "Neck", "Head"};
  const std::vector<int> lower = {0, 1, 2, 1, 4, 5};
  const std::vector<mbk::JointType> types = {mbk::JointType::kFree123,  mbk::JointType::kBall123,
                                             mbk::JointType::kRevolute, mbk::JointType::kUniversal,
                                             mbk::JointType::kFree123,  mbk::JointType::kFixed};
  for (int k = 1; k <= 6; ++k) {
    EXPECT_EQ(model.bodies[k].name, names[k - 1]);
    EXPECT_EQ(model.bodies[k].lower, lower[k - 1]);
    EXPECT_EQ(model.bodies[k].joint.type, types[k - 1]) << names[k - 1];
    EXPECT_EQ(model.bodies[k].mass, 0.0);
  }
  EXPECT_EQ(model.bodies[3].joint.axis, Eigen::Vector3d::UnitX());
  EXPECT_TRUE(model.bodies[3].joint.offset.isApprox(Eigen::Vector3d(0, -0.40, 0.01), 1e-15));
  EXPECT_TRUE(model.bodies[1].joint.offset.isApprox(Eigen::Vector3d(0.10, 0.90, -0.05), 1e-15));
  const std::vector<std::string> coordinates = {
      "Hips/x",      "Hips/y",          "Hips/z",         "Hips/alpha",      "Hips/beta",
      "Hips/gamma",  "LeftUpLeg/alpha", "LeftUpLeg/beta", "LeftUpLeg/gamma", "LeftLeg",
      "Chest/alpha", "Chest/beta",      "Neck/x",         "Neck/y",          "Neck/z",
      "Neck/alpha",  "Neck/beta",       "Neck/gamma"};
  EXPECT_EQ(model.coordinate_names, coordinates);
  // Neck's position channels (z and x) replace its OFFSET's: (0, 25, 0) cm, then (-4, 25, 3).
  EXPECT_TRUE(model.bodies[5].joint.offset.isApprox(Eigen::Vector3d(0, 0.25, 0), 1e-15));
  ASSERT_EQ(model.warnings.size(), 1u);
  EXPECT_NE(model.warnings[0].find("bone lengths change during the motion"), std::string::npos)
      << model.warnings[0];
  EXPECT_NE(model.warnings[0].find(": Neck 0.25-0.255 m"), std::string::npos) << model.warnings[0];
}

TEST(BvhModel, FrameValuesBecomeCoordinatesInRadiansAndMetres) {
  const mbk::BvhFile bvh = mbk::parse_bvh(kSkeleton, "walk.bvh");
  const mbk::Model model = mbk::model_from_bvh(bvh, {kScale});
  const std::vector<double> q = mbk::bvh_frame_coordinates(bvh, model, 1, kScale);
  // Neck's "Zposition Xposition" go to z and x whatever their order; its y and gamma stay 0.
  const std::vector<double> expected = {0.015,     -0.02,      0.03,       10 * kDeg, -20 * kDeg,
                                        30 * kDeg, 40 * kDeg,  -50 * kDeg, 60 * kDeg, -70 * kDeg,
                                        15 * kDeg, 25 * kDeg,  -0.04,      0,         0.03,
                                        35 * kDeg, -45 * kDeg, 0};
  ASSERT_EQ(q.size(), expected.size());
  for (size_t i = 0; i < q.size(); ++i) EXPECT_NEAR(q[i], expected[i], 1e-15) << i;
  EXPECT_THROW(mbk::bvh_frame_coordinates(bvh, model, 2, kScale), std::invalid_argument);
}

// The BVH format's own forward kinematics as exporters mean it: a segment's origin is its
// parent's origin plus the parent's rotation times its translation (the ROOT's: OFFSET + position
// channels; a JOINT's: the OFFSET with its position channels' axes replaced by their values); its
// rotation is the parent's times the
// rotation channels' elementary rotations in channel order.
struct Poses {
  std::vector<Eigen::Vector3d> origin;
  std::vector<Eigen::Matrix3d> rotation;
};

Poses bvh_poses(const mbk::BvhFile& bvh, int frame) {
  std::vector<Eigen::Vector3d> origin(bvh.segments.size());
  std::vector<Eigen::Matrix3d> rotation(bvh.segments.size());
  for (size_t i = 0; i < bvh.segments.size(); ++i) {
    const mbk::BvhSegment& s = bvh.segments[i];
    Eigen::Vector3d translation = s.offset;
    Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();
    for (size_t c = 0; c < s.channels.size(); ++c) {
      const int axis = static_cast<int>(s.channels[c]) % 3;
      const double value = bvh.value(frame, s.first_column + static_cast<int>(c));
      if (mbk::is_rotation(s.channels[c]))
        turn = turn * Eigen::AngleAxisd(value * kDeg, Eigen::Vector3d::Unit(axis)).matrix();
      else if (s.parent < 0)
        translation[axis] += value;
      else
        translation[axis] = value;
    }
    const bool root = s.parent < 0;
    origin[i] =
        root ? translation : Eigen::Vector3d(origin[s.parent] + rotation[s.parent] * translation);
    rotation[i] = root ? turn : Eigen::Matrix3d(rotation[s.parent] * turn);
  }
  for (Eigen::Vector3d& p : origin) p *= kScale;
  return {origin, rotation};
}

void expect_the_formats_forward_kinematics(const std::string& text) {
  const mbk::BvhFile bvh = mbk::parse_bvh(text, "walk.bvh");
  const mbk::Model model = mbk::model_from_bvh(bvh, {kScale});
  mbk::JointState<double> state(model);
  mbk::Data<double> data(model);
  const std::vector<double> q = mbk::bvh_frame_coordinates(bvh, model, 1, kScale);
  state.position = Eigen::Map<const Eigen::VectorXd>(q.data(), q.size());
  mbk::forward_kinematics(model, state, data);
  const Poses expected = bvh_poses(bvh, 1);
  for (int k = 1; k <= model.body_count(); ++k) {
    EXPECT_LT((data.origin[k] - expected.origin[k - 1]).norm(),
              1e-12 * expected.origin[k - 1].norm())
        << model.bodies[k].name << ": " << data.origin[k].transpose() << " vs "
        << expected.origin[k - 1].transpose();
    EXPECT_LT((data.rotation[k] - expected.rotation[k - 1]).norm(), 1e-14) << model.bodies[k].name;
  }
}

TEST(BvhModel, JointPositionsAgreeWithTheFormatsForwardKinematics) {
  expect_the_formats_forward_kinematics(kSkeleton);
}

// Every joint with 6 channels whose positions repeat the OFFSET (Bandai Namco's and LAFAN1's
// layout): the channels are the translation, so the skeleton keeps its OFFSET lengths; added to
// the OFFSET they would double every bone (the head at 2 x 60 cm above the hips).
TEST(BvhModel, PositionChannelsOfAJointAreItsTranslationNotAnIncrement) {
  const char text[] =
      "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n"
      " CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"
      " JOINT Spine\n {\n  OFFSET 0 20 0\n"
      "  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"
      "  JOINT Head\n  {\n   OFFSET 0 40 0\n"
      "   CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"
      "   End Site\n   {\n    OFFSET 0 10 0\n   }\n  }\n }\n}\n"
      "MOTION\nFrames: 2\nFrame Time: 0.01\n"
      "5 90 1 0 0 0 0 20 0 0 0 0 0 40 0 0 0 0\n"
      "7 91 2 0 0 0 0 20 0 0 0 0 0 40 0 0 0 0\n";
  const mbk::BvhFile bvh = mbk::parse_bvh(text, "walk.bvh");
  const mbk::Model model = mbk::model_from_bvh(bvh, {kScale});
  EXPECT_TRUE(model.warnings.empty()) << model.warnings.front();
  mbk::JointState<double> state(model);
  mbk::Data<double> data(model);
  const std::vector<double> q = mbk::bvh_frame_coordinates(bvh, model, 1, kScale);
  state.position = Eigen::Map<const Eigen::VectorXd>(q.data(), q.size());
  mbk::forward_kinematics(model, state, data);
  EXPECT_LT((data.origin[3] - Eigen::Vector3d(0.07, 0.91 + 0.60, 0.02)).norm(), 1e-12)
      << data.origin[3].transpose();
  expect_the_formats_forward_kinematics(text);
}

// A bone whose position channels change its length is named with its range, in metres.
TEST(BvhModel, BonesThatChangeLengthAreNamedWithTheirRange) {
  const mbk::BvhFile bvh = mbk::parse_bvh(kSkeleton, "walk.bvh");
  const std::vector<mbk::BoneLength> bones = mbk::changing_bones(bvh, kScale);
  ASSERT_EQ(bones.size(), 1u);
  EXPECT_EQ(bones[0].name, "Neck");
  EXPECT_NEAR(bones[0].min, 0.25, 1e-15);
  EXPECT_NEAR(bones[0].max, std::sqrt(0.04 * 0.04 + 0.25 * 0.25 + 0.03 * 0.03), 1e-15);
  // The same values in both frames: no change, no warning.
  EXPECT_TRUE(mbk::changing_bones(mbk::parse_bvh(rigid(), "walk.bvh"), kScale).empty());
}

// Under a ROOT that stays at 0 (Bandai Namco's joint_Root), the first JOINT's position channels
// are the skeleton's motion, not a bone: they change, and nothing is warned.
TEST(BvhModel, AJointUnderARootFixedInSpaceCarriesTheMotionNotABone) {
  const char text[] =
      "HIERARCHY\nROOT joint_Root\n{\n OFFSET 0 0 0\n"
      " CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
      " JOINT Hips\n {\n  OFFSET 1 90 -450\n"
      "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
      "  End Site\n  {\n   OFFSET 0 -90 0\n  }\n }\n}\n"
      "MOTION\nFrames: 2\nFrame Time: 0.01\n"
      "0 0 0 0 0 0 -0.5 93 -9 0 0 0\n"
      "0 0 0 0 0 0 -0.7 93 -8 0 0 0\n";
  const mbk::BvhFile bvh = mbk::parse_bvh(text, "walk.bvh");
  EXPECT_EQ(mbk::fixed_in_space(bvh), (std::vector<bool>{true, false}));
  EXPECT_TRUE(mbk::changing_bones(bvh, kScale).empty());
}

TEST(BvhModel, MixedOrdersAgreeWithTheFormatsForwardKinematics) {
  const mbk::Model model = model_of(mixed());
  const std::vector<mbk::JointType> types = {mbk::JointType::kFree123,  mbk::JointType::kBall123,
                                             mbk::JointType::kRevolute, mbk::JointType::kBall123,
                                             mbk::JointType::kFree123,  mbk::JointType::kFixed};
  const std::vector<mbk::EulerOrder> orders = {mbk::EulerOrder::kZYX, mbk::EulerOrder::kZXZ,
                                               mbk::EulerOrder::kXYZ, mbk::EulerOrder::kZXY,
                                               mbk::EulerOrder::kYZX, mbk::EulerOrder::kXYZ};
  for (int k = 1; k <= 6; ++k) {
    EXPECT_EQ(model.bodies[k].joint.type, types[k - 1]) << k;
    EXPECT_EQ(model.bodies[k].joint.euler_order, orders[k - 1]) << k;
  }
  expect_the_formats_forward_kinematics(mixed());
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

TEST(BvhModel, ChannelsNoJointTakesNameTheirSegmentsLine) {
  const char* const neck = "CHANNELS 4 Zposition Xposition Xrotation Yrotation";
  const std::vector<std::array<const char*, 3>> cases = {
      // channels, replaced by, error
      {"CHANNELS 2 Xrotation Yrotation", "CHANNELS 2 Yrotation Yrotation",
       "walk.bvh:20: JOINT Chest: two successive rotations about one axis"},
      {neck, "CHANNELS 4 Xrotation Yrotation Zrotation Xrotation",
       "walk.bvh:24: JOINT Neck: more than three rotation channels"},
      {neck, "CHANNELS 4 Zposition Zposition Xrotation Yrotation",
       "walk.bvh:24: JOINT Neck: two position channels along one axis"},
      {"Zposition Xrotation Yrotation Zrotation", "Zposition Xrotation Xrotation Zrotation",
       "walk.bvh:2: ROOT Hips: two successive rotations about one axis"}};
  for (const auto& [from, to, error] : cases)
    EXPECT_EQ(error_of(replaced(kSkeleton, from, to)), error);
}

TEST(BvhModel, ASegmentNameUsedTwiceNamesBothLines) {
  EXPECT_EQ(error_of(replaced(kSkeleton, "JOINT Head", "JOINT LeftLeg")),
            "walk.bvh:28: JOINT LeftLeg: a second segment of this name (the first at line 10)");
}

TEST(BvhModel, AScaleThatMakesNoHumanIsWarnedAbout) {
  const mbk::Model metres = model_of(rigid(), {kScale});
  EXPECT_TRUE(metres.warnings.empty()) << metres.warnings.front();
  const mbk::Model centimetres = model_of(rigid(), {1.0});
  ASSERT_EQ(centimetres.warnings.size(), 1u);
  EXPECT_NE(centimetres.warnings[0].find("standing height is 170 m"), std::string::npos)
      << centimetres.warnings[0];
  // The warning names the scale that makes the skeleton human (here: centimetres).
  EXPECT_NE(centimetres.warnings[0].find(": --scale 0.01 (bvh.launch scale:=0.01, the node's "
                                         "~scale) gives 1.7 m (file units in centimetres)"),
            std::string::npos)
      << centimetres.warnings[0];
  EXPECT_THROW(model_of(kSkeleton, {-1.0}), std::invalid_argument);
}

// A two-bone skeleton `2 bone` file units tall.
std::string skeleton_of_height(const std::string& bone) {
  return "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\nJOINT Spine\n{\nOFFSET 0 " +
         bone + " 0\nCHANNELS 1 Xrotation\nEnd Site\n{\nOFFSET 0 " + bone +
         " 0\n}\n}\n}\nMOTION\nFrames: 1\nFrame Time: 0.01\n0 0\n";
}

// The --scale a height warning suggests ("" when it suggests none).
std::string suggested_scale(const std::string& warning) {
  const std::string key = ": --scale ";
  const size_t at = warning.find(key);
  if (at == std::string::npos) return "";
  const size_t begin = at + key.size();
  return warning.substr(begin, warning.find(' ', begin) - begin);
}

TEST(BvhModel, AHeightWarningSuggestsOnlyAScaleThatScaleAccepts) {
  // Tiny and huge skeletons that a --scale makes human: the one suggested does.
  for (const std::string height : {"1e-9", "1e-300", "1e300"}) {
    SCOPED_TRACE(height);
    const mbk::Model model = model_of(skeleton_of_height(height), {1.0});
    ASSERT_EQ(model.warnings.size(), 1u);
    const std::string scale = suggested_scale(model.warnings[0]);
    ASSERT_FALSE(scale.empty()) << model.warnings[0];
    const mbk::BvhModelOptions options = mbk::bvh_model_options(scale, "", "", "");
    EXPECT_TRUE(model_of(skeleton_of_height(height), options).warnings.empty());
  }
  // Skeletons no double --scale makes human: named, and no scale suggested.
  for (const auto& [height, what] :
       {std::pair<std::string, std::string>{"1e-320", "small"}, {"1e308", "large"}}) {
    SCOPED_TRACE(height);
    const mbk::Model model = model_of(skeleton_of_height(height), {1.0});
    ASSERT_EQ(model.warnings.size(), 1u);
    EXPECT_EQ(suggested_scale(model.warnings[0]), "") << model.warnings[0];
    EXPECT_NE(model.warnings[0].find("walk.bvh: the skeleton's standing height is "),
              std::string::npos)
        << model.warnings[0];
    EXPECT_NE(model.warnings[0].find("too " + what + " for any --scale"), std::string::npos)
        << model.warnings[0];
  }
}

}  // namespace
