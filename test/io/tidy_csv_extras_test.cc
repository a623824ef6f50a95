// The tidy CSV's extra columns (io/tidy_csv.h TidyCsvExtras): the body-axes columns are the R
// columns of the same row rotated by the row's own orientation (S0K^T x from qx..qw); the
// angles of a joint that turns past pi continue across the rows (no 2 pi jump) and equal its
// coordinate; the relative omega and alpha are the joint's rate and acceleration; the system row
// leaves every extra cell empty.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/io/tidy_csv.h"

namespace {

using V = mbk::Vec3<double>;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

// Two bodies on revolute joints about z (the second 0.5 along the first's x), a point mass each.
mbk::Model two_hinges() {
  mbk::Model model;
  model.bodies.resize(3);
  for (int k = 1; k <= 2; ++k) {
    mbk::Body& b = model.bodies[k];
    b.name = k == 1 ? "upper" : "lower";
    b.lower = k - 1;
    b.joint.name = b.name + "_joint";
    b.joint.type = mbk::JointType::kRevolute;
    b.joint.axis = k == 1 ? V::UnitY() : V::UnitZ();
    b.joint.offset = k == 1 ? V::Zero() : V(0.5, 0, 0);
    b.mass = 1;
    b.mass_center = V(0.2, 0.1, 0);
  }
  mbk::finalize_model(model);
  return model;
}

TEST(TidyCsvExtras, BodyAxesAnglesAndRelativeMotion) {
  const mbk::Model model = two_hinges();
  mbk::TidyCsvExtras extras;
  extras.body_axes = true;
  extras.angles = {mbk::EulerOrder::kXYZ, mbk::EulerOrder::kZXY, mbk::EulerOrder::kXYZ};
  const std::string path = ::testing::TempDir() + "tidy_extras.csv";
  const int rows = 60;
  {
    mbk::TidyCsvWriter w(path, model, false, "system", extras);
    EXPECT_TRUE(w.sequential());
    mbk::JointState<double> s(model);
    mbk::Data<double> d(model);
    for (int r = 0; r < rows; ++r) {
      const double t = r * 0.01;
      s.position << 0.3 * std::sin(3 * t), 2.9 + t;  // the second joint turns past pi
      s.velocity << 0.9 * std::cos(3 * t), 1.0;
      s.acceleration << -2.7 * std::sin(3 * t), 0.25;
      mbk::forward_kinematics(model, s, d);
      w.write(t, d);
    }
    w.close();
  }
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split(line);
  std::map<std::string, size_t> col;
  for (size_t i = 0; i < header.size(); ++i) col[header[i]] = i;
  for (const char* name : {"omega_body_x", "acceleration_body_z", "angle_order", "angle_3",
                           "relative_omega_z", "relative_alpha_z"})
    ASSERT_TRUE(col.count(name)) << name;
  int lower_rows = 0;
  double last_angle = 0;
  while (std::getline(in, line)) {
    const std::vector<std::string> c = split(line);
    ASSERT_EQ(c.size(), header.size()) << line;
    const auto num = [&](const std::string& name) { return std::stod(c[col.at(name)]); };
    const auto vec = [&](const std::string& name) {
      return V(num(name + "_x"), num(name + "_y"), num(name + "_z"));
    };
    if (c[1] == "system") {
      for (size_t i = col["omega_body_x"]; i < c.size(); ++i) EXPECT_EQ(c[i], "") << header[i];
      continue;
    }
    const Eigen::Quaterniond q(num("qw"), num("qx"), num("qy"), num("qz"));
    const mbk::Mat3<double> st = q.toRotationMatrix().transpose();
    // The quaternion's text is exact; rebuilding S0K from it costs a few ulps: 1e-14 relative.
    for (const char* name : {"omega", "alpha", "velocity", "acceleration"}) {
      const V r = st * vec(name), b = vec(std::string(name) + "_body");
      EXPECT_LE((r - b).norm(), 1e-14 * std::max(1.0, r.norm())) << c[1] << " " << name;
    }
    EXPECT_EQ(c[col["angle_order"]], c[1] == "upper" ? "ZXY" : "XYZ");
    if (c[1] != "lower") continue;
    const double t = num("stamp"), angle = num("angle_3");
    EXPECT_NEAR(angle, 2.9 + t, 1e-14);  // past pi, continuous
    EXPECT_NEAR(num("angle_1"), 0.0, 1e-14);
    EXPECT_NEAR(num("angle_2"), 0.0, 1e-14);
    EXPECT_LE((vec("relative_omega") - V(0, 0, 1.0)).norm(), 1e-14);
    EXPECT_LE((vec("relative_alpha") - V(0, 0, 0.25)).norm(), 1e-14);
    if (lower_rows++) {
      EXPECT_LT(std::abs(angle - last_angle), 0.011);
    }
    last_angle = angle;
  }
  EXPECT_EQ(lower_rows, rows);
  EXPECT_GT(last_angle, M_PI);
}

TEST(TidyCsvExtras, AnglesNeedAnOrderPerBody) {
  const mbk::Model model = two_hinges();
  mbk::TidyCsvExtras extras;
  extras.angles = {mbk::EulerOrder::kXYZ};
  EXPECT_THROW(
      mbk::TidyCsvWriter(::testing::TempDir() + "tidy_bad.csv", model, false, "system", extras),
      std::invalid_argument);
}

}  // namespace
