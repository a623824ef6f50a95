// Whole-system quantities: total mass, system mass center G and its motion, linear
// momentum, angular momentum about G; and the partial velocities with respect to the independent
// speeds (mimic columns folded into their sources'). Closed forms, finite differences, point
// masses, and the recursion v_k = sum_r v_kr y_r.
#include "mb_kinematics/core/system_kinematics.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/independent_speeds.h"
#include "mb_kinematics/core/inertia.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/io/urdf_model.h"
#include "test/support/checks.h"
#include "test/support/test_models.h"
#include "test/support/urdf_facts.h"

namespace {

using V = mbk::Vec3<double>;
using M = mbk::Mat3<double>;
using mbk::JointType;

constexpr double kEps = 2.220446049250313e-16;

mbk::SystemKinematics<double> system_at(const mbk::Model& model,
                                        const mbk::JointState<double>& state,
                                        mbk::Data<double>& data) {
  mbk::forward_kinematics(model, state, data);
  mbk::SystemKinematics<double> s;
  mbk::system_kinematics(model, data, s);
  return s;
}

// ---- Closed form, two bodies: B1 and B2 hinge about z at R's origin, G_1 at 1 m along B1's
// x, G_2 at 2 m along B2's y. H about the origin is sum_k (I_k,zz + m_k |r_k|^2) theta_k', and
// H_G = H_O - M p_G x v_G (the parallel axis theorem: an independent route to the same number).
TEST(SystemKinematics, TwoBodiesClosedForm) {
  mbk::Model model;
  model.bodies.resize(3);
  const double m[] = {0, 1.5, 3.0}, izz[] = {0, 0.2, 0.35};
  const V r[] = {V::Zero(), V(1, 0, 0), V(0, 2, 0)};
  for (int k = 1; k <= 2; ++k) {
    mbk::Body& b = model.bodies[k];
    b.name = "B" + std::to_string(k);
    b.joint.type = JointType::kRevolute;
    b.joint.axis = V::UnitZ();
    b.mass_center = r[k];
    b.mass = m[k];
    b.inertia = V(0.1, 0.3, izz[k]).asDiagonal();
    b.has_inertia = true;
  }
  mbk::finalize_model(model);
  mbk::JointState<double> state(model);
  const double th[] = {0.3, -1.1}, w[] = {0.7, -2.0}, wd[] = {1.3, 0.4};
  for (int i = 0; i < 2; ++i) {
    state.position[i] = th[i];
    state.velocity[i] = w[i];
    state.acceleration[i] = wd[i];
  }
  mbk::Data<double> data(model);
  const mbk::SystemKinematics<double> s = system_at(model, state, data);

  const V p1(std::cos(th[0]), std::sin(th[0]), 0), p2(-2 * std::sin(th[1]), 2 * std::cos(th[1]), 0);
  const V v1 = w[0] * V(-p1.y(), p1.x(), 0), v2 = w[1] * V(-p2.y(), p2.x(), 0);
  const V a1 = wd[0] * V(-p1.y(), p1.x(), 0) - w[0] * w[0] * p1;
  const V a2 = wd[1] * V(-p2.y(), p2.x(), 0) - w[1] * w[1] * p2;
  const double total = m[1] + m[2];
  const V pg = (m[1] * p1 + m[2] * p2) / total, vg = (m[1] * v1 + m[2] * v2) / total;
  const double h_o = (izz[1] + m[1] * 1.0) * w[0] + (izz[2] + m[2] * 4.0) * w[1];
  const V h_g = V(0, 0, h_o) - total * pg.cross(vg);

  EXPECT_EQ(s.mass, 4.5);
  EXPECT_TRUE(s.angular_momentum_known);
  const double tol = 8 * kEps;  // a handful of roundings of O(1) numbers
  EXPECT_LT((s.mass_center - pg).norm(), tol);
  EXPECT_LT((s.velocity - vg).norm(), tol);
  EXPECT_LT((s.acceleration - (m[1] * a1 + m[2] * a2) / total).norm(), 4 * tol);
  EXPECT_LT((s.linear_momentum - total * vg).norm(), 4 * tol);
  EXPECT_LT((s.angular_momentum - h_g).norm(), 8 * tol) << s.angular_momentum.transpose();
}

// ---- Closed form, a symmetric spinning system: a hub on a hinge about z (inertia diag(A, A,
// C)) carrying two equal arms on fixed joints at +-L along its x, each turned about z by its own
// rpy; G stays at the origin and does not move, and H_G = (C + 2 c + 2 m L^2) omega along z,
// with c the arms' zz moment (unchanged by a turn about z), whatever the arms' xx, yy, xy.
TEST(SystemKinematics, SymmetricSpinningSystem) {
  mbk::Model model;
  model.bodies.resize(4);
  const double a = 0.4, c_hub = 0.6, mass = 2.0, length = 0.8, c_arm = 0.25;
  mbk::Body& hub = model.bodies[1];
  hub.name = "hub";
  hub.joint.type = JointType::kRevolute;
  hub.joint.axis = V::UnitZ();
  hub.mass = 5.0;
  hub.inertia = V(a, a, c_hub).asDiagonal();
  hub.has_inertia = true;
  for (int k = 2; k <= 3; ++k) {
    mbk::Body& arm = model.bodies[k];
    arm.name = "arm" + std::to_string(k);
    arm.lower = 1;
    arm.joint.type = JointType::kFixed;
    arm.joint.offset = V(k == 2 ? length : -length, 0, 0);
    arm.joint.rotation =
        Eigen::AngleAxisd(k == 2 ? 0.3 : 0.3 + M_PI, V::UnitZ()).toRotationMatrix();
    arm.mass = mass;
    arm.inertia = mbk::inertia_matrix(0.1, 0.2, c_arm, 0.03, 0.0, 0.0);
    arm.has_inertia = true;
  }
  mbk::finalize_model(model);
  mbk::JointState<double> state(model);
  state.position[0] = 1.2;
  state.velocity[0] = 3.0;
  state.acceleration[0] = -0.5;
  mbk::Data<double> data(model);
  const mbk::SystemKinematics<double> s = system_at(model, state, data);
  const double tol = 16 * kEps;
  EXPECT_LT(s.mass_center.norm(), tol);
  EXPECT_LT(s.velocity.norm(), tol * 3.0);
  EXPECT_LT(s.acceleration.norm(), tol * 9.0);
  const V expected(0, 0, (c_hub + 2 * c_arm + 2 * mass * length * length) * 3.0);
  EXPECT_LT((s.angular_momentum - expected).norm(), tol * expected.norm())
      << s.angular_momentum.transpose();
}

// Without an inertia for a body with mass, H_G is unknown and named; massless bodies need none.
TEST(SystemKinematics, WithoutInertiasTheAngularMomentumIsLeftOut) {
  mbk::Model model = mbk::make_bare_model({0, 1, 1}, JointType::kBall123);
  EXPECT_EQ(mbk::bodies_without_inertia(model), (std::vector<std::string>{"B1", "B2", "B3"}));
  model.bodies[1].has_inertia = model.bodies[3].has_inertia = true;
  model.bodies[2].mass = 0;  // massless: no inertia needed
  mbk::finalize_model(model);
  EXPECT_TRUE(mbk::inertias_known(model));
  model.bodies[3].has_inertia = false;
  EXPECT_EQ(mbk::bodies_without_inertia(model), std::vector<std::string>{"B3"});
  mbk::Data<double> data(model);
  const mbk::JointState<double> state = mbk_test::Trajectory(model, 3).at<double>(0.4);
  const mbk::SystemKinematics<double> s = system_at(model, state, data);
  EXPECT_FALSE(s.angular_momentum_known);
  EXPECT_EQ(s.angular_momentum, V::Zero());
  EXPECT_GT(s.velocity.norm(), 0.0);  // the rest is there
}

// ---- Finite differences along smooth trajectories of random trees: v_G = d/dt p_G and
// a_G = d/dt v_G. Fourth-order central difference with h = 5e-4 and the tolerance of
// finite_difference_test.cc (1e-10 relative to max(1, |f|, |f'|)): p_G is a weighted mean of the
// p_k, so truncation and rounding bounds carry over.
TEST(SystemKinematics, MassCenterMotionIsTheTimeDerivative) {
  constexpr double h = 5e-4, tol = 1e-10;
  for (int n : {1, 3, 8, 21}) {
    for (unsigned seed : {1u, 2u, 3u}) {
      const mbk::Model model = mbk::with_random_inertias(mbk_test::random_tree(n, seed), seed);
      const mbk_test::Trajectory trajectory(model, seed);
      for (double t : {0.0, 0.9}) {
        mbk::Data<double> data(model);
        const mbk::SystemKinematics<double> s = system_at(model, trajectory.at<double>(t), data);
        std::vector<mbk::SystemKinematics<double>> samples;
        for (double offset : mbk_test::kStencilOffsets)
          samples.push_back(system_at(model, trajectory.at<double>(t + offset * h), data));
        const V dp =
            mbk_test::central_difference<V>([&](int i) { return samples[i].mass_center; }, h);
        const V dv = mbk_test::central_difference<V>([&](int i) { return samples[i].velocity; }, h);
        const std::string where = "n=" + std::to_string(n) + " seed=" + std::to_string(seed);
        EXPECT_LT((dp - s.velocity).norm(),
                  tol * std::max({1.0, s.mass_center.norm(), s.velocity.norm()}))
            << where;
        EXPECT_LT((dv - s.acceleration).norm(),
                  tol * std::max({1.0, s.velocity.norm(), s.acceleration.norm()}))
            << where;
        EXPECT_LE((s.linear_momentum - s.mass * s.velocity).norm(),
                  4 * kEps * s.linear_momentum.norm());
      }
    }
  }
}

// ---- The angular momentum against point masses: each body replaced by six points of m_k / 6 at
// +-s_i along its principal axes through G_k (s_x^2 = 3 (B + C - A) / (2 m), ...; the same mass,
// mass center and inertia), carried by S0K and p_k, their velocities by finite differences of
// their positions: H_G = sum_points m (P - p_G) x (P' - v_G). Tolerance: the finite difference's,
// 1e-10 relative to the scale sum m |P - p_G| max(1, |P'|).
struct PointMass {
  int body;
  double mass;
  V offset;  // from G_k, in Bk
};

std::vector<PointMass> point_masses(const mbk::Model& model) {
  std::vector<PointMass> points;
  for (int k = 1; k <= model.body_count(); ++k) {
    const mbk::Body& b = model.bodies[k];
    Eigen::SelfAdjointEigenSolver<M> eig(b.inertia);
    const V i = eig.eigenvalues();
    for (int axis = 0; axis < 3; ++axis) {
      const double rest = i.sum() - i[axis];  // the other two moments
      const double s = std::sqrt(std::max(0.0, 3.0 * (rest - i[axis]) / (2.0 * b.mass)));
      for (double sign : {1.0, -1.0})
        points.push_back({k, b.mass / 6.0, V(sign * s * eig.eigenvectors().col(axis))});
    }
  }
  return points;
}

TEST(SystemKinematics, AngularMomentumOfSixPointMassesPerBody) {
  constexpr double h = 5e-4, tol = 1e-10;
  for (int n : {1, 2, 5, 13}) {
    for (unsigned seed : {4u, 5u, 6u}) {
      const mbk::Model model = mbk::with_random_inertias(mbk_test::random_tree(n, seed), seed + 10);
      const std::vector<PointMass> points = point_masses(model);
      {  // the points have the body's mass and inertia
        M inertia = M::Zero();
        for (const PointMass& p : points)
          if (p.body == 1)
            inertia +=
                p.mass * (p.offset.squaredNorm() * M::Identity() - p.offset * p.offset.transpose());
        ASSERT_LT((inertia - model.bodies[1].inertia).norm(), 1e-14);
      }
      const mbk_test::Trajectory trajectory(model, seed);
      const double t = 0.37;
      mbk::Data<double> data(model);
      const mbk::SystemKinematics<double> s = system_at(model, trajectory.at<double>(t), data);
      std::vector<mbk::Data<double>> samples;
      for (double offset : mbk_test::kStencilOffsets) {
        samples.emplace_back(model);
        mbk::forward_kinematics(model, trajectory.at<double>(t + offset * h), samples.back());
      }
      auto position = [&](const mbk::Data<double>& d, const PointMass& p) {
        return V(d.mass_center[p.body] + d.rotation[p.body] * p.offset);
      };
      V h_points = V::Zero();
      double scale = 0;
      for (const PointMass& p : points) {
        const V velocity =
            mbk_test::central_difference<V>([&](int i) { return position(samples[i], p); }, h);
        const V r = position(data, p) - s.mass_center;
        h_points += p.mass * r.cross(velocity - s.velocity);
        scale += p.mass * r.norm() * std::max(1.0, velocity.norm());
      }
      EXPECT_LT((h_points - s.angular_momentum).norm(), tol * scale)
          << "n=" << n << " seed=" << seed << ": " << s.angular_momentum.transpose() << " vs "
          << h_points.transpose();
    }
  }
}

// ---- Partial velocities with respect to the independent speeds, on a URDF with mimic joints:
// the finite difference in each independent speed (mimics applied) of omega_k and v_k is the
// folded column (exact to rounding: both are linear in the speeds), and the recursion's omega_k,
// v_k, alpha_k, a_k are the sums over the folded columns to rounding.
const char kMimicUrdf[] = R"(<robot name="mimic">
  <link name="base"/>
  <link name="a"><inertial><origin xyz="0.2 0.1 0"/><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="b"><inertial><origin xyz="0.3 0 0.1"/><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="c"><inertial><origin xyz="0 0.2 0.05"/><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="d"><inertial><origin xyz="0.1 0 0"/><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <joint name="ja" type="continuous"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/></joint>
  <joint name="jb" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0.5 0 0" rpy="0.2 0 0"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/><mimic joint="ja" multiplier="-2" offset="0.1"/></joint>
  <joint name="jc" type="prismatic"><parent link="b"/><child link="c"/><origin xyz="0.4 0 0"/><axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="jd" type="revolute"><parent link="c"/><child link="d"/><origin xyz="0 0.3 0"/><axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/><mimic joint="jc" multiplier="1.5"/></joint>
</robot>)";

TEST(IndependentSpeeds, MimicColumnsGoIntoTheirSources) {
  const mbk::Model model = mbk::load_urdf_string(kMimicUrdf, "mimic.urdf");
  ASSERT_EQ(model.nv, 4);
  double f = 0;
  EXPECT_EQ(mbk::independent_speed(model, model.speed_index("jb"), f), model.speed_index("ja"));
  EXPECT_EQ(f, -2.0);
  EXPECT_EQ(mbk::independent_speed(model, model.speed_index("jc"), f), model.speed_index("jc"));
  EXPECT_EQ(f, 1.0);

  mbk::JointState<double> state = mbk_test::Trajectory(model, 7).at<double>(0.6);
  mbk::apply_mimics(model, state);
  mbk::PartialVelocities<double> pv(model);
  mbk::Data<double> partial(model), recursive(model), plus(model), minus(model);
  mbk::partial_velocity_kinematics(model, state, pv, partial);
  mbk::forward_kinematics(model, state, recursive);
  const std::vector<int> independent = {model.speed_index("ja"), model.speed_index("jc")};
  for (int k = 1; k <= model.body_count(); ++k) {
    const std::vector<mbk::SpeedColumn> columns = mbk::independent_columns(model, pv, k);
    V omega = V::Zero(), v = V::Zero(), alpha = V::Zero(), a = V::Zero();
    double scale = 1.0;
    for (const mbk::SpeedColumn& c : columns) {
      EXPECT_TRUE(std::find(independent.begin(), independent.end(), c.speed) != independent.end())
          << "body " << k << " has a column of dependent speed " << model.speed_names[c.speed];
      const double y = state.velocity[c.speed], yd = state.acceleration[c.speed];
      omega += c.omega * y;
      v += c.velocity * y;
      alpha += c.omega * yd + c.omega_dot * y;
      a += c.velocity * yd + c.velocity_dot * y;
      scale += (c.omega.norm() + c.velocity.norm()) * (std::abs(y) + std::abs(yd)) +
               (c.omega_dot.norm() + c.velocity_dot.norm()) * std::abs(y);
    }
    // The recursion: 64 eps of the magnitude scale (a few dozen roundings at most).
    const double tol = 64 * kEps * scale;
    EXPECT_LT((omega - recursive.omega[k]).norm(), tol) << "body " << k;
    EXPECT_LT((v - recursive.mass_center_velocity[k]).norm(), tol) << "body " << k;
    EXPECT_LT((alpha - recursive.alpha[k]).norm(), tol) << "body " << k;
    EXPECT_LT((a - recursive.mass_center_acceleration[k]).norm(), tol) << "body " << k;
    // Finite differences in each independent speed (step 1: exact for a linear function).
    for (int r : independent) {
      mbk::JointState<double> up = state, down = state;
      up.velocity[r] += 1.0;
      down.velocity[r] -= 1.0;
      mbk::apply_mimics(model, up);
      mbk::apply_mimics(model, down);
      mbk::forward_kinematics(model, up, plus, mbk::Level::kVelocity);
      mbk::forward_kinematics(model, down, minus, mbk::Level::kVelocity);
      const V d_omega = (plus.omega[k] - minus.omega[k]) / 2.0;
      const V d_v = (plus.mass_center_velocity[k] - minus.mass_center_velocity[k]) / 2.0;
      V col_omega = V::Zero(), col_v = V::Zero();
      for (const mbk::SpeedColumn& c : columns)
        if (c.speed == r) col_omega = c.omega, col_v = c.velocity;
      EXPECT_LT((d_omega - col_omega).norm(), tol) << "body " << k << " speed " << r;
      EXPECT_LT((d_v - col_v).norm(), tol) << "body " << k << " speed " << r;
    }
  }
  // Body d (on jd, mimic of jc) has columns ja and jc only, and jc's includes 1.5 x jd's axis.
  EXPECT_EQ(mbk::independent_columns(model, pv, model.body_index("d")).size(), 2u);
}

// Along a trajectory of the mimic model, the folded _dot columns are the time derivatives of the
// folded columns (tolerance of partial_velocity_test.cc: 1e-10 relative).
TEST(IndependentSpeeds, DotColumnsAreTimeDerivatives) {
  constexpr double h = 5e-4, tol = 1e-10;
  const mbk::Model model = mbk::load_urdf_string(kMimicUrdf, "mimic.urdf");
  const mbk_test::Trajectory trajectory(model, 8);
  auto columns_at = [&](double t, int k) {
    mbk::JointState<double> state = trajectory.at<double>(t);
    mbk::apply_mimics(model, state);
    mbk::PartialVelocities<double> pv(model);
    mbk::Data<double> data(model);
    mbk::partial_velocity_kinematics(model, state, pv, data);
    return mbk::independent_columns(model, pv, k);
  };
  const double t = 1.1;
  for (int k = 1; k <= model.body_count(); ++k) {
    const std::vector<mbk::SpeedColumn> now = columns_at(t, k);
    std::vector<std::vector<mbk::SpeedColumn>> samples;
    for (double offset : mbk_test::kStencilOffsets)
      samples.push_back(columns_at(t + offset * h, k));
    for (size_t c = 0; c < now.size(); ++c) {
      const V d_omega =
          mbk_test::central_difference<V>([&](int i) { return samples[i][c].omega; }, h);
      const V d_v =
          mbk_test::central_difference<V>([&](int i) { return samples[i][c].velocity; }, h);
      const double scale = std::max({1.0, now[c].velocity.norm(), now[c].velocity_dot.norm()});
      EXPECT_LT((d_omega - now[c].omega_dot).norm(), tol * scale) << "body " << k;
      EXPECT_LT((d_v - now[c].velocity_dot).norm(), tol * scale) << "body " << k;
    }
  }
}

// ---- The root link: a URDF root link's mass counts, fixed in R; M is the sum of the
// URDF's <mass> values. H_G = H_O - M p_G x v_G, the root link at rest adding nothing to H_O.
TEST(SystemKinematics, RootLinkMassCountsFixedInR) {
  const mbk::Model model = mbk::load_urdf_string(mbk_test::kHeavyRootUrdf, "q.urdf");
  mbk::JointState<double> state(model);
  state.position[0] = 0.4;
  state.velocity[0] = 1.3;
  state.acceleration[0] = -0.7;
  mbk::Data<double> data(model);
  const mbk::SystemKinematics<double> s = system_at(model, state, data);
  const double m0 = 15.36, m1 = 2.5, total = m0 + m1;
  EXPECT_EQ(s.mass, total);
  const V p_g = (m0 * V(0.1, -0.02, 0.05) + m1 * data.mass_center[1]) / total;
  EXPECT_LT((s.mass_center - p_g).norm(), 4 * kEps);
  EXPECT_LT((s.velocity - m1 * data.mass_center_velocity[1] / total).norm(), 8 * kEps);
  EXPECT_LT((s.acceleration - m1 * data.mass_center_acceleration[1] / total).norm(), 8 * kEps);
  ASSERT_TRUE(s.angular_momentum_known);
  const M i1 = data.rotation[1] * model.bodies[1].inertia * data.rotation[1].transpose();
  const V h_o = i1 * data.omega[1] + m1 * data.mass_center[1].cross(data.mass_center_velocity[1]);
  EXPECT_LT((s.angular_momentum - (h_o - total * s.mass_center.cross(s.velocity))).norm(),
            16 * kEps);
}

// The double overload (on a CPU with AVX2: 256-bit vectors) gives the template's numbers bit
// for bit: random trees with random full inertias, a root link with mass, a body without an
// inertia (H_G left out), no mass at all, and speeds of 1 and 1e3.
bool same_bits(const V& a, const V& b) { return std::memcmp(a.data(), b.data(), sizeof(V)) == 0; }

void expect_template_bits(const mbk::Model& model, const mbk::JointState<double>& state,
                          const std::string& where) {
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, state, data);
  for (mbk::Level level : {mbk::Level::kPose, mbk::Level::kVelocity, mbk::Level::kAcceleration}) {
    mbk::SystemKinematics<double> fast, reference;
    fast.mass = -1;  // every field is written
    mbk::system_kinematics(model, data, fast, level);
    mbk::system_kinematics<double>(model, data, reference, level);
    EXPECT_EQ(std::memcmp(&fast.mass, &reference.mass, sizeof(double)), 0) << where;
    EXPECT_TRUE(same_bits(fast.mass_center, reference.mass_center)) << where;
    EXPECT_TRUE(same_bits(fast.velocity, reference.velocity)) << where;
    EXPECT_TRUE(same_bits(fast.acceleration, reference.acceleration)) << where;
    EXPECT_TRUE(same_bits(fast.linear_momentum, reference.linear_momentum)) << where;
    EXPECT_TRUE(same_bits(fast.angular_momentum, reference.angular_momentum)) << where;
    EXPECT_EQ(fast.angular_momentum_known, reference.angular_momentum_known) << where;
  }
}

TEST(SystemKinematics, DoubleOverloadIsTheTemplateBitForBit) {
  for (int n : {1, 3, 8, 21, 100}) {
    for (unsigned seed : {1u, 2u, 3u}) {
      mbk::Model model = mbk::with_random_inertias(mbk_test::random_tree(n, seed), seed);
      model.bodies[0].mass = 2.5;  // the root link counts too
      model.bodies[0].mass_center = V(0.1, -0.2, 0.3);
      model.bodies[0].inertia = V(0.2, 0.3, 0.4).asDiagonal();
      model.bodies[0].has_inertia = true;
      std::mt19937 rng(seed);
      for (double speed : {1.0, 1e3}) {
        const mbk::JointState<double> state = mbk::random_state(model, rng, speed);
        const std::string where = "n=" + std::to_string(n) + " seed=" + std::to_string(seed) +
                                  " speed=" + std::to_string(speed);
        expect_template_bits(model, state, where);
        mbk::Model partial = model;
        partial.bodies[n].has_inertia = false;  // H_G unknown
        expect_template_bits(partial, state, where + " without an inertia");
      }
    }
  }
  const mbk::Model heavy = mbk::load_urdf_string(mbk_test::kHeavyRootUrdf, "q.urdf");
  std::mt19937 rng(7);
  expect_template_bits(heavy, mbk::random_state(heavy, rng), "heavy root");
  mbk::Model massless = mbk_test::random_tree(5, 1);  // M = 0: no mass center
  for (mbk::Body& body : massless.bodies) body.mass = 0;
  expect_template_bits(massless, mbk::random_state(massless, rng), "massless");
}

}  // namespace
