// Peer check against MuJoCo itself (doc/method.md 8): an MJCF model loaded by io/mjcf_model.h
// moves as MuJoCo moves it. Per MJCF body, the frame (origin, S0K), the mass center, omega,
// alpha and the mass center's velocity and acceleration from both formulations (recursive and
// partial velocities) equal MuJoCo's xpos, xmat, xipos and, with gravity off, mj_objectVelocity
// and mj_objectAcceleration at the inertial frame (after mj_kinematics, mj_comPos, mj_comVel and
// mj_rnePostConstraint), on random MJCF trees (every joint type, several joints per body, joint
// anchors off the body frame, refs, free roots), on the shipped MJCF models, and on URDF models
// (the human model, the published robots) as MuJoCo's own URDF import reads them.
//
// States go from MuJoCo's (qpos, qvel, qacc) to ours by coordinate name
// (test/support/mujoco_state.h).
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/io/mjcf_model.h"
#include "mb_kinematics/io/text_file.h"
#include "mb_kinematics/io/urdf_model.h"
#include "test/support/mujoco_state.h"
#include "test/support/mujoco_urdf.h"
#include "test/support/temp_file.h"
#include "test/support/test_models.h"

namespace {

// Tolerance, relative to the largest magnitude of the quantity over the bodies and samples (1 for
// rotation matrices): both programs compose the same rigid motions in double with a different
// order of operations, so they differ by rounding only.
constexpr double kRelativeTolerance = 1e-12;

struct MjDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using MjModelPtr = std::unique_ptr<mjModel, MjDeleter>;
using MjDataPtr = std::unique_ptr<mjData, MjDeleter>;

MjModelPtr mujoco_load(const std::string& path) {
  char error[1000] = "";
  MjModelPtr m(mj_loadXML(path.c_str(), nullptr, error, sizeof error));
  EXPECT_TRUE(m) << path << ": " << error;
  return m;
}

// The largest difference of one quantity and the largest magnitude of MuJoCo's.
struct Error {
  double diff = 0, scale = 0;
  template <typename A, typename B>
  void add(const A& ours, const B& theirs) {
    diff = std::max(diff, (ours - theirs).cwiseAbs().maxCoeff());
    scale = std::max(scale, theirs.norm());
  }
  double relative() const { return scale > 0 ? diff / scale : diff; }
};

struct Errors {
  Error origin, rotation, mass_center, omega, alpha, velocity, acceleration;
  int bodies = 0;
};

using Vec3 = Eigen::Vector3d;
using RowMat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

Vec3 vec(const mjtNum* v) { return Vec3(v[0], v[1], v[2]); }

// MuJoCo's model `m` and ours of the same file moved at `samples` random states of MuJoCo's.
Errors compare_with_mujoco(const MjModelPtr& m, const mbk::Model& model, unsigned seed, int samples,
                           bool impose_our_mimics = false) {
  Errors err;
  if (!m) return err;
  m->opt.gravity[0] = m->opt.gravity[1] = m->opt.gravity[2] = 0;  // cacc holds -gravity else
  const MjDataPtr d(mj_makeData(m.get()));
  mbk::Data<double> data(model), data_pv(model);
  mbk::PartialVelocities<double> pv(model);
  std::mt19937 rng(seed);
  for (int n = 0; n < samples; ++n) {
    mbk_test::random_mujoco_state(m.get(), d.get(), rng);
    const mbk::JointState<double> state = mbk_test::our_state(m.get(), d.get(), model);
    if (impose_our_mimics) mbk_test::impose_mimics(m.get(), d.get(), model, state);
    mj_kinematics(m.get(), d.get());
    mj_comPos(m.get(), d.get());
    mj_comVel(m.get(), d.get());
    mj_rnePostConstraint(m.get(), d.get());
    mbk::forward_kinematics(model, state, data, mbk::Level::kAcceleration);
    mbk::partial_velocity_kinematics(model, state, pv, data_pv, mbk::Level::kAcceleration);
    for (int b = 1; b < m->nbody; ++b) {
      const std::string name = m->names + m->name_bodyadr[b];
      if (name == model.bodies[0].name) continue;  // a URDF's root link: our R, welded in MuJoCo
      const int k = model.body_index(name);
      EXPECT_GT(k, 0) << "MuJoCo's body " << name << " is no body of ours";
      if (k <= 0) continue;
      mjtNum velocity[6], acceleration[6];  // rotational, then linear; at xipos, world axes
      mj_objectVelocity(m.get(), d.get(), mjOBJ_BODY, b, velocity, 0);
      mj_objectAcceleration(m.get(), d.get(), mjOBJ_BODY, b, acceleration, 0);
      for (const mbk::Data<double>* ours : {&data, &data_pv}) {
        err.origin.add(ours->origin[k], vec(d->xpos + 3 * b));
        err.rotation.add(ours->rotation[k], Eigen::Map<const RowMat3>(d->xmat + 9 * b));
        err.mass_center.add(ours->mass_center[k], vec(d->xipos + 3 * b));
        err.omega.add(ours->omega[k], vec(velocity));
        err.velocity.add(ours->mass_center_velocity[k], vec(velocity + 3));
        err.alpha.add(ours->alpha[k], vec(acceleration));
        err.acceleration.add(ours->mass_center_acceleration[k], vec(acceleration + 3));
      }
      ++err.bodies;
    }
  }
  err.rotation.scale = 1;
  return err;
}

Errors compare_with_mujoco(const std::string& mjcf_path, unsigned seed, int samples) {
  return compare_with_mujoco(mujoco_load(mjcf_path), mbk::load_mjcf_file(mjcf_path), seed, samples);
}

// A URDF file read by MuJoCo's URDF import (test/support/mujoco_urdf.h) and by ours; MuJoCo's
// import drops <mimic>, so MuJoCo's state takes our mimic coordinates.
Errors compare_urdf_with_mujoco(const std::string& path, unsigned seed, int samples) {
  const std::string urdf = mbk::read_text_file(path, "URDF");
  std::string error;
  const MjModelPtr m(mbk_test::load_urdf_in_mujoco(urdf, &error));
  EXPECT_TRUE(m) << path << ": " << error;
  return compare_with_mujoco(m, mbk::load_urdf_string(urdf, "model"), seed, samples, true);
}

void expect_equal_to_mujoco(const Errors& e, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_GT(e.bodies, 0);
  EXPECT_LE(e.origin.relative(), kRelativeTolerance) << "origin, scale " << e.origin.scale;
  EXPECT_LE(e.rotation.relative(), kRelativeTolerance) << "rotation";
  EXPECT_LE(e.mass_center.relative(), kRelativeTolerance) << "mass center";
  EXPECT_LE(e.omega.relative(), kRelativeTolerance) << "omega, scale " << e.omega.scale;
  EXPECT_LE(e.velocity.relative(), kRelativeTolerance) << "velocity, scale " << e.velocity.scale;
  EXPECT_LE(e.alpha.relative(), kRelativeTolerance) << "alpha, scale " << e.alpha.scale;
  EXPECT_LE(e.acceleration.relative(), kRelativeTolerance)
      << "acceleration, scale " << e.acceleration.scale;
  std::printf(
      "%s: %d body samples; relative errors origin %.1e rotation %.1e mass center %.1e "
      "omega %.1e velocity %.1e alpha %.1e acceleration %.1e\n",
      what.c_str(), e.bodies, e.origin.relative(), e.rotation.relative(), e.mass_center.relative(),
      e.omega.relative(), e.velocity.relative(), e.alpha.relative(), e.acceleration.relative());
}

// A random MJCF tree: the shape of make_random_tree's (the project's generator), and per body a
// random pos and quat, 0 to 3 joints (hinge, slide, ball as the last; a child of the world may
// instead be on a free joint), anchors on and off the body frame, random refs, axes and inertials.
std::string random_mjcf(int n, unsigned seed) {
  const std::vector<int> lower = mbk::make_random_tree(n, seed).lower_body_array();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), unit(0, 1);
  std::vector<std::vector<int>> children(n + 1);
  for (int k = 1; k <= n; ++k) children[lower[k - 1]].push_back(k);
  std::ostringstream x;
  x.precision(17);
  const auto v3 = [&] {
    return std::to_string(u(rng)) + " " + std::to_string(u(rng)) + " " + std::to_string(u(rng));
  };
  const auto v4 = [&] { return v3() + " " + std::to_string(u(rng)); };
  std::function<void(int)> body = [&](int k) {
    x << "<body name=\"b" << k << "\" pos=\"" << v3() << "\" quat=\"" << v4() << "\">\n";
    const double a = 0.1 + 0.9 * unit(rng), b = 0.1 + 0.9 * unit(rng);
    const double c = std::abs(a - b) + (a + b - std::abs(a - b)) * (0.1 + 0.8 * unit(rng));
    x << "<inertial mass=\"" << 0.5 + 1.5 * unit(rng) << "\" pos=\"" << v3() << "\" quat=\"" << v4()
      << "\" diaginertia=\"" << a << " " << b << " " << c << "\"/>\n";
    if (lower[k - 1] == 0 && unit(rng) < 0.3) {
      x << "<joint name=\"j" << k << "\" type=\"free\"/>\n";
    } else {
      const int joints = static_cast<int>(unit(rng) * 4);
      for (int i = 0; i < joints; ++i) {
        const double t = unit(rng);  // MuJoCo: no rotation after a ball in one body
        const char* type = t < 0.5 ? "hinge" : t < 0.75 || i + 1 < joints ? "slide" : "ball";
        x << "<joint name=\"j" << k << "_" << i << "\" type=\"" << type << "\" pos=\""
          << (unit(rng) < 0.5 ? "0 0 0" : v3()) << "\" axis=\"" << v3() << "\"";
        if (type[0] != 'b') x << " ref=\"" << u(rng) << "\"";
        x << "/>\n";
      }
    }
    for (int child : children[k]) body(child);
    x << "</body>\n";
  };
  x << "<mujoco model=\"random\"><compiler angle=\"radian\"/><worldbody>\n";
  for (int child : children[0]) body(child);
  x << "</worldbody></mujoco>\n";
  return x.str();
}

TEST(MujocoPeer, RandomTreesMoveAsInMujoco) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const std::string path =
        mbk_test::write_temp(random_mjcf(5 + 3 * static_cast<int>(seed), seed), "random.xml");
    expect_equal_to_mujoco(compare_with_mujoco(path, seed, 10), "seed " + std::to_string(seed));
  }
}

TEST(MujocoPeer, ShippedModelsMoveAsInMujoco) {
  for (const char* file : {"humanoid.xml", "panda.xml", "op3.xml"})
    expect_equal_to_mujoco(
        compare_with_mujoco(mbk_test::source_path(std::string("test/robots/mjcf/") + file), 7, 50),
        file);
}

}  // namespace

// The URDF path against MuJoCo's own URDF import: the human model (ball and free joints as
// chains of one-axis joints between massless links, the links with mass holding their mass
// centers off the link frame).
TEST(MujocoPeer, HumanUrdfMovesAsInMujoco) {
  expect_equal_to_mujoco(
      compare_urdf_with_mujoco(mbk_test::source_path("config/human_body.urdf"), 3, 50),
      "config/human_body.urdf");
}

// The published robot descriptions (test/robots/LICENSES.md): fixed joints, continuous wheels,
// prismatic torsos, mimic grippers, inertials rotated off the link frames.
TEST(MujocoPeer, RobotUrdfsMoveAsInMujoco) {
  for (const char* file : {"solo12", "anymal_c", "romeo_small", "panda", "baxter", "pr2"}) {
    const std::string path = std::string("test/robots/") + file + ".urdf";
    expect_equal_to_mujoco(compare_urdf_with_mujoco(mbk_test::source_path(path), 5, 20), path);
  }
}

// Why the URDF reaches MuJoCo with explicit inertials: a body with neither an inertial nor a
// geom gets its own pos (its frame in its parent's) as its inertial frame's position in its own
// frame, so the mass center of a massless link after an offset joint lands off the link frame.
TEST(MujocoPeer, MujocoPutsAnInertialFreeBodysMassCenterAtItsPos) {
  const std::string urdf =
      "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" "
      "type=\"continuous\"><origin xyz=\"0 0 0.5\"/><parent link=\"a\"/><child link=\"b\"/>"
      "<axis xyz=\"1 0 0\"/></joint></robot>";
  const auto ipos_of_b = [](const std::string& text) {
    char error[1000] = "";
    const std::string path = mbk_test::write_temp(text, "inertial_free.urdf");
    const MjModelPtr m(mj_loadXML(path.c_str(), nullptr, error, sizeof error));
    EXPECT_TRUE(m) << error;
    if (!m) return Vec3(Vec3::Constant(NAN));
    const int b = mj_name2id(m.get(), mjOBJ_BODY, "b");
    EXPECT_GT(b, 0);
    return vec(m->body_ipos + 3 * b);
  };
  const std::string bare =
      "<robot name=\"r\"><mujoco><compiler fusestatic=\"false\" "
      "boundmass=\"1e-6\" boundinertia=\"1e-9\"/></mujoco>" +
      urdf.substr(std::string("<robot name=\"r\">").size());
  EXPECT_EQ(ipos_of_b(bare), Vec3(0, 0, 0.5));
  std::string error;
  const MjModelPtr m(mbk_test::load_urdf_in_mujoco(urdf, &error));
  ASSERT_TRUE(m) << error;
  EXPECT_EQ(vec(m->body_ipos + 3 * mj_name2id(m.get(), mjOBJ_BODY, "b")), Vec3::Zero());
}
