// The real recordings (test/mocap/: CMU trials 131_01, start, walk, stop, and 131_03, start, hop,
// stop; two Euler orders in one skeleton) through the BVH loader and the core, against a forward
// kinematics of the BVH written here on its own (long double, the file's channels composed in the
// file's order): every joint position to 1e-12 relative, every segment's angular velocity against a
// central difference of the orientations, and the whole-body mass against --body-mass.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/io/bvh.h"
#include "mb_kinematics/io/bvh_model.h"

namespace {

using Mat3L = Eigen::Matrix<long double, 3, 3>;
using Vec3L = Eigen::Matrix<long double, 3, 1>;

// A recording of test/mocap/ and its number of frames.
struct Recording {
  const char* file;
  int frames;
};
const Recording kRecordings[] = {{"131_01.bvh", 994}, {"131_03.bvh", 1102}};
constexpr double kCmuScale = 0.0254 / 0.45;  // metres per CMU unit (test/mocap/README.md)

// The BVH's pose of every segment at one frame, in the file's own terms: origins (scaled) and
// orientations in the root's fixed frame.
struct BvhPose {
  std::vector<Vec3L> origin;
  std::vector<Mat3L> rotation;
};

// The rotation by `degrees` about the x, y or z axis.
Mat3L axis_rotation(mbk::BvhChannel channel, long double degrees) {
  const long double a = degrees * 3.141592653589793238462643383279502884L / 180;
  const long double c = std::cos(a), s = std::sin(a);
  Mat3L r = Mat3L::Identity();
  const int axis = channel == mbk::BvhChannel::kXrotation   ? 0
                   : channel == mbk::BvhChannel::kYrotation ? 1
                                                            : 2;
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  r(i, i) = c;
  r(i, j) = -s;
  r(j, i) = s;
  r(j, j) = c;
  return r;
}

int position_axis(mbk::BvhChannel channel) {
  return channel == mbk::BvhChannel::kXposition   ? 0
         : channel == mbk::BvhChannel::kYposition ? 1
                                                  : 2;
}

// Forward kinematics of one frame given as channel values `row` (bvh.channel_count of them):
// each segment at its parent's origin plus the parent's rotation times its offset (plus, for
// the root, its position channels); its rotation the parent's times the channel rotations in
// the order the file lists them.
BvhPose bvh_pose(const mbk::BvhFile& bvh, const std::vector<long double>& row, long double scale) {
  BvhPose pose;
  for (const mbk::BvhSegment& s : bvh.segments) {
    Vec3L local = s.offset.cast<long double>() * scale;
    Mat3L turn = Mat3L::Identity();
    for (size_t c = 0; c < s.channels.size(); ++c) {
      const long double v = row[s.first_column + c];
      if (mbk::is_rotation(s.channels[c]))
        turn = turn * axis_rotation(s.channels[c], v);
      else
        local[position_axis(s.channels[c])] += v * scale;
    }
    if (s.parent < 0) {
      pose.origin.push_back(local);
      pose.rotation.push_back(turn);
    } else {
      pose.origin.push_back(pose.origin[s.parent] + pose.rotation[s.parent] * local);
      pose.rotation.push_back(pose.rotation[s.parent] * turn);
    }
  }
  return pose;
}

std::vector<long double> frame_row(const mbk::BvhFile& bvh, int frame) {
  std::vector<long double> row(bvh.channel_count);
  for (int c = 0; c < bvh.channel_count; ++c) row[c] = bvh.value(frame, c);
  return row;
}

// The angular velocity (in the fixed frame) that turns `before` into `after` in time 2h at a
// constant rate: the central difference of the orientations, axis times angle of
// after * before^T over 2h.
Vec3L central_omega(const Mat3L& before, const Mat3L& after, long double h) {
  const Eigen::AngleAxis<long double> turn(Mat3L(after * before.transpose()));
  return turn.axis() * turn.angle() / (2 * h);
}

class RealRecording : public ::testing::TestWithParam<Recording> {
 protected:
  void SetUp() override {
    bvh_ = mbk::read_bvh(std::string(MBK_SOURCE_DIR) + "/test/mocap/" + GetParam().file);
    mbk::unwrap_rotations(bvh_);
    options_.scale = kCmuScale;
    options_.body_mass = 68.5;
    model_ = mbk::model_from_bvh(bvh_, options_);
    for (const mbk::BvhSegment& s : bvh_.segments) body_.push_back(model_.body_index(s.name));
  }
  // The model's state at `frame`, its speeds the central difference of the coordinates.
  mbk::JointState<double> state_at(int frame) const {
    mbk::JointState<double> state(model_);
    const auto q = [&](int f) {
      const std::vector<double> v = mbk::bvh_frame_coordinates(bvh_, model_, f, kCmuScale);
      return Eigen::Map<const Eigen::VectorXd>(v.data(), v.size()).eval();
    };
    state.position = q(frame);
    state.velocity = (q(frame + 1) - q(frame - 1)) / (2 * bvh_.frame_time);
    return state;
  }

  mbk::BvhFile bvh_;
  mbk::BvhModelOptions options_;
  mbk::Model model_;
  std::vector<int> body_;  // body_[segment]: its body in the model
};

TEST_P(RealRecording, TheRecordingIsTheOnePublished) {
  EXPECT_EQ(bvh_.segments.size(), 31u);
  EXPECT_EQ(bvh_.channel_count, 96);
  EXPECT_EQ(bvh_.frame_count, GetParam().frames);
  EXPECT_EQ(bvh_.frame_time, 0.0083333);
  for (int b : body_) EXPECT_GT(b, 0) << "a BVH segment is no body of the model";
}

// Every joint position (the origin O_k of every body) of every frame from the core equals the
// independent forward kinematics to 1e-12 of the skeleton's reach from R's origin.
TEST_P(RealRecording, JointPositionsAgreeWithAnIndependentForwardKinematics) {
  mbk::Data<double> data(model_);
  double worst = 0;
  for (int f = 1; f + 1 < bvh_.frame_count; ++f) {
    mbk::forward_kinematics(model_, state_at(f), data, mbk::Level::kPose);
    const BvhPose pose = bvh_pose(bvh_, frame_row(bvh_, f), kCmuScale);
    long double reach = 0;
    for (const Vec3L& p : pose.origin) reach = std::max(reach, p.norm());
    for (size_t s = 0; s < body_.size(); ++s) {
      const long double error = (data.origin[body_[s]].cast<long double>() - pose.origin[s]).norm();
      const long double turn =
          (data.rotation[body_[s]].cast<long double>() - pose.rotation[s]).norm();
      worst = std::max(worst, static_cast<double>(error / reach));
      ASSERT_LE(error, 1e-12L * reach) << bvh_.segments[s].name << " at frame " << f;
      ASSERT_LE(turn, 1e-12L) << bvh_.segments[s].name << " orientation at frame " << f;
    }
  }
  std::printf("worst joint position difference: %.3g of the reach\n", worst);
}

// The sum of the absolute rotation rates (rad/s) along each segment's chain, itself included:
// a bound on how fast its orientation turns along c(t) = c + t rate; the k-th derivative of
// R(c(t)) (a product of rotations about fixed axes at these rates) is at most its k-th power.
std::vector<long double> chain_rates(const mbk::BvhFile& bvh,
                                     const std::vector<long double>& rate) {
  std::vector<long double> sum;
  for (const mbk::BvhSegment& s : bvh.segments) {
    long double own = 0;
    for (size_t c = 0; c < s.channels.size(); ++c)
      if (mbk::is_rotation(s.channels[c])) own += std::fabs(rate[s.first_column + c]);
    own *= 3.141592653589793238462643383279502884L / 180;
    sum.push_back(s.parent < 0 ? own : own + sum[s.parent]);
  }
  return sum;
}

// Every segment's angular velocity from the core (coordinates and their central-difference
// rates at a frame) equals the central difference of the independent orientations along the
// same motion, c(t) = c_f + t c'_f in the file's channels, over a step h = 1e-6 s. The
// difference's error is at most h^2 / 6 times the third derivative of R, so below h^2 L^3 with L
// the segment's chain_rates; rounding adds about 1e-19 / h = 1e-13 rad/s in long double and the
// core's double about 1e-15 |omega|: 1e-9 rad/s covers both.
TEST_P(RealRecording, AngularVelocitiesAgreeWithDifferencesOfTheOrientations) {
  constexpr long double h = 1e-6L;
  mbk::Data<double> data(model_);
  double worst = 0, fastest = 0;
  for (int f = 1; f + 1 < bvh_.frame_count; ++f) {
    mbk::forward_kinematics(model_, state_at(f), data, mbk::Level::kVelocity);
    std::vector<long double> before = frame_row(bvh_, f), after = before;
    std::vector<long double> rate(bvh_.channel_count);
    for (int c = 0; c < bvh_.channel_count; ++c) {
      rate[c] = (static_cast<long double>(bvh_.value(f + 1, c)) - bvh_.value(f - 1, c)) /
                (2 * static_cast<long double>(bvh_.frame_time));
      before[c] -= h * rate[c];
      after[c] += h * rate[c];
    }
    const std::vector<long double> bound = chain_rates(bvh_, rate);
    const BvhPose p0 = bvh_pose(bvh_, before, kCmuScale), p1 = bvh_pose(bvh_, after, kCmuScale);
    for (size_t s = 0; s < body_.size(); ++s) {
      const Vec3L expected = central_omega(p0.rotation[s], p1.rotation[s], h);
      const long double error = (data.omega[body_[s]].cast<long double>() - expected).norm();
      worst = std::max(worst, static_cast<double>(error));
      fastest = std::max(fastest, static_cast<double>(expected.norm()));
      ASSERT_LE(error, h * h * bound[s] * bound[s] * bound[s] + 1e-9L)
          << bvh_.segments[s].name << " at frame " << f << ", chain rate " << bound[s];
    }
  }
  EXPECT_GT(fastest, 1.0);  // a moving skeleton
  std::printf("worst angular velocity difference: %.3g rad/s (fastest segment %.3g rad/s)\n", worst,
              fastest);
}

TEST_P(RealRecording, WholeBodyMassIsTheBodyMass) {
  double mass = 0;
  for (int k = 1; k <= model_.body_count(); ++k) mass += model_.bodies[k].mass;
  EXPECT_NEAR(mass, options_.body_mass, 1e-12 * options_.body_mass);
}

// The CMU skeleton read in the default unit (metres) is far from human: the one warning names the
// CMU unit's scale, for mbk, bvh.launch and the node, and the height it gives.
TEST_P(RealRecording, TheDefaultScaleWarnsWithTheCmuScale) {
  const mbk::Model in_file_units = mbk::model_from_bvh(bvh_, mbk::BvhModelOptions());
  ASSERT_EQ(in_file_units.warnings.size(), 1u);
  EXPECT_NE(in_file_units.warnings[0].find(": --scale 0.056444 (bvh.launch scale:=0.056444, the "
                                           "node's ~scale) gives "),
            std::string::npos)
      << in_file_units.warnings[0];
  EXPECT_NE(in_file_units.warnings[0].find("(file units in CMU's 1/0.45 inch)"), std::string::npos)
      << in_file_units.warnings[0];
  EXPECT_TRUE(model_.warnings.empty()) << model_.warnings.front();  // at kCmuScale: no warning
}

INSTANTIATE_TEST_SUITE_P(Cmu, RealRecording, ::testing::ValuesIn(kRecordings),
                         [](const ::testing::TestParamInfo<Recording>& info) {
                           return "trial_" +
                                  std::string(info.param.file).substr(0, 6);  // trial_131_01
                         });

}  // namespace
