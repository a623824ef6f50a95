// Checks that need no other program (doc/method.md 6) on random trees with every joint type:
// velocities and accelerations are the time derivatives of positions and velocities along smooth
// trajectories, omega is the skew part of S0K' S0K^T; the two formulations (doc/method.md 4 and 5)
// agree; and the double instantiation agrees with the long double one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "mb_kinematics/analysis/reference_kinematics.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "test/support/checks.h"
#include "test/support/test_models.h"

namespace {

using V = mbk::Vec3<double>;
using M = mbk::Mat3<double>;
using mbk::SpeedKind;

const int kSizes[] = {1, 2, 3, 5, 8, 13, 21, 40};
const unsigned kSeeds[] = {1, 2, 3, 4, 5};
const double kTimes[] = {0.0, 0.73, 2.9};

// Central differences: fourth order (test/support/checks.h) with h = 5e-4. Truncation error is
// h^4/30 |f^(5)| ~ h^4/30 Omega^4 |f'|, where Omega is the fastest rate in f: the joint
// frequencies are 0.5..2 rad/s, but a body at depth 40 sums many of them and Omega reaches
// ~10 rad/s, giving ~2e-11 |f'| (h = 1e-3 would give 3e-10, measured). Rounding: each sample
// carries ~depth * eps relative error (<= 40 * 1.1e-16), amplified by 18 / (12 h) = 3e3, i.e.
// ~1e-11 |f|. Worst measured over all cases: 1.7e-11 (for a = dv/dt). kFdTol = 1e-10 relative
// to max(1, |f|, |f'|) of the body; a wrong term (e.g. a missing Coriolis 2 omega x s') is
// O(|f'|) and misses it by orders of magnitude.
constexpr double kH = 5e-4;
constexpr double kFdTol = 1e-10;

// The formulations agree to rounding (doc/method.md 5): 1e-12 relative to the sum of magnitudes of
// the doc/method.md 5 sums (SumScales), which bounds the rounding of either (< ~300 terms of a few
// ulp each: at most ~1e-13; measured 4e-16).
constexpr double kAgreeTol = 1e-12;

// Long double vs double on the same inputs: the double result carries up to ~depth * eps ~ 1e-14
// relative error of the same scales (the long double one 2000 times less); measured 1.3e-15.
constexpr double kLongDoubleTol = 1e-13;

std::string where(int n, unsigned seed, double t) {
  return "n=" + std::to_string(n) + " seed=" + std::to_string(seed) + " t=" + std::to_string(t);
}

// Kinematics at t + offset * h for each stencil offset.
using StateAt = std::function<mbk::JointState<double>(double)>;

std::vector<mbk::Data<double>> stencil(const mbk::Model& model, const StateAt& state_at, double t) {
  std::vector<mbk::Data<double>> samples;
  for (double offset : mbk_test::kStencilOffsets) {
    samples.emplace_back(model);
    mbk::forward_kinematics(model, state_at(t + offset * kH), samples.back());
  }
  return samples;
}

// d/dt of member `f` of body k by the central difference.
V derivative(const std::vector<mbk::Data<double>>& samples, std::vector<V> mbk::Data<double>::*f,
             int k) {
  return mbk_test::central_difference<V>([&](int i) { return (samples[i].*f)[k]; }, kH);
}

M rotation_derivative(const std::vector<mbk::Data<double>>& samples, int k) {
  return mbk_test::central_difference<M>([&](int i) { return samples[i].rotation[k]; }, kH);
}

// Expects d/dt of `f` (sampled) to equal `df` (computed) for body k.
void expect_derivative(const std::vector<mbk::Data<double>>& samples, const mbk::Data<double>& at,
                       std::vector<V> mbk::Data<double>::*f, std::vector<V> mbk::Data<double>::*df,
                       int k, const std::string& what) {
  const V fd = derivative(samples, f, k);
  const V exact = (at.*df)[k];
  const double scale = std::max({1.0, (at.*f)[k].norm(), exact.norm()});
  EXPECT_LE((fd - exact).norm(), kFdTol * scale)
      << what << "\n computed    " << exact.transpose() << "\n differenced " << fd.transpose();
}

void expect_derivatives(const mbk::Model& model, const StateAt& state_at, double t,
                        const std::string& tag) {
  mbk::Data<double> at(model);
  mbk::forward_kinematics(model, state_at(t), at);
  const auto samples = stencil(model, state_at, t);
  using D = mbk::Data<double>;
  for (int k = 1; k <= model.body_count(); ++k) {
    const std::string w = tag + " body " + std::to_string(k) + ": ";
    expect_derivative(samples, at, &D::mass_center, &D::mass_center_velocity, k, w + "v = dp/dt");
    expect_derivative(samples, at, &D::mass_center_velocity, &D::mass_center_acceleration, k,
                      w + "a = dv/dt");
    expect_derivative(samples, at, &D::origin, &D::origin_velocity, k, w + "vO = dO/dt");
    expect_derivative(samples, at, &D::origin_velocity, &D::origin_acceleration, k,
                      w + "aO = dvO/dt");
    expect_derivative(samples, at, &D::omega, &D::alpha, k, w + "alpha = d omega/dt");
    // omega from the skew part of S0K' S0K^T (doc/method.md 6); S0K is O(1).
    const V omega =
        mbk_test::vee_of_skew_part(rotation_derivative(samples, k) * at.rotation[k].transpose());
    EXPECT_LE((omega - at.omega[k]).norm(), kFdTol * std::max(1.0, at.omega[k].norm()))
        << w << "omega from S0K'\n computed    " << at.omega[k].transpose() << "\n differenced "
        << omega.transpose();
  }
}

TEST(FiniteDifference, CoordinateDerivativeSpeeds) {
  for (int n : kSizes)
    for (unsigned seed : kSeeds) {
      const mbk::Model model = mbk_test::random_tree(n, seed);
      const mbk_test::Trajectory trajectory(model, seed + 100);
      const StateAt state_at = [&](double t) { return trajectory.at<double>(t); };
      for (double t : kTimes) expect_derivatives(model, state_at, t, where(n, seed, t));
    }
}

// Euler joints with angular-velocity speeds ("quasi-coordinates", Table 4.3.10): the same
// coordinate trajectory, speeds w_k and w_k' from state_with_angular_speeds.
TEST(FiniteDifference, AngularVelocitySpeeds) {
  for (int n : kSizes)
    for (unsigned seed : kSeeds) {
      const mbk::Model quasi = mbk_test::random_tree(n, seed, SpeedKind::kAngularVelocity);
      const mbk::Model coords = mbk_test::random_tree(n, seed);
      const mbk_test::Trajectory trajectory(coords, seed + 100);
      const StateAt state_at = [&](double t) {
        return mbk_test::state_with_angular_speeds(quasi, coords, trajectory, t);
      };
      for (double t : kTimes) expect_derivatives(quasi, state_at, t, where(n, seed, t));
    }
}

// ---- The two formulations agree on every body and quantity, at every level.

void expect_agree(const V& a, const V& b, double scale, const std::string& what) {
  EXPECT_LE((a - b).norm(), kAgreeTol * scale)
      << what << "\n recursive " << a.transpose() << "\n partial   " << b.transpose();
}

void expect_same_pose(const mbk::Data<double>& a, const mbk::Data<double>& b, int k,
                      const std::string& w) {
  // Poses are the same products in both (doc/method.md 4); positions relative to max(1 m, |p|).
  EXPECT_LE((a.rotation[k] - b.rotation[k]).norm(), kAgreeTol) << w << "S0K";
  expect_agree(a.origin[k], b.origin[k], std::max(1.0, a.origin[k].norm()), w + "origin");
  expect_agree(a.mass_center[k], b.mass_center[k], std::max(1.0, a.mass_center[k].norm()),
               w + "mass center");
}

void expect_formulations_agree(const mbk::Model& model, const mbk::JointState<double>& state,
                               mbk::Level level, const std::string& tag) {
  mbk_test::BothFormulations both(model);
  both.run(model, state, level);
  // The scales need the full partial velocity arrays, whatever level is under test.
  mbk_test::BothFormulations full(model);
  full.run(model, state);
  const mbk::Data<double>& a = both.recursive;
  const mbk::Data<double>& b = both.partial;
  for (int k = 1; k <= model.body_count(); ++k) {
    const std::string w = tag + " body " + std::to_string(k) + ": ";
    expect_same_pose(a, b, k, w);
    if (level == mbk::Level::kPose) continue;
    const mbk_test::SumScales s = mbk_test::sum_scales(full.pv, state, k);
    expect_agree(a.omega[k], b.omega[k], s.omega, w + "omega");
    expect_agree(a.mass_center_velocity[k], b.mass_center_velocity[k], s.velocity, w + "velocity");
    expect_agree(a.origin_velocity[k], b.origin_velocity[k], s.origin_velocity,
                 w + "origin velocity");
    if (level == mbk::Level::kVelocity) continue;
    expect_agree(a.alpha[k], b.alpha[k], s.alpha, w + "alpha");
    expect_agree(a.mass_center_acceleration[k], b.mass_center_acceleration[k], s.acceleration,
                 w + "acceleration");
    expect_agree(a.origin_acceleration[k], b.origin_acceleration[k], s.origin_acceleration,
                 w + "origin acceleration");
  }
}

const mbk::Level kLevels[] = {mbk::Level::kPose, mbk::Level::kVelocity, mbk::Level::kAcceleration};

TEST(Formulations, AgreeWithCoordinateDerivativeSpeeds) {
  for (int n : kSizes)
    for (unsigned seed : kSeeds) {
      const mbk::Model model = mbk_test::random_tree(n, seed);
      const mbk_test::Trajectory trajectory(model, seed + 200);
      for (double t : kTimes)
        for (mbk::Level level : kLevels)
          expect_formulations_agree(
              model, trajectory.at<double>(t), level,
              where(n, seed, t) + " level " + std::to_string(static_cast<int>(level)));
    }
}

TEST(Formulations, AgreeWithAngularVelocitySpeeds) {
  for (int n : kSizes)
    for (unsigned seed : kSeeds) {
      const mbk::Model quasi = mbk_test::random_tree(n, seed, SpeedKind::kAngularVelocity);
      const mbk::Model coords = mbk_test::random_tree(n, seed);
      const mbk_test::Trajectory trajectory(coords, seed + 200);
      for (double t : kTimes)
        for (mbk::Level level : kLevels)
          expect_formulations_agree(
              quasi, mbk_test::state_with_angular_speeds(quasi, coords, trajectory, t), level,
              where(n, seed, t) + " level " + std::to_string(static_cast<int>(level)));
    }
}

// A lower level computes the same leading quantities as the full update.
TEST(Formulations, LowerLevelsMatchFullUpdate) {
  const mbk::Model model = mbk_test::random_tree(21, 7);
  const mbk::JointState<double> state = mbk_test::Trajectory(model, 8).at<double>(0.5);
  mbk_test::BothFormulations full(model), pose(model), vel(model);
  full.run(model, state);
  pose.run(model, state, mbk::Level::kPose);
  vel.run(model, state, mbk::Level::kVelocity);
  for (const auto* d : {&pose.recursive, &pose.partial, &vel.recursive, &vel.partial}) {
    EXPECT_EQ(d->rotation, full.recursive.rotation);
    EXPECT_EQ(d->origin, full.recursive.origin);
    EXPECT_EQ(d->mass_center, full.recursive.mass_center);
  }
  EXPECT_EQ(vel.recursive.omega, full.recursive.omega);
  EXPECT_EQ(vel.recursive.mass_center_velocity, full.recursive.mass_center_velocity);
  EXPECT_EQ(vel.partial.omega, full.partial.omega);
  EXPECT_EQ(vel.partial.mass_center_velocity, full.partial.mass_center_velocity);
}

// The update chosen for the CPU (AVX2 where it has it, kinematics.h) is the portable one, bit for
// bit: no FMA or reordering crept into it.
TEST(Formulations, CpuDispatchIsThePortableUpdate) {
  const mbk::Model model = mbk_test::random_tree(40, 3);
  const mbk::JointState<double> state = mbk_test::Trajectory(model, 4).at<double>(0.7);
  mbk::Data<double> chosen(model), portable(model);
  mbk::forward_kinematics(model, state, chosen);
  mbk::detail::forward_kinematics_at<mbk::Level::kAcceleration>(model, state, portable);
  EXPECT_EQ(chosen.rotation, portable.rotation);
  EXPECT_EQ(chosen.origin, portable.origin);
  EXPECT_EQ(chosen.mass_center, portable.mass_center);
  EXPECT_EQ(chosen.omega, portable.omega);
  EXPECT_EQ(chosen.alpha, portable.alpha);
  EXPECT_EQ(chosen.mass_center_velocity, portable.mass_center_velocity);
  EXPECT_EQ(chosen.mass_center_acceleration, portable.mass_center_acceleration);
  EXPECT_EQ(chosen.origin_velocity, portable.origin_velocity);
  EXPECT_EQ(chosen.origin_acceleration, portable.origin_acceleration);
}

// ---- The scalar template: double against long double, both formulations.

template <typename S>
V to_double(const mbk::Vec3<S>& v) {
  return v.template cast<double>();
}

void expect_long_double_agrees(const mbk::Model& model, const mbk_test::Trajectory& trajectory,
                               double t, const std::string& tag) {
  // The same (double) inputs for both, so that only the kinematics' rounding differs:
  // Trajectory::at<long double> would also remove the inputs' own rounding, which near a zero
  // of y' (sin(phase) ~ 0) is large relative to y'.
  const mbk::JointState<double> sd = trajectory.at<double>(t);
  mbk::JointState<long double> sl(model);
  sl.position = sd.position.cast<long double>();
  sl.velocity = sd.velocity.cast<long double>();
  sl.acceleration = sd.acceleration.cast<long double>();
  mbk_test::BothFormulations d(model);
  d.run(model, sd);
  mbk::Data<long double> rl(model), pl(model);
  mbk::PartialVelocities<long double> pvl(model);
  mbk::forward_kinematics(model, sl, rl);
  mbk::partial_velocity_kinematics(model, sl, pvl, pl);
  for (int k = 1; k <= model.body_count(); ++k) {
    const std::string w = tag + " body " + std::to_string(k) + ": ";
    const mbk_test::SumScales s = mbk_test::sum_scales(pvl, sl, k);
    const double len = std::max(1.0, to_double(rl.mass_center[k]).norm());
    struct Item {
      const char* name;
      V dr, dp, l;
      double scale;
    };
    const Item items[] = {
        {"origin", d.recursive.origin[k], d.partial.origin[k], to_double(rl.origin[k]), len},
        {"mass center", d.recursive.mass_center[k], d.partial.mass_center[k],
         to_double(rl.mass_center[k]), len},
        {"omega", d.recursive.omega[k], d.partial.omega[k], to_double(rl.omega[k]), s.omega},
        {"velocity", d.recursive.mass_center_velocity[k], d.partial.mass_center_velocity[k],
         to_double(rl.mass_center_velocity[k]), s.velocity},
        {"alpha", d.recursive.alpha[k], d.partial.alpha[k], to_double(rl.alpha[k]), s.alpha},
        {"acceleration", d.recursive.mass_center_acceleration[k],
         d.partial.mass_center_acceleration[k], to_double(rl.mass_center_acceleration[k]),
         s.acceleration},
    };
    for (const Item& it : items) {
      EXPECT_LE((it.dr - it.l).norm(), kLongDoubleTol * it.scale) << w << it.name << " recursive";
      EXPECT_LE((it.dp - it.l).norm(), kLongDoubleTol * it.scale) << w << it.name << " partial";
    }
    // The long double formulations agree with each other below double rounding (measured
    // 2e-17; in double they differ by up to 4e-16): the template really computes in long double.
    EXPECT_LE(
        (to_double(pl.mass_center_acceleration[k]) - to_double(rl.mass_center_acceleration[k]))
            .norm(),
        1e-16 * s.acceleration)
        << w << "long double formulations";
    EXPECT_LE((d.recursive.rotation[k] - rl.rotation[k].cast<double>()).norm(), kLongDoubleTol)
        << w << "S0K";
  }
}

TEST(ScalarTemplate, DoubleAgreesWithLongDouble) {
  if (std::numeric_limits<long double>::digits <= std::numeric_limits<double>::digits)
    GTEST_SKIP() << "long double is no wider than double here";
  for (int n : kSizes)
    for (unsigned seed : kSeeds) {
      const mbk::Model model = mbk_test::random_tree(n, seed);
      const mbk_test::Trajectory trajectory(model, seed + 300);
      for (double t : kTimes) expect_long_double_agrees(model, trajectory, t, where(n, seed, t));
    }
}

}  // namespace
