// Bare YAML scenes read from the parser's events (io/yaml_bare_scene.h), without yaml-cpp's node
// tree: the same model and the same errors, line for line, as through the tree, which reads
// everything that is not a plain bare scene.
#include "mb_kinematics/io/yaml_bare_scene.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "mb_kinematics/io/yaml_scene.h"

namespace {

// The load's lower body array and joint types, or its error.
std::string outcome(const std::string& text) {
  try {
    const mbk::Model model = mbk::load_yaml_scene_string(text, "scene.yaml");
    std::string out = model.frame + (model.speeds == mbk::SpeedKind::kAngularVelocity ? " w" : "");
    for (int k = 1; k <= model.body_count(); ++k)
      out += " " + std::to_string(model.bodies[k].lower) + ":" +
             mbk::to_string(model.bodies[k].joint.type);
    return out;
  } catch (const std::invalid_argument& e) {
    return std::string("error ") + e.what();
  }
}

TEST(YamlBareScene, SameModelsAndErrorsAsTheNodeTree) {
  const std::vector<std::string> scenes = {
      "lower_body_array: [0, 1, 1, 3]\n",
      "lower_body_array:\n  - 0\n  - 1\n  - 0x2\njoint_type: revolute\nframe: base\n",
      "frame: w\nspeeds: angular_velocity\nlower_body_array: [0, 0, '1']\n",
      "lower_body_array: [0, 1.5]\n",
      "lower_body_array: [0, 1, 3]\n",
      "lower_body_array: [0, x]\n",
      "lower_body_array: [0, .inf]\n",
      "lower_body_array: [0, 1]\njoint_type: hinge\n",
      "lower_body_array: [0, 1]\nspeeds: fast\n",
      "frame: ''\nlower_body_array: [0]\n",
      "lower_body_array: [0, 1e10]\n",
      "lower_body_array: []\n",
      "notes: {a: [1, 2]}\nlower_body_array: [0, 1]\n",
  };
  for (const std::string& text : scenes) {
    // An unused anchor sends the text to the node tree.
    EXPECT_EQ(outcome(text), outcome(text + "unused: &a 1\n")) << text;
  }
}

TEST(YamlBareScene, OnlyPlainBareScenesAreReadFromEvents) {
  mbk::Model model;
  EXPECT_TRUE(mbk::read_bare_scene("lower_body_array: [0, 1]\n", model));
  EXPECT_EQ(model.body_count(), 2);
  for (const char* other :
       {"bodies: []\nlower_body_array: [0]\n", "lower_body_array: [0, &a 1, *a]\n",
        "lower_body_array: 0\n", "lower_body_array: [0, [1]]\n", "lower_body_array: [0, ~]\n",
        "[0, 1]\n", "frame: {a: 1}\nlower_body_array: [0]\n",
        "lower_body_array: [0]\nlower_body_array: [0]\n", "frame: w\n"})
    EXPECT_FALSE(mbk::read_bare_scene(other, model)) << other;
}

}  // namespace
