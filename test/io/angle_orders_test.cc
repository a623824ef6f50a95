// mbk bag --angles' orders (io/angle_orders.h): one order for every body, a YAML file by body or
// joint name with a default, and a one-line error for each mistake.
#include "mb_kinematics/io/angle_orders.h"

#include <gtest/gtest.h>

#include <string>

#include "mb_kinematics/io/yaml_scene.h"

namespace {

using mbk::EulerOrder;

const char kScene[] = R"(frame: world
bodies:
  - {name: thigh, lower: 0, joint: {name: hip, type: ball_123}, mass: 1}
  - {name: shank, lower: thigh, joint: {name: knee, type: revolute, axis: [0, 1, 0]}, mass: 1}
  - {name: foot, lower: shank, joint: {name: ankle, type: revolute, axis: [0, 1, 0]}, mass: 1}
)";

std::string error_of(const mbk::Model& model, const std::string& yaml) {
  try {
    mbk::parse_angle_orders(model, yaml, "orders.yaml");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(AngleOrders, OneForAllOrAFile) {
  const mbk::Model model = mbk::load_yaml_scene_string(kScene, "scene");
  const std::vector<EulerOrder> all = mbk::angle_orders(model, "zxy");
  ASSERT_EQ(all.size(), 4u);
  for (int k = 1; k <= 3; ++k) EXPECT_EQ(all[k], EulerOrder::kZXY);
  const std::vector<EulerOrder> some =
      mbk::parse_angle_orders(model, "hip: YXZ\nfoot: 313\ndefault: XZY\n", "orders.yaml");
  EXPECT_EQ(some[1], EulerOrder::kYXZ);
  EXPECT_EQ(some[2], EulerOrder::kXZY);
  EXPECT_EQ(some[3], EulerOrder::kZXZ);
  EXPECT_THROW(mbk::angle_orders(model, "XXY"), std::invalid_argument);
}

TEST(AngleOrders, MistakesNamed) {
  const mbk::Model model = mbk::load_yaml_scene_string(kScene, "scene");
  EXPECT_EQ(error_of(model, "hip: YXZ\n"),
            "orders.yaml: no order for shank, foot (name them, or give default: ORDER)");
  EXPECT_EQ(error_of(model, "default: XYZ\nelbow: XYZ\n"),
            "orders.yaml:2: no body or joint named elbow");
  EXPECT_EQ(error_of(model, "default: XYZ\nhip: XYZ\nthigh: ZYX\n"),
            "orders.yaml:3: body thigh given an order twice (also on line 2)");
  EXPECT_NE(error_of(model, "default: XYZ\nhip: XYY\n")
                .find("orders.yaml:2: hip: unknown Euler "
                      "order 'XYY'"),
            std::string::npos);
  EXPECT_EQ(error_of(model, "- XYZ\n"), "orders.yaml: expected a map of body or joint name: order");
  EXPECT_NE(error_of(model, "a: [\n").find("orders.yaml: not YAML"), std::string::npos);
}

}  // namespace
