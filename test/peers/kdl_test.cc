// Peer check against Orocos KDL (doc/method.md 8): link poses from KDL's tree solver and link
// twists from its chain velocity solver, on the shipped URDFs and on URDFs written from random
// trees, for random joint positions and velocities. KDL has no acceleration kinematics (no
// forward solver for FrameAcc in orocos_kdl 1.5), so accelerations are not compared here.
//
// Links are matched by name (our bodies are the URDF links, numbered breadth-first by the
// loader), coordinates by URDF joint name (model.coordinate_index). The same URDF is compared
// with our model loaded from it and, where there is one, with the model it was written from
// (YAML scene or random tree; the links `<body>__alpha` etc. that the writer adds for ball and
// free joints exist only in KDL then and are skipped).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <kdl/chain.hpp>
#include <kdl/chainfksolvervel_recursive.hpp>
#include <kdl/frames.hpp>
#include <kdl/framevel.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/jntarrayvel.hpp>
#include <kdl/tree.hpp>
#include <kdl/treefksolverpos_recursive.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/core/system_kinematics.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/text_file.h"
#include "mb_kinematics/io/urdf_model.h"
#include "mb_kinematics/io/urdf_writer.h"
#include "test/support/checks.h"
#include "test/support/test_models.h"
#include "test/support/urdf_facts.h"

namespace {

// Tolerances. Both programs compose the same rigid transforms in double precision with a
// different order of operations (KDL: Frame products along the chain, its own axis-angle
// rotations; ours: S0J SJK with Rodrigues and 1-2-3 matrices), so they differ by rounding only,
// which grows with the size of the numbers and the depth of the chains. The largest scenes here
// (random trees: chains of up to ~40 URDF joints, |O_k| up to ~20 m, velocities up to ~90 m/s
// with speeds |q'| <= 2) show up to 2.7e-14 m and 1.6e-13 m/s, i.e. 5 to 10 ulps of those
// magnitudes (ulp(20) = 3.6e-15, ulp(90) = 1.4e-14); the shipped scenes (|O_k| < 6 m) show
// < 1e-15 and < 4e-15. 1e-13 and 1e-12 leave a margin of four to six on the worst case and are
// still 1e4 times smaller than what a 1e-9 m slip of one joint offset produces (test
// DetectsASmallModelError).
constexpr double kPoseTolerance = 1e-13;      // m, and rotation matrix entries
constexpr double kVelocityTolerance = 1e-12;  // m/s and rad/s

struct Errors {
  double position = 0, rotation = 0;              // poses of every link (tree solver)
  double origin_velocity = 0, omega = 0;          // twists along every root-to-leaf chain
  double chain_position = 0, chain_rotation = 0;  // poses from the chain velocity solver
  int links = 0, chains = 0, velocity_links = 0;  // what was compared
  double position_scale = 0, velocity_scale = 0;  // largest |O_k|; largest |v_Ok|, |omega_k|
};

double max_abs_diff(const KDL::Vector& a, const mbk::Vec3<double>& b) {
  return std::max({std::abs(a.x() - b.x()), std::abs(a.y() - b.y()), std::abs(a.z() - b.z())});
}

double max_abs_diff(const KDL::Rotation& a, const mbk::Mat3<double>& b) {
  double e = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) e = std::max(e, std::abs(a(i, j) - b(i, j)));
  return e;
}

// Random positions (angles in [-pi, pi], translations in [-pi, pi] m) and speeds in [-2, 2]
// per KDL joint name; sets our state through coordinate_index and KDL's tree array through q_nr.
struct Sample {
  std::map<std::string, double> q, qd;
};

Sample random_sample(const KDL::Tree& tree, std::mt19937& rng) {
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), speed(-2.0, 2.0);
  Sample s;
  for (const auto& [name, element] : tree.getSegments()) {
    const KDL::Joint& joint = GetTreeElementSegment(element).getJoint();
    if (joint.getType() == KDL::Joint::None) continue;
    s.q[joint.getName()] = angle(rng);
    s.qd[joint.getName()] = speed(rng);
  }
  return s;
}

// Compares our two formulations (forward_kinematics and partial_velocity_kinematics, full level)
// with KDL on `samples` random states; the errors are the largest over both.
Errors compare_with_kdl(const mbk::Model& model, const KDL::Tree& tree, unsigned seed,
                        int samples) {
  Errors err;
  // Structure: every body is a KDL segment, every coordinate a KDL joint and back.
  const KDL::SegmentMap& segments = tree.getSegments();
  for (int k = 1; k <= model.body_count(); ++k)
    EXPECT_TRUE(segments.count(model.bodies[k].name)) << model.bodies[k].name << " not in KDL";
  EXPECT_EQ(model.nq, model.nv);  // URDF joints: speeds are coordinate derivatives
  EXPECT_EQ(static_cast<int>(tree.getNrOfJoints()), model.nq);

  const std::string root = GetTreeElementSegment(tree.getRootSegment()->second).getName();
  EXPECT_EQ(root, model.frame);
  std::vector<KDL::Chain> chains;  // root to every leaf
  for (const auto& [name, element] : segments) {
    if (!GetTreeElementChildren(element).empty() || name == root) continue;
    chains.emplace_back();
    EXPECT_TRUE(tree.getChain(root, name, chains.back())) << name;
  }
  err.chains = static_cast<int>(chains.size());

  std::mt19937 rng(seed);
  KDL::TreeFkSolverPos_recursive tree_fk(tree);
  mbk::JointState<double> state(model);
  mbk::Data<double> data(model), data_pv(model);  // recursive and partial velocity forms
  mbk::PartialVelocities<double> pv(model);
  for (int n = 0; n < samples; ++n) {
    const Sample s = random_sample(tree, rng);
    int set = 0;
    for (const auto& [name, value] : s.q) {
      const int i = model.coordinate_index(name);
      EXPECT_GE(i, 0) << "KDL joint " << name << " is no coordinate of ours";
      if (i < 0) continue;
      state.position[i] = value;
      state.velocity[i] = s.qd.at(name);
      state.acceleration[i] = 0;
      ++set;
    }
    EXPECT_EQ(set, model.nq);
    mbk::forward_kinematics(model, state, data, mbk::Level::kAcceleration);
    mbk::partial_velocity_kinematics(model, state, pv, data_pv, mbk::Level::kAcceleration);

    KDL::JntArray q(tree.getNrOfJoints());
    for (const auto& [name, element] : segments) {
      const KDL::Joint& joint = GetTreeElementSegment(element).getJoint();
      if (joint.getType() != KDL::Joint::None)
        q(GetTreeElementQNr(element)) = s.q.at(joint.getName());
    }
    err.links = 0;
    for (int k = 1; k <= model.body_count(); ++k) {
      KDL::Frame frame;
      EXPECT_GE(tree_fk.JntToCart(q, frame, model.bodies[k].name), 0) << model.bodies[k].name;
      for (const mbk::Data<double>* d : {&data, &data_pv}) {
        err.position = std::max(err.position, max_abs_diff(frame.p, d->origin[k]));
        err.rotation = std::max(err.rotation, max_abs_diff(frame.M, d->rotation[k]));
      }
      err.position_scale = std::max(err.position_scale, data.origin[k].norm());
      err.velocity_scale =
          std::max({err.velocity_scale, data.origin_velocity[k].norm(), data.omega[k].norm()});
      ++err.links;
    }

    std::vector<bool> seen(model.bodies.size(), false);
    for (const KDL::Chain& chain : chains) {
      KDL::JntArrayVel qv(chain.getNrOfJoints());
      unsigned j = 0;
      for (const KDL::Segment& segment : chain.segments) {
        const KDL::Joint& joint = segment.getJoint();
        if (joint.getType() == KDL::Joint::None) continue;
        qv.q(j) = s.q.at(joint.getName());
        qv.qdot(j) = s.qd.at(joint.getName());
        ++j;
      }
      KDL::ChainFkSolverVel_recursive chain_fk(chain);
      for (unsigned i = 0; i < chain.getNrOfSegments(); ++i) {
        const int k = model.body_index(chain.getSegment(i).getName());
        if (k < 1) continue;  // a link the URDF writer added; not a body of this model
        KDL::FrameVel out;
        EXPECT_GE(chain_fk.JntToCart(qv, out, static_cast<int>(i) + 1), 0);
        // GetTwist(): velocity of the segment frame's origin and the angular velocity, both in
        // base (root) coordinates: our origin_velocity[k] and omega[k].
        const KDL::Twist twist = out.GetTwist();
        const KDL::Frame frame = out.GetFrame();
        for (const mbk::Data<double>* d : {&data, &data_pv}) {
          err.origin_velocity =
              std::max(err.origin_velocity, max_abs_diff(twist.vel, d->origin_velocity[k]));
          err.omega = std::max(err.omega, max_abs_diff(twist.rot, d->omega[k]));
          err.chain_position = std::max(err.chain_position, max_abs_diff(frame.p, d->origin[k]));
          err.chain_rotation = std::max(err.chain_rotation, max_abs_diff(frame.M, d->rotation[k]));
        }
        seen[k] = true;
      }
    }
    err.velocity_links = static_cast<int>(std::count(seen.begin() + 1, seen.end(), true));
    EXPECT_EQ(err.velocity_links, model.body_count()) << "links on no root-to-leaf chain";
  }
  return err;
}

void expect_within_tolerance(const Errors& e) {
  EXPECT_LT(e.position, kPoseTolerance);
  EXPECT_LT(e.rotation, kPoseTolerance);
  EXPECT_LT(e.chain_position, kPoseTolerance);
  EXPECT_LT(e.chain_rotation, kPoseTolerance);
  EXPECT_LT(e.origin_velocity, kVelocityTolerance);
  EXPECT_LT(e.omega, kVelocityTolerance);
  std::printf(
      "  %d links, %d chains: pose %.1e m %.1e, chain pose %.1e m %.1e, velocity %.1e m/s, "
      "omega %.1e rad/s; scale %.1f m %.1f m/s\n",
      e.links, e.chains, e.position, e.rotation, e.chain_position, e.chain_rotation,
      e.origin_velocity, e.omega, e.position_scale, e.velocity_scale);
}

KDL::Tree tree_from_file(const std::string& path) {
  KDL::Tree tree;
  EXPECT_TRUE(kdl_parser::treeFromFile(path, tree)) << path;
  return tree;
}

KDL::Tree tree_from_string(const std::string& xml) {
  KDL::Tree tree;
  EXPECT_TRUE(kdl_parser::treeFromString(xml, tree));
  return tree;
}

// random_tree with the joints URDF and KDL share: fixed, revolute, prismatic, ball_123 and
// free_123 (the writer expands the last two into chains of URDF joints). Euler-parameter joints
// have no URDF form; kdl_parser turns URDF planar joints into fixed ones.
mbk::Model urdf_random_tree(int n, unsigned seed) {
  mbk::Model model = mbk_test::random_tree(n, seed);
  for (int k = 1; k <= model.body_count(); ++k) {
    mbk::Joint& joint = model.bodies[k].joint;
    if (joint.type == mbk::JointType::kBallEuler) joint.type = mbk::JointType::kBall123;
    if (joint.type == mbk::JointType::kFreeEuler) joint.type = mbk::JointType::kFree123;
    if (joint.type == mbk::JointType::kPlanar) joint.type = mbk::JointType::kPrismatic;
  }
  mbk::finalize_model(model);
  return model;
}

constexpr int kSamples = 20;

TEST(KdlPeer, HumanBodyUrdf) {
  const std::string path = mbk_test::source_path("config/human_body.urdf");
  const KDL::Tree tree = tree_from_file(path);
  const mbk::Model model = mbk::load_urdf_file(path);
  ASSERT_EQ(model.body_count(), 37);  // 16 bodies and 21 links of the ball and free joints
  const Errors e = compare_with_kdl(model, tree, 1, kSamples);
  EXPECT_EQ(e.chains, 5);  // head, two forearms, two feet
  expect_within_tolerance(e);
}

TEST(KdlPeer, HumanBodySceneAgainstItsUrdf) {
  const KDL::Tree tree = tree_from_file(mbk_test::source_path("config/human_body.urdf"));
  const mbk::Model model = mbk::load_model_file(mbk_test::source_path("config/human_body.yaml"));
  ASSERT_EQ(model.body_count(), 16);
  expect_within_tolerance(compare_with_kdl(model, tree, 2, kSamples));
}

TEST(KdlPeer, TenBodyUrdf) {
  const std::string path = mbk_test::source_path("config/ten_body.urdf");
  const KDL::Tree tree = tree_from_file(path);
  expect_within_tolerance(compare_with_kdl(mbk::load_urdf_file(path), tree, 3, kSamples));
}

TEST(KdlPeer, TenBodySceneAgainstItsUrdf) {
  const KDL::Tree tree = tree_from_file(mbk_test::source_path("config/ten_body.urdf"));
  const mbk::Model model = mbk::load_model_file(mbk_test::source_path("config/ten_body.yaml"));
  ASSERT_EQ(model.body_count(), 10);
  expect_within_tolerance(compare_with_kdl(model, tree, 4, kSamples));
}

TEST(KdlPeer, RandomTrees) {
  for (unsigned seed = 1; seed <= 8; ++seed) {
    SCOPED_TRACE("random tree seed " + std::to_string(seed));
    const mbk::Model model = urdf_random_tree(30, seed);
    const std::string xml = mbk::write_urdf(model, "random");
    const KDL::Tree tree = tree_from_string(xml);
    expect_within_tolerance(compare_with_kdl(model, tree, 100 + seed, kSamples));
    expect_within_tolerance(
        compare_with_kdl(mbk::load_urdf_string(xml), tree, 200 + seed, kSamples));
  }
}

TEST(KdlPeer, RevoluteChain) {
  const mbk::Model model = mbk_test::revolute_chain(40);
  const std::string xml = mbk::write_urdf(model, "chain");
  const KDL::Tree tree = tree_from_string(xml);
  const Errors e = compare_with_kdl(model, tree, 5, kSamples);
  EXPECT_EQ(e.chains, 1);
  expect_within_tolerance(e);
  expect_within_tolerance(compare_with_kdl(mbk::load_urdf_string(xml), tree, 6, kSamples));
}

// The comparison can fail: a joint offset off by 1e-9 m in the middle of the spine shows in the
// poses and in the velocities of every body above it, far beyond the tolerances.
TEST(KdlPeer, DetectsASmallModelError) {
  const KDL::Tree tree = tree_from_file(mbk_test::source_path("config/human_body.urdf"));
  mbk::Model model = mbk::load_model_file(mbk_test::source_path("config/human_body.yaml"));
  const int waist = model.body_index("middle_torso");
  ASSERT_GT(waist, 0);
  model.bodies[waist].joint.offset.x() += 1e-9;
  mbk::finalize_model(model);  // the joint kernels copy the offsets
  const Errors e = compare_with_kdl(model, tree, 7, kSamples);
  EXPECT_GT(e.position, 100 * kPoseTolerance);
  EXPECT_GT(e.origin_velocity, 100 * kVelocityTolerance);
  EXPECT_LT(e.omega, kVelocityTolerance);  // an offset does not change angular velocities
}

// ---- The real-robot conformance set: published robot descriptions nobody on the
// project wrote (test/robots/LICENSES.md), one of each kind. Each loads (imperfect inertias only
// warn), its poses and twists agree with KDL (robot_state_publisher's solver), its system mass is
// the sum of the URDF's <mass> values, root link included, and omega and alpha agree with
// finite differences of the orientations.
struct RealRobot {
  const char* file;
  int bodies;
  bool warns;  // has inertias that are not physical
};

constexpr RealRobot kRealRobots[] = {{"panda", 12, false},  {"anymal_c", 77, true},
                                     {"solo12", 16, false}, {"romeo_small", 57, true},
                                     {"pr2", 81, true},     {"baxter", 56, false}};

// omega_k against the skew part of S0K' S0K^T and alpha_k against omega_k', both from the
// fourth-order central difference along a smooth trajectory of every coordinate.
void expect_rates_match_differences(const mbk::Model& model) {
  const mbk_test::Trajectory trajectory(model, 11);
  const double t = 0.37, h = 1e-3;
  mbk::Data<double> now(model);
  mbk::forward_kinematics(model, trajectory.at<double>(t), now, mbk::Level::kAcceleration);
  std::vector<mbk::Data<double>> around;
  for (double offset : mbk_test::kStencilOffsets) {
    around.emplace_back(model);
    mbk::forward_kinematics(model, trajectory.at<double>(t + offset * h), around.back(),
                            mbk::Level::kAcceleration);
  }
  double omega_error = 0, alpha_error = 0, scale = 1;
  for (int k = 1; k <= model.body_count(); ++k) {
    const mbk::Mat3<double> s_dot = mbk_test::central_difference<mbk::Mat3<double>>(
        [&](int i) { return around[i].rotation[k]; }, h);
    const mbk::Vec3<double> alpha = mbk_test::central_difference<mbk::Vec3<double>>(
        [&](int i) { return around[i].omega[k]; }, h);
    omega_error = std::max(
        omega_error,
        (mbk_test::vee_of_skew_part(s_dot * now.rotation[k].transpose()) - now.omega[k]).norm());
    alpha_error = std::max(alpha_error, (alpha - now.alpha[k]).norm());
    scale = std::max({scale, now.omega[k].norm(), now.alpha[k].norm()});
  }
  EXPECT_LT(omega_error, 1e-8 * scale);  // O(h^4) truncation, far above rounding
  EXPECT_LT(alpha_error, 1e-7 * scale);
}

TEST(RealRobots, LoadAgreeWithKdlAndWeighWhatTheUrdfSays) {
  for (const RealRobot& robot : kRealRobots) {
    const std::string path =
        mbk_test::source_path(std::string("test/robots/") + robot.file + ".urdf");
    SCOPED_TRACE(path);
    const mbk::Model model = mbk::load_urdf_file(path);
    EXPECT_EQ(model.body_count(), robot.bodies);
    EXPECT_EQ(model.warnings.size(), robot.warns ? 1u : 0u);
    const Errors e = compare_with_kdl(model, tree_from_file(path), 21, 5);
    expect_within_tolerance(e);
    mbk::Data<double> data(model);
    mbk::forward_kinematics(model, mbk::JointState<double>(model), data);
    mbk::SystemKinematics<double> system;
    mbk::system_kinematics(model, data, system);
    const double sum = mbk_test::urdf_mass_sum(mbk::read_text_file(path, "URDF"));
    EXPECT_NEAR(system.mass, sum, 1e-12 * sum);
    EXPECT_EQ(system.angular_momentum_known, !robot.warns);
    expect_rates_match_differences(model);
  }
}

}  // namespace
