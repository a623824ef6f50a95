// A Model as URDF text, so that robot_state_publisher, KDL and rviz's RobotModel can use
// YAML scenes. Joints URDF lacks are expanded into chains of URDF joints with the same
// coordinate names: ball_123 into revolutes `<joint>/alpha` (x), `/beta` (new y), `/gamma`
// (new z) (doc/method.md 2: "three hinges about x, then the new y, then the new z"; about the
// axes of the joint's euler_order in its order, e.g. z, new x, new y for ZXY); free_123 into
// prismatics `<joint>/x`, `/y`, `/z` then the same three revolutes. The intermediate links,
// `<body>__<coordinate>`, are massless. Simple visuals (material `mbk_body`, grey-blue): a
// sphere at each mass center and a capsule from each joint point to the next. Mimics are
// written as URDF mimics; names are XML-escaped. Throws std::invalid_argument, naming the
// bodies, for a name with a control character and for two links or joints of one name.
#pragma once

#include <string>

#include "mb_kinematics/core/model.h"

namespace mbk {

enum class UrdfStyle {
  // The same kinematics and coordinates under URDF's joints (for KDL, robot_state_publisher
  // and our URDF loader). Throws std::invalid_argument for Euler-parameter joints, which no
  // URDF joint chain matches.
  kEquivalent,
  // For rviz's RobotModel beside a node that runs the scene itself (and so publishes tf for the
  // scene's bodies only): one link per body, ball and free joints as URDF `floating` joints,
  // no intermediate links. Not for kinematics: the coordinates differ.
  kDisplay,
};

// The comment that marks a written <inertia> as a token (the scene gave none; URDF needs one):
// load_urdf_string then leaves the body without inertia, so nothing is invented.
constexpr const char kTokenInertia[] = "mbk: token inertia, the scene gives none";

std::string write_urdf(const Model& model, const std::string& robot_name,
                       UrdfStyle style = UrdfStyle::kEquivalent);

}  // namespace mbk
