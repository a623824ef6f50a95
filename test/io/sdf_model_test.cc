// SDFormat models through io/sdf_model.h equal their URDF twins: each URDF of config/ and
// test/robots/ written as SDFormat (every link posed relative_to its parent link, the joint frame
// the child's, axes in the joint frame, the same inertials), then loaded by both loaders: the
// same bodies in the same order, the same coordinates, masses and inertias, and the same
// kinematics (both formulations of the core) on random states to 1e-12 relative. Also: features
// a URDF cannot express (joint frames off the child link, nested models, frames, a joint to the
// world, ball and universal joints) against hand-made YAML twins, and the errors.
#include "mb_kinematics/io/sdf_model.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/urdf_model.h"
#include "mb_kinematics/io/yaml_scene.h"
#include "test/support/test_models.h"

namespace {

constexpr double kRelativeTolerance = 1e-12;

std::string numbers(std::initializer_list<double> values) {
  std::ostringstream out;
  out.precision(17);
  for (double v : values) out << (out.tellp() > 0 ? " " : "") << v;
  return out.str();
}

std::string pose(const mbk::Vec3<double>& p, const mbk::Mat3<double>& r) {
  const Eigen::Vector3d ypr = r.eulerAngles(2, 1, 0);  // R = Rz(yaw) Ry(pitch) Rx(roll)
  return numbers({p.x(), p.y(), p.z(), ypr[2], ypr[1], ypr[0]});
}

// sdformat accepts positive definite inertias only.
bool positive_definite(const mbk::Body& body) {
  return body.has_inertia &&
         Eigen::SelfAdjointEigenSolver<mbk::Mat3<double>>(body.inertia).eigenvalues().minCoeff() >
             0;
}

// A massless link has no <inertial> (sdformat refuses a zero mass: it gets SDFormat's default,
// 1 kg); one whose inertia sdformat refuses (not positive definite) gets 1e-6 kg m^2 about each
// axis.
std::string inertial(const mbk::Body& body) {
  if (body.mass == 0) return "";
  const mbk::Mat3<double> i = positive_definite(body)
                                  ? body.inertia
                                  : mbk::Mat3<double>(1e-6 * mbk::Mat3<double>::Identity());
  return "<inertial><pose>" + pose(body.mass_center, mbk::Mat3<double>::Identity()) +
         "</pose><mass>" + numbers({body.mass}) + "</mass><inertia><ixx>" + numbers({i(0, 0)}) +
         "</ixx><ixy>" + numbers({i(0, 1)}) + "</ixy><ixz>" + numbers({i(0, 2)}) + "</ixz><iyy>" +
         numbers({i(1, 1)}) + "</iyy><iyz>" + numbers({i(1, 2)}) + "</iyz><izz>" +
         numbers({i(2, 2)}) + "</izz></inertia></inertial>";
}

// SDFormat frames share one namespace: a joint named as a link is `<joint>__joint` in the twin.
std::string twin_joint_name(const mbk::Model& model, const std::string& joint) {
  return model.body_index(joint) >= 0 || joint == model.frame ? joint + "__joint" : joint;
}

// The URDF name of a twin's coordinate.
std::string urdf_name(const std::string& coordinate) {
  const std::string tail = "__joint";
  return coordinate.size() > tail.size() &&
                 coordinate.compare(coordinate.size() - tail.size(), tail.size(), tail) == 0
             ? coordinate.substr(0, coordinate.size() - tail.size())
             : coordinate;
}

// The SDFormat twin of a model with fixed, revolute and prismatic joints. A root link named
// `world` (a name SDFormat reserves) is the world: its children are joined to it.
std::string sdf_twin(const mbk::Model& model) {
  std::string sdf = "<?xml version=\"1.0\"?>\n<sdf version=\"1.9\"><model name=\"twin\">\n";
  const bool world = model.frame == "world";
  if (!world)
    sdf += "<link name=\"" + model.frame + "\">" + inertial(model.bodies[0]) + "</link>\n";
  for (int k = 1; k <= model.body_count(); ++k) {
    const mbk::Body& b = model.bodies[k];
    const std::string& parent = model.bodies[b.lower].name;
    const std::string relative_to = world && b.lower == 0 ? "" : " relative_to=\"" + parent + "\"";
    sdf += "<link name=\"" + b.name + "\"><pose" + relative_to + ">" +
           pose(b.joint.offset, b.joint.rotation) + "</pose>" + inertial(b) + "</link>\n";
    const char* type = b.joint.type == mbk::JointType::kRevolute    ? "revolute"
                       : b.joint.type == mbk::JointType::kPrismatic ? "prismatic"
                                                                    : "fixed";
    EXPECT_TRUE(b.joint.type == mbk::JointType::kFixed || type[0] != 'f') << b.joint.name;
    sdf += "<joint name=\"" + twin_joint_name(model, b.joint.name) + "\" type=\"" + type +
           "\"><parent>" + parent + "</parent><child>" + b.name + "</child>";
    if (type[0] != 'f')
      sdf += "<axis><xyz>" + numbers({b.joint.axis.x(), b.joint.axis.y(), b.joint.axis.z()}) +
             "</xyz></axis>";
    sdf += "</joint>\n";
  }
  return sdf + "</model></sdf>\n";
}

struct Error {
  double diff = 0, scale = 0;
  template <typename A, typename B>
  void add(const A& a, const B& b) {
    diff = std::max(diff, (a - b).cwiseAbs().maxCoeff());
    scale = std::max(scale, b.norm());
  }
  double relative() const { return scale > 0 ? diff / scale : diff; }
};

// Both models' kinematics on `samples` random states of `a` (mimics applied), copied into `b`'s
// coordinates by name; bodies matched by name.
void expect_same_kinematics(const mbk::Model& a, const mbk::Model& b, int samples) {
  std::mt19937 rng(5);
  mbk::Data<double> da(a), db(b);
  Error origin, rotation, mass_center, omega, alpha, velocity, acceleration;
  for (int n = 0; n < samples; ++n) {
    mbk::JointState<double> sa = mbk::random_state(a, rng);
    mbk::apply_mimics(a, sa);
    mbk::JointState<double> sb(b);
    for (int i = 0; i < b.nq; ++i) {
      const int j = a.coordinate_index(urdf_name(b.coordinate_names[i]));
      ASSERT_GE(j, 0) << b.coordinate_names[i];
      sb.position[i] = sa.position[j];
      sb.velocity[i] = sa.velocity[j];
      sb.acceleration[i] = sa.acceleration[j];
    }
    mbk::forward_kinematics(a, sa, da, mbk::Level::kAcceleration);
    mbk::forward_kinematics(b, sb, db, mbk::Level::kAcceleration);
    for (int k = 1; k <= a.body_count(); ++k) {
      const int m = b.body_index(a.bodies[k].name);
      ASSERT_GT(m, 0) << a.bodies[k].name;
      origin.add(db.origin[m], da.origin[k]);
      rotation.add(db.rotation[m], da.rotation[k]);
      mass_center.add(db.mass_center[m], da.mass_center[k]);
      omega.add(db.omega[m], da.omega[k]);
      alpha.add(db.alpha[m], da.alpha[k]);
      velocity.add(db.mass_center_velocity[m], da.mass_center_velocity[k]);
      acceleration.add(db.mass_center_acceleration[m], da.mass_center_acceleration[k]);
    }
  }
  rotation.scale = 1;
  for (const auto& [name, e] : {std::pair<const char*, Error>{"origin", origin},
                                {"rotation", rotation},
                                {"mass center", mass_center},
                                {"omega", omega},
                                {"alpha", alpha},
                                {"velocity", velocity},
                                {"acceleration", acceleration}})
    EXPECT_LE(e.relative(), kRelativeTolerance) << name << ", scale " << e.scale;
}

void expect_same_structure(const mbk::Model& urdf, const mbk::Model& sdf) {
  ASSERT_EQ(sdf.body_count(), urdf.body_count());
  EXPECT_EQ(sdf.frame, urdf.frame);
  for (int k = 0; k <= urdf.body_count(); ++k) {
    const mbk::Body& a = urdf.bodies[k];
    const mbk::Body& b = sdf.bodies[k];
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.lower, a.lower) << a.name;
    EXPECT_EQ(b.joint.type, a.joint.type) << a.name;
    const bool world = k == 0 && urdf.frame == "world";  // not a link of the twin
    EXPECT_NEAR(b.mass, a.mass == 0 && !world ? 1.0 : a.mass, 1e-12 * std::max(1.0, a.mass))
        << a.name;
    if (positive_definite(a)) {
      EXPECT_LE((b.inertia - a.inertia).cwiseAbs().maxCoeff(), 1e-12 * (1 + a.inertia.norm()))
          << a.name;
    }
  }
  std::vector<std::string> ca = urdf.coordinate_names, cb;
  for (const std::string& c : sdf.coordinate_names) cb.push_back(urdf_name(c));
  std::sort(ca.begin(), ca.end());
  std::sort(cb.begin(), cb.end());
  EXPECT_EQ(cb, ca);
}

TEST(SdfModel, UrdfTwinsLoadToTheSameModel) {
  for (const char* file :
       {"config/human_body.urdf", "config/ten_body.urdf", "test/robots/anymal_c.urdf",
        "test/robots/baxter.urdf", "test/robots/panda.urdf", "test/robots/pr2.urdf",
        "test/robots/romeo_small.urdf", "test/robots/solo12.urdf"}) {
    SCOPED_TRACE(file);
    const mbk::Model urdf = mbk::load_urdf_file(mbk_test::source_path(file));
    const mbk::Model sdf = mbk::load_sdf_string(sdf_twin(urdf), file);
    expect_same_structure(urdf, sdf);
    expect_same_kinematics(urdf, sdf, 20);
  }
}

std::string error_of(const std::string& text) {
  try {
    mbk::load_model(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SdfModel, WhatDoesNotMapIsOneLineNamingIt) {
  const std::string screw = R"(<sdf version="1.9"><model name="m"><link name="a"/><link name="b"/>
      <joint name="s" type="screw"><parent>a</parent><child>b</child>
      <axis><xyz>0 0 1</xyz></axis></joint></model></sdf>
)";
  EXPECT_EQ(error_of(screw),
            "<text>: joint 's': type screw does not map (revolute, continuous, prismatic, fixed, "
            "ball and universal do)");
  const std::string loop = R"(<sdf version="1.9"><model name="m"><link name="a"/><link name="b"/>
      <link name="c"/><joint name="j1" type="fixed"><parent>a</parent><child>b</child></joint>
      <joint name="j2" type="fixed"><parent>c</parent><child>b</child></joint></model></sdf>
)";
  EXPECT_EQ(error_of(loop),
            "<text>: link 'b' is the child of two joints ('j1' and 'j2'): a closed loop, not a "
            "tree");
  const std::string refused = error_of("<sdf version=\"1.9\"><model name=\"m\"></model></sdf>\n");
  EXPECT_EQ(refused.rfind("<text>: sdformat refuses the model: ", 0), 0u) << refused;
  EXPECT_EQ(refused.find('\n'), std::string::npos) << refused;
}

TEST(SdfModel, SdfFilesAndTextLoadThroughLoadModel) {
  const std::string path = mbk_test::source_path("test/io/data/sdf_features.sdf");
  const mbk::Model model = mbk::load_model_file(path);
  EXPECT_EQ(model.frame, "world");
  EXPECT_GT(model.body_index("hand::palm"), 0);
  EXPECT_GE(model.coordinate_index("wrist/e4"), 0);
  EXPECT_GE(model.coordinate_index("hand::knuckle/beta"), 0);
  EXPECT_GT(model.body_index("arm__shoulder"), 0);  // the joint frame is not arm's
}

}  // namespace
