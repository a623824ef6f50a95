// The partial velocity arrays (doc/method.md 5): their sparsity along the lower body array, the
// chapter's Table 4.4.1 with its erratum (doc/method.md 7), that they are the body Jacobians'
// columns, their O(N * depth) storage, and their time derivatives.
#include "mb_kinematics/core/partial_velocity.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"
#include "test/support/checks.h"
#include "test/support/test_models.h"

namespace {

using V = mbk::Vec3<double>;
using M = mbk::Mat3<double>;
using mbk::JointType;
using mbk::SpeedKind;

const std::vector<int> kTenBody = {0, 1, 2, 1, 1, 5, 2, 7, 8, 9};  // Fig. 4.2.1
const std::vector<int> kHuman = {0, 1, 2, 3, 4, 5, 4, 7, 4, 9, 2, 11, 12, 2, 14, 15};

// Body k's path to R, from the body next to R outward to k itself: L^v(k), ..., L(k), k.
std::vector<int> path_to(const mbk::Model& model, int k) {
  std::vector<int> path;
  for (; k > 0; k = model.bodies[k].lower) path.push_back(k);
  std::reverse(path.begin(), path.end());
  return path;
}

// The generalized speeds of body u's own joint.
std::vector<int> own_speeds(const mbk::Model& model, int u) {
  const mbk::Body& b = model.bodies[u];
  std::vector<int> r;
  for (int c = 0; c < mbk::speed_count(b.joint.type, model.speeds); ++c) r.push_back(b.v_index + c);
  return r;
}

// Body k's stored speed columns r, in storage order.
std::vector<int> stored_speeds(const mbk::PartialVelocities<double>& pv, int k) {
  return std::vector<int>(pv.speed.begin() + pv.begin[k],
                          pv.speed.begin() + pv.begin[k] + pv.count[k]);
}

// The speeds of Bk's joint and its ancestors', from R outward.
std::vector<int> expected_speeds(const mbk::Model& model, int k) {
  std::vector<int> r;
  for (int u : path_to(model, k)) {
    const std::vector<int> own = own_speeds(model, u);
    r.insert(r.end(), own.begin(), own.end());
  }
  return r;
}

// Any state with nonzero coordinates (the columns depend on q only).
mbk::JointState<double> some_state(const mbk::Model& model, unsigned seed) {
  return mbk_test::Trajectory(model, seed).at<double>(0.3);
}

// ---- Sparsity: omega_krm has nonzero column blocks exactly for the speeds of Bk's joint and of
// its ancestors' joints (doc/method.md 5); all other columns are zero and not stored.
TEST(PartialVelocities, SparsityOfTheTenBodySystem) {
  const mbk::Model model = mbk::make_bare_model(kTenBody, JointType::kBall123);
  ASSERT_EQ(model.nv, 30);
  mbk::PartialVelocities<double> pv(model);
  mbk::Data<double> data(model);
  mbk::partial_velocity_kinematics(model, some_state(model, 1), pv, data);
  for (int k = 1; k <= 10; ++k) {
    SCOPED_TRACE("body " + std::to_string(k));
    EXPECT_EQ(stored_speeds(pv, k), expected_speeds(model, k));
    EXPECT_EQ(pv.count[k], 3 * static_cast<int>(path_to(model, k).size()));
    for (int i = pv.begin[k]; i < pv.begin[k] + pv.count[k]; ++i)  // 1-2-3 columns are unit
      EXPECT_NEAR(pv.omega[i].norm(), 1.0, 1e-15) << "column of speed " << pv.speed[i];
  }
}

// Table 4.4.1, column k = 6, with L(6) = 5 (doc/method.md 7): blocks of B1, B5 and B6, not of B4.
TEST(PartialVelocities, BodySixHasBlocksOfB1B5B6NotB4) {
  const mbk::Model model = mbk::make_bare_model(kTenBody, JointType::kBall123);
  const mbk::PartialVelocities<double> pv(model);
  const std::vector<int> speeds = stored_speeds(pv, 6);
  auto has = [&](int body) {
    const std::vector<int> own = own_speeds(model, body);
    return std::all_of(own.begin(), own.end(), [&](int r) {
      return std::find(speeds.begin(), speeds.end(), r) != speeds.end();
    });
  };
  auto has_any = [&](int body) {
    const std::vector<int> own = own_speeds(model, body);
    return std::any_of(own.begin(), own.end(), [&](int r) {
      return std::find(speeds.begin(), speeds.end(), r) != speeds.end();
    });
  };
  EXPECT_TRUE(has(1));
  EXPECT_TRUE(has(5));
  EXPECT_TRUE(has(6));
  for (int u : {2, 3, 4, 7, 8, 9, 10}) EXPECT_FALSE(has_any(u)) << "block of B" << u;
  EXPECT_EQ(speeds.size(), 9u);
}

// Table 4.4.1 literally: with relative angular velocity components as speeds (quasi-coordinates,
// Table 4.3.10) the blocks of omega_6 are I (B1), S01 (B5) and S05 (B6). Each stored column is
// S0J times a unit vector, so the comparison is exact.
TEST(PartialVelocities, Table441ColumnSixWithQuasiCoordinates) {
  mbk::Model model = mbk::make_bare_model(kTenBody, JointType::kBallEuler);
  model.speeds = SpeedKind::kAngularVelocity;
  mbk::finalize_model(model);
  mbk::PartialVelocities<double> pv(model);
  mbk::Data<double> data(model);
  mbk::JointState<double> state(model);
  state.position = some_state(mbk::make_bare_model(kTenBody, JointType::kBallEuler), 2).position;
  mbk::partial_velocity_kinematics(model, state, pv, data);
  const M blocks[] = {M::Identity(), data.rotation[1], data.rotation[5]};  // I, S01, S05
  ASSERT_EQ(pv.count[6], 9);
  for (int b = 0; b < 3; ++b)
    for (int c = 0; c < 3; ++c) {
      const int i = pv.begin[6] + 3 * b + c;
      EXPECT_EQ(pv.omega[i], V(blocks[b].col(c))) << "block " << b << " column " << c;
    }
}

// ---- The partial velocities are the columns of the body Jacobians (doc/method.md 5): with the
// unit speed vector e_r, the recursion of doc/method.md 4 gives omega_k = omega_kr and v_k = v_kr
// (zero where r is not stored). Exact: the recursion then adds only zeros to the same products.
void expect_jacobian_columns(const mbk::Model& model, const mbk::JointState<double>& state,
                             const std::string& tag) {
  mbk::PartialVelocities<double> pv(model);
  mbk::Data<double> partial(model), unit(model);
  mbk::partial_velocity_kinematics(model, state, pv, partial, mbk::Level::kVelocity);
  for (int r = 0; r < model.nv; ++r) {
    mbk::JointState<double> e = state;
    e.velocity.setZero();
    e.velocity[r] = 1.0;
    mbk::forward_kinematics(model, e, unit, mbk::Level::kVelocity);
    for (int k = 1; k <= model.body_count(); ++k) {
      V omega = V::Zero(), v = V::Zero(), vo = V::Zero();
      for (int i = pv.begin[k]; i < pv.begin[k] + pv.count[k]; ++i)
        if (pv.speed[i] == r) {
          omega = pv.omega[i];
          v = pv.velocity[i];
          vo = pv.origin_velocity[i];
        }
      const std::string w = tag + " speed " + std::to_string(r) + " body " + std::to_string(k);
      EXPECT_EQ(unit.omega[k], omega) << w << " omega";
      EXPECT_EQ(unit.mass_center_velocity[k], v) << w << " mass center velocity";
      EXPECT_EQ(unit.origin_velocity[k], vo) << w << " origin velocity";
    }
  }
}

TEST(PartialVelocities, AreTheJacobianColumns) {
  expect_jacobian_columns(mbk::make_bare_model(kTenBody, JointType::kBall123),
                          some_state(mbk::make_bare_model(kTenBody, JointType::kBall123), 3),
                          "ten-body");
  for (SpeedKind kind : {SpeedKind::kCoordinateDerivatives, SpeedKind::kAngularVelocity})
    for (unsigned seed = 1; seed <= 4; ++seed) {
      const mbk::Model model = mbk_test::random_tree(25, seed, kind);
      const mbk::Model coords = mbk_test::random_tree(25, seed);
      const mbk_test::Trajectory trajectory(coords, seed);
      const mbk::JointState<double> state =
          kind == SpeedKind::kAngularVelocity
              ? mbk_test::state_with_angular_speeds(model, coords, trajectory, 0.4)
              : trajectory.at<double>(0.4);
      expect_jacobian_columns(model, state, "seed " + std::to_string(seed));
    }
}

// From a nonzero state, adding 1 to speed r alone changes omega_k and v_k by omega_kr and v_kr
// (linearity in the speeds), to rounding: 1e-14 relative to the sums' magnitude scale, which is
// a few ulp of those sums (< 100 terms of 1.1e-16 each, mostly cancelling).
TEST(PartialVelocities, PerturbingOneSpeedAddsItsColumn) {
  const mbk::Model model = mbk_test::random_tree(30, 11);
  const mbk::JointState<double> state = mbk_test::Trajectory(model, 12).at<double>(0.8);
  mbk::PartialVelocities<double> pv(model);
  mbk::Data<double> base(model), moved(model);
  mbk::partial_velocity_kinematics(model, state, pv, base, mbk::Level::kVelocity);
  mbk::forward_kinematics(model, state, base, mbk::Level::kVelocity);
  for (int k = 1; k <= model.body_count(); ++k) {
    const mbk_test::SumScales s = mbk_test::sum_scales(pv, state, k);
    for (int i = pv.begin[k]; i < pv.begin[k] + pv.count[k]; ++i) {
      mbk::JointState<double> e = state;
      e.velocity[pv.speed[i]] += 1.0;
      mbk::forward_kinematics(model, e, moved, mbk::Level::kVelocity);
      const double so = s.omega + 2 * pv.omega[i].norm(),
                   sv = s.velocity + 2 * pv.velocity[i].norm();
      EXPECT_LE((moved.omega[k] - base.omega[k] - pv.omega[i]).norm(), 1e-14 * so);
      EXPECT_LE(
          (moved.mass_center_velocity[k] - base.mass_center_velocity[k] - pv.velocity[i]).norm(),
          1e-14 * sv);
    }
  }
}

// ---- Storage: sum over bodies of the speeds of the joint and its ancestors, O(N * depth).
size_t expected_storage(const mbk::Model& model) {
  size_t total = 0;
  for (int k = 1; k <= model.body_count(); ++k) total += expected_speeds(model, k).size();
  return total;
}

void expect_storage(const mbk::Model& model, size_t expected, const std::string& tag) {
  const mbk::PartialVelocities<double> pv(model);
  for (const auto* a : {&pv.omega, &pv.origin_velocity, &pv.velocity, &pv.omega_dot,
                        &pv.origin_velocity_dot, &pv.velocity_dot})
    EXPECT_EQ(a->size(), expected) << tag;
  EXPECT_EQ(pv.speed.size(), expected) << tag;
}

TEST(PartialVelocities, StorageIsSumOfAncestorSpeeds) {
  for (int n = 1; n <= 40; ++n)  // a chain of n hinges: 1 + 2 + ... + n columns
    expect_storage(mbk_test::revolute_chain(n), static_cast<size_t>(n * (n + 1) / 2),
                   "chain " + std::to_string(n));
  // Ten-body system on ball joints: 3 * (1+2+3+2+2+3+3+4+5+6) = 93 columns, not 10 * 30.
  expect_storage(mbk::make_bare_model(kTenBody, JointType::kBall123), 93, "ten-body");
  // Human body model on hinges: depths 1,2,3,4,5,6,5,6,5,6,3,4,5,3,4,5 sum to 67.
  expect_storage(mbk::make_bare_model(kHuman, JointType::kRevolute), 67, "human");
  for (SpeedKind kind : {SpeedKind::kCoordinateDerivatives, SpeedKind::kAngularVelocity})
    for (unsigned seed = 1; seed <= 5; ++seed) {
      const mbk::Model model = mbk_test::random_tree(40, seed, kind);
      expect_storage(model, expected_storage(model), "random seed " + std::to_string(seed));
    }
}

// ---- Time derivatives of the partial velocities (doc/method.md 5, eq. 4.5.2-4.5.4, 4.8.3-4.8.7):
// omega_kr', v_kr' and the origin's are d/dt of the stored columns along a trajectory. Same
// fourth-order central difference, step and tolerance as finite_difference_test.cc: h = 5e-4,
// truncation ~h^4/30 Omega^4 |f'| ~ 2e-11 and rounding ~3e3 * depth * eps |f| ~ 1e-11 relative to
// max(1, |f|, |f'|), bounded by 1e-10.
constexpr double kH = 5e-4;
constexpr double kFdTol = 1e-10;

using Columns = std::vector<V> mbk::PartialVelocities<double>::*;

void expect_column_derivatives(const mbk::Model& model,
                               const std::function<mbk::JointState<double>(double)>& state_at,
                               double t, const std::string& tag) {
  mbk::PartialVelocities<double> at(model);
  mbk::Data<double> data(model);
  mbk::partial_velocity_kinematics(model, state_at(t), at, data);
  std::vector<mbk::PartialVelocities<double>> samples;
  for (double offset : mbk_test::kStencilOffsets) {
    samples.emplace_back(model);
    mbk::partial_velocity_kinematics(model, state_at(t + offset * kH), samples.back(), data);
  }
  using PV = mbk::PartialVelocities<double>;
  const std::pair<Columns, Columns> pairs[] = {{&PV::omega, &PV::omega_dot},
                                               {&PV::velocity, &PV::velocity_dot},
                                               {&PV::origin_velocity, &PV::origin_velocity_dot}};
  for (const auto& [f, df] : pairs)
    for (size_t i = 0; i < at.speed.size(); ++i) {
      const V fd = mbk_test::central_difference<V>([&](int s) { return (samples[s].*f)[i]; }, kH);
      const V exact = (at.*df)[i];
      const double scale = std::max({1.0, (at.*f)[i].norm(), exact.norm()});
      EXPECT_LE((fd - exact).norm(), kFdTol * scale)
          << tag << " column " << i << " (speed " << at.speed[i] << ")\n computed    "
          << exact.transpose() << "\n differenced " << fd.transpose();
    }
}

TEST(PartialVelocities, DerivativesAreTimeDerivativesOfTheColumns) {
  for (int n : {1, 4, 12, 40})
    for (unsigned seed = 1; seed <= 4; ++seed) {
      const std::string tag = "n=" + std::to_string(n) + " seed=" + std::to_string(seed);
      const mbk::Model coords = mbk_test::random_tree(n, seed);
      const mbk::Model quasi = mbk_test::random_tree(n, seed, SpeedKind::kAngularVelocity);
      const mbk_test::Trajectory trajectory(coords, seed + 50);
      expect_column_derivatives(
          coords, [&](double t) { return trajectory.at<double>(t); }, 1.1, tag);
      expect_column_derivatives(
          quasi,
          [&](double t) {
            return mbk_test::state_with_angular_speeds(quasi, coords, trajectory, t);
          },
          1.1, tag + " angular velocity speeds");
    }
}

}  // namespace
