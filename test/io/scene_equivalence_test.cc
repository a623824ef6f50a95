// The shipped scenes in their two forms (config/*.yaml and the URDF generated from it) are the
// same model: same bodies, coordinates and kinematics. Also the body numbering rules of
// doc/method.md 8 (YAML: file order; URDF: breadth-first in the file's joint order).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/partial_velocity.h"
#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/io/urdf_model.h"
#include "mb_kinematics/io/urdf_writer.h"
#include "mb_kinematics/io/yaml_scene.h"
#include "test/support/test_models.h"

namespace {

using mbk_test::source_path;

struct Scene {
  const char* name;  // config/<name>.yaml and config/<name>.urdf; also the URDF robot name
};

const Scene kScenes[] = {{"ten_body"}, {"human_body"}};

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << "cannot open " << path;
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The URDF has a massless link `<body>__<coord>` between the hinges of every expanded ball or
// free joint; it is nowhere in the YAML form.
bool is_intermediate_link(const mbk::Model& yaml, const mbk::Body& body) {
  const size_t sep = body.name.rfind("__");
  if (sep == std::string::npos || yaml.body_index(body.name.substr(0, sep)) < 0) return false;
  const std::string coord = body.name.substr(sep + 2);
  return body.mass == 0 &&
         (coord == "x" || coord == "y" || coord == "z" || coord == "alpha" || coord == "beta");
}

// The same random state in both models, coordinate by coordinate (matched by name).
void random_states(const mbk::Model& yaml, const mbk::Model& urdf, unsigned seed,
                   mbk::JointState<double>& ys, mbk::JointState<double>& us) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < yaml.nq; ++i) {
    const int j = urdf.coordinate_index(yaml.coordinate_names[i]);
    ASSERT_GE(j, 0) << yaml.coordinate_names[i];
    us.position[j] = ys.position[i] = M_PI * u(rng);
    us.velocity[j] = ys.velocity[i] = 2.0 * u(rng);
    us.acceleration[j] = ys.acceleration[i] = 5.0 * u(rng);
  }
}

// Largest norm of a quantity over the bodies: the scale its rounding errors are relative to.
template <typename V>
double max_norm(const std::vector<V>& values) {
  double m = 0;
  for (const V& v : values) m = std::max(m, v.norm());
  return m;
}

// Compares the YAML model's kinematics `a` with the URDF model's `b`, body by body (by name).
// The two forms do the same arithmetic in a different order (a ball joint's A B C in one step
// versus three chained hinges, a deeper tree), so they agree to rounding: a few dozen eps of
// each quantity's scale. 1e-13 (~450 eps) leaves room for that and nothing more; a wrong axis,
// offset or sign is off by far more.
void expect_same_kinematics(const mbk::Model& yaml, const mbk::Data<double>& a,
                            const mbk::Model& urdf, const mbk::Data<double>& b,
                            const std::string& what) {
  const double tol = 1e-13;
  const double s_pos = std::max(max_norm(a.origin), max_norm(a.mass_center));
  const double s_omega = max_norm(a.omega), s_alpha = max_norm(a.alpha);
  const double s_vel = max_norm(a.mass_center_velocity),
               s_acc = max_norm(a.mass_center_acceleration);
  for (int k = 1; k <= yaml.body_count(); ++k) {
    const std::string& name = yaml.bodies[k].name;
    const int u = urdf.body_index(name);
    ASSERT_GT(u, 0) << name << " not in the URDF";
    SCOPED_TRACE(what + ", body " + name);
    EXPECT_LE((a.rotation[k] - b.rotation[u]).norm(), tol) << "rotation";
    EXPECT_LE((a.origin[k] - b.origin[u]).norm(), tol * s_pos) << "origin";
    EXPECT_LE((a.mass_center[k] - b.mass_center[u]).norm(), tol * s_pos) << "mass center";
    EXPECT_LE((a.omega[k] - b.omega[u]).norm(), tol * s_omega) << "omega";
    EXPECT_LE((a.alpha[k] - b.alpha[u]).norm(), tol * s_alpha) << "alpha";
    EXPECT_LE((a.mass_center_velocity[k] - b.mass_center_velocity[u]).norm(), tol * s_vel)
        << "velocity";
    EXPECT_LE((a.mass_center_acceleration[k] - b.mass_center_acceleration[u]).norm(), tol * s_acc)
        << "acceleration";
  }
}

TEST(SceneEquivalence, SameBodiesAndCoordinates) {
  for (const Scene& scene : kScenes) {
    SCOPED_TRACE(scene.name);
    const std::string base = source_path(std::string("config/") + scene.name);
    const mbk::Model yaml = mbk::load_model_file(base + ".yaml");
    const mbk::Model urdf = mbk::load_model_file(base + ".urdf");
    EXPECT_EQ(yaml.frame, urdf.frame);
    ASSERT_EQ(yaml.nq, urdf.nq);
    ASSERT_EQ(yaml.nv, urdf.nv);
    for (const std::string& name : yaml.coordinate_names)
      EXPECT_GE(urdf.coordinate_index(name), 0) << name << " not in the URDF";
    // Every URDF link is a YAML body with the same mass and mass center, or an intermediate
    // link; a YAML body's lower body is reached through its intermediate links only.
    int bodies = 0;
    for (int u = 1; u <= urdf.body_count(); ++u) {
      const mbk::Body& ub = urdf.bodies[u];
      const int k = yaml.body_index(ub.name);
      if (k < 0) {
        EXPECT_TRUE(is_intermediate_link(yaml, ub)) << "unexpected URDF link " << ub.name;
        continue;
      }
      ++bodies;
      EXPECT_EQ(ub.mass, yaml.bodies[k].mass) << ub.name;
      EXPECT_EQ(ub.mass_center, yaml.bodies[k].mass_center) << ub.name;
      int lower = ub.lower;
      while (lower > 0 && is_intermediate_link(yaml, urdf.bodies[lower]))
        lower = urdf.bodies[lower].lower;
      EXPECT_EQ(urdf.bodies[lower].name, yaml.bodies[yaml.bodies[k].lower].name) << ub.name;
    }
    EXPECT_EQ(bodies, yaml.body_count());
  }
}

TEST(SceneEquivalence, SameKinematicsForRandomStates) {
  for (const Scene& scene : kScenes) {
    const std::string base = source_path(std::string("config/") + scene.name);
    const mbk::Model yaml = mbk::load_model_file(base + ".yaml");
    const mbk::Model urdf = mbk::load_model_file(base + ".urdf");
    mbk::Data<double> ya(yaml), ua(urdf), yb(yaml), ub(urdf);
    mbk::PartialVelocities<double> ypv(yaml), upv(urdf);
    for (unsigned seed = 1; seed <= 8; ++seed) {
      mbk::JointState<double> ys(yaml), us(urdf);
      random_states(yaml, urdf, seed, ys, us);
      const std::string what = std::string(scene.name) + " seed " + std::to_string(seed);
      mbk::forward_kinematics(yaml, ys, ya);
      mbk::forward_kinematics(urdf, us, ua);
      expect_same_kinematics(yaml, ya, urdf, ua, what + " recursive");
      mbk::partial_velocity_kinematics(yaml, ys, ypv, yb);
      mbk::partial_velocity_kinematics(urdf, us, upv, ub);
      expect_same_kinematics(yaml, yb, urdf, ub, what + " partial velocities");
    }
  }
}

// The committed URDFs are generated; a scene edit without regenerating them shows up here.
TEST(SceneEquivalence, CommittedUrdfIsUpToDate) {
  for (const Scene& scene : kScenes) {
    const std::string yaml_path = std::string("config/") + scene.name + ".yaml";
    const std::string urdf_path = std::string("config/") + scene.name + ".urdf";
    const std::string generated =
        mbk::write_urdf(mbk::load_model_file(source_path(yaml_path)), scene.name);
    EXPECT_TRUE(generated == read_text(source_path(urdf_path)))
        << urdf_path << " differs from what " << yaml_path
        << " gives now; regenerate it with: rosrun mb_kinematics mbk urdf --model " << yaml_path
        << " --name " << scene.name << " > " << urdf_path;
  }
}

TEST(Numbering, YamlFileOrderIsTheNumbering) {
  const mbk::Model ten = mbk::load_model_file(source_path("config/ten_body.yaml"));
  EXPECT_EQ(ten.lower_body_array(), (std::vector<int>{0, 1, 2, 1, 1, 5, 2, 7, 8, 9}));
  for (int k = 1; k <= 10; ++k) EXPECT_EQ(ten.bodies[k].name, "B" + std::to_string(k));

  const mbk::Model human = mbk::load_model_file(source_path("config/human_body.yaml"));
  EXPECT_EQ(human.lower_body_array(),
            (std::vector<int>{0, 1, 2, 3, 4, 5, 4, 7, 4, 9, 2, 11, 12, 2, 14, 15}));  // Tab. 4.2.2
  EXPECT_EQ(human.bodies[1].name, "pelvis");
  EXPECT_EQ(human.bodies[6].name, "head");
  EXPECT_EQ(human.bodies[16].name, "left_foot");

  // Names out of alphabetical order, lower bodies by name and by number.
  const mbk::Model m = mbk::load_yaml_scene_string(
      "bodies:\n"
      "  - {name: zeta, lower: 0, joint: {type: revolute}}\n"
      "  - {name: alpha, lower: zeta, joint: {type: prismatic}}\n"
      "  - {name: mid, lower: 1, joint: {type: ball_123}}\n"
      "  - {name: beta, lower: alpha, joint: {type: fixed}}\n");
  ASSERT_EQ(m.body_count(), 4);
  EXPECT_EQ(m.bodies[1].name, "zeta");
  EXPECT_EQ(m.bodies[2].name, "alpha");
  EXPECT_EQ(m.bodies[3].name, "mid");
  EXPECT_EQ(m.bodies[4].name, "beta");
  EXPECT_EQ(m.lower_body_array(), (std::vector<int>{0, 1, 1, 2}));
  EXPECT_EQ(m.coordinate_names,
            (std::vector<std::string>{"zeta_joint", "alpha_joint", "mid_joint/alpha",
                                      "mid_joint/beta", "mid_joint/gamma"}));
}

TEST(Numbering, UrdfBreadthFirstInFileJointOrder) {
  // Joints listed neither alphabetically nor breadth-first, links in yet another order.
  // Breadth-first from base in file order: base's joints z_top (c), m_top (b); then c's
  // a_deep (d), y_side (f); then b's b_deep (e). Sorted by joint name it would be b first.
  const char* xml = R"(<?xml version="1.0"?>
<robot name="order">
  <link name="e"/> <link name="d"/> <link name="base"/> <link name="c"/> <link name="f"/>
  <link name="b"/>
  <joint name="a_deep" type="revolute">
    <parent link="c"/> <child link="d"/> <axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="z_top" type="continuous">
    <parent link="base"/> <child link="c"/> <origin xyz="0 0 1"/>
  </joint>
  <joint name="b_deep" type="continuous"> <parent link="b"/> <child link="e"/> </joint>
  <joint name="y_side" type="prismatic">
    <parent link="c"/> <child link="f"/> <axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="m_top" type="fixed"> <parent link="base"/> <child link="b"/> </joint>
</robot>
)";
  const mbk::Model m = mbk::load_urdf_string(xml, "order.urdf");
  EXPECT_EQ(m.frame, "base");
  ASSERT_EQ(m.body_count(), 5);
  std::vector<std::string> names;
  for (int k = 1; k <= m.body_count(); ++k) names.push_back(m.bodies[k].name);
  EXPECT_EQ(names, (std::vector<std::string>{"c", "b", "d", "f", "e"}));
  EXPECT_EQ(m.lower_body_array(), (std::vector<int>{0, 0, 1, 1, 2}));
  for (int k = 1; k <= m.body_count(); ++k) EXPECT_LT(m.bodies[k].lower, k);
  EXPECT_EQ(m.coordinate_names, (std::vector<std::string>{"z_top", "a_deep", "y_side", "b_deep"}));
}

// Ball and free joints in mixed Euler orders (test/io/data/euler_orders.yaml) as chains of URDF
// joints about each order's axes: read back by the URDF loader, every body has the scene's
// pose, angular velocity and acceleration on the same coordinates.
TEST(SceneEquivalence, UrdfAxisChainsFollowEachJointsEulerOrder) {
  const mbk::Model yaml = mbk::load_model_file(source_path("test/io/data/euler_orders.yaml"));
  const mbk::Model urdf = mbk::load_urdf_string(mbk::write_urdf(yaml, "orders"), "orders.urdf");
  mbk::JointState<double> ys(yaml), us(urdf);
  random_states(yaml, urdf, 5, ys, us);
  mbk::Data<double> yd(yaml), ud(urdf);
  mbk::forward_kinematics(yaml, ys, yd);
  mbk::forward_kinematics(urdf, us, ud);
  for (int k = 1; k <= yaml.body_count(); ++k) {
    const std::string& name = yaml.bodies[k].name;
    const int uk = urdf.body_index(name);
    ASSERT_GE(uk, 0) << name;
    EXPECT_LT((yd.rotation[k] - ud.rotation[uk]).norm(), 1e-13) << name;
    EXPECT_LT((yd.origin[k] - ud.origin[uk]).norm(), 1e-13) << name;
    EXPECT_LT((yd.omega[k] - ud.omega[uk]).norm(), 1e-12) << name;
    EXPECT_LT((yd.alpha[k] - ud.alpha[uk]).norm(), 1e-11) << name;
  }
}

}  // namespace
