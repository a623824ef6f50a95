// The SDFormat reader library (sdformat_reader.h): libsdformat12's model into ours. Frames come
// from sdformat's semantic pose API: each joint's frame resolved relative to its parent and its
// child link (relative_to, frames, nested models handled by sdformat itself).
#include "mb_kinematics/io/sdformat_reader.h"

#include <ignition/math/Inertial.hh>
#include <ignition/math/Pose3.hh>
#include <map>
#include <sdf/Console.hh>
#include <sdf/Joint.hh>
#include <sdf/JointAxis.hh>
#include <sdf/Link.hh>
#include <sdf/Model.hh>
#include <sdf/Root.hh>
#include <sdf/World.hh>
#include <stdexcept>
#include <vector>

#include "mb_kinematics/core/printable.h"

namespace mbk {
namespace {

using Pose = ignition::math::Pose3d;

// One line from sdformat's errors: the first (its first 300 characters: a text it cannot parse
// is quoted whole), and how many more.
std::string first_error(const sdf::Errors& errors) {
  std::string line = errors.front().Message();
  if (line.size() > 300) line = line.substr(0, 300) + "...";
  for (char& c : line)
    if (c == '\n') c = ' ';
  if (errors.size() > 1) line += " (and " + std::to_string(errors.size() - 1) + " more)";
  return line;
}

void check(const sdf::Errors& errors, const std::string& what) {
  if (!errors.empty()) throw std::invalid_argument(what + ": " + first_error(errors));
}

Vec3<double> vec3(const ignition::math::Vector3d& v) { return Vec3<double>(v.X(), v.Y(), v.Z()); }

Mat3<double> rotation(const ignition::math::Quaterniond& q) {
  return Eigen::Quaterniond(q.W(), q.X(), q.Y(), q.Z()).normalized().toRotationMatrix();
}

// Links and joints of a model and its nested models, with scoped names (`nested::link`), the
// joints in the order the file lists them (each model's before its nested models').
struct ScopedLink {
  std::string name;
  const sdf::Link* link;
  Pose model_pose;  // the link's model frame in the top model's frame
};
struct ScopedJoint {
  std::string name, scope;  // scope: "" or "nested::"
  const sdf::Joint* joint;
  Pose model_pose;  // the joint's model frame in the top model's frame
};

void collect(const sdf::Model& model, const std::string& scope, const Pose& model_pose,
             std::vector<ScopedLink>& links, std::vector<ScopedJoint>& joints) {
  for (uint64_t i = 0; i < model.LinkCount(); ++i)
    links.push_back({scope + model.LinkByIndex(i)->Name(), model.LinkByIndex(i), model_pose});
  for (uint64_t i = 0; i < model.JointCount(); ++i) {
    const sdf::Joint* joint = model.JointByIndex(i);
    joints.push_back({scope + joint->Name(), scope, joint, model_pose});
  }
  for (uint64_t i = 0; i < model.ModelCount(); ++i) {
    const sdf::Model& nested = *model.ModelByIndex(i);
    Pose pose;
    check(nested.SemanticPose().Resolve(pose), "nested model '" + scope + nested.Name() + "'");
    collect(nested, scope + nested.Name() + "::", model_pose * pose, links, joints);
  }
}

// The one model of a file: its <model>, or the only model of its <world>.
const sdf::Model& the_model(const sdf::Root& root) {
  if (root.Model()) return *root.Model();
  if (root.WorldCount() == 1 && root.WorldByIndex(0)->ModelCount() == 1)
    return *root.WorldByIndex(0)->ModelByIndex(0);
  throw std::invalid_argument(
      "no single model: the file has " + std::to_string(root.WorldCount()) + " worlds" +
      (root.WorldCount() == 1
           ? " with " + std::to_string(root.WorldByIndex(0)->ModelCount()) + " models"
           : std::string()) +
      "; give a file with one <model>");
}

const char* type_name(sdf::JointType type) {
  switch (type) {
    case sdf::JointType::BALL:
      return "ball";
    case sdf::JointType::CONTINUOUS:
      return "continuous";
    case sdf::JointType::FIXED:
      return "fixed";
    case sdf::JointType::GEARBOX:
      return "gearbox";
    case sdf::JointType::PRISMATIC:
      return "prismatic";
    case sdf::JointType::REVOLUTE:
      return "revolute";
    case sdf::JointType::REVOLUTE2:
      return "revolute2";
    case sdf::JointType::SCREW:
      return "screw";
    case sdf::JointType::UNIVERSAL:
      return "universal";
    case sdf::JointType::INVALID:
      break;
  }
  return "invalid";
}

Vec3<double> axis_of(const ScopedJoint& j, unsigned index) {
  const sdf::JointAxis* axis = j.joint->Axis(index);
  if (!axis)
    throw std::invalid_argument("joint '" + j.name + "' has no axis " + std::to_string(index + 1));
  ignition::math::Vector3d xyz;  // in the joint frame
  check(axis->ResolveXyz(xyz), "joint '" + j.name + "' axis");
  return vec3(xyz).normalized();
}

// Our joint type and axis (in the joint frame); a universal joint's two axes (perpendicular)
// become the joint frame's x and y: `turn` is that frame in the SDFormat joint frame.
void set_type(const ScopedJoint& j, Joint& joint, Mat3<double>& turn) {
  turn.setIdentity();
  switch (j.joint->Type()) {
    case sdf::JointType::REVOLUTE:
    case sdf::JointType::CONTINUOUS:
      joint.type = JointType::kRevolute;
      joint.axis = axis_of(j, 0);
      return;
    case sdf::JointType::PRISMATIC:
      joint.type = JointType::kPrismatic;
      joint.axis = axis_of(j, 0);
      return;
    case sdf::JointType::FIXED:
      joint.type = JointType::kFixed;
      return;
    case sdf::JointType::BALL:
      joint.type = JointType::kBallEuler;
      return;
    case sdf::JointType::UNIVERSAL: {
      const Vec3<double> a = axis_of(j, 0), b = axis_of(j, 1);
      if (std::abs(a.dot(b)) > 1e-12)
        throw std::invalid_argument("universal joint '" + j.name +
                                    "': its axes are not perpendicular, which does not map");
      joint.type = JointType::kUniversal;
      turn << a, b, a.cross(b);
      return;
    }
    case sdf::JointType::GEARBOX:
    case sdf::JointType::REVOLUTE2:
    case sdf::JointType::SCREW:
    case sdf::JointType::INVALID:
      break;
  }
  throw std::invalid_argument(std::string("joint '") + j.name + "': type " +
                              type_name(j.joint->Type()) +
                              " does not map (revolute, continuous, prismatic, fixed, ball and "
                              "universal do)");
}

// m_k, r_k and I_k from the link's <inertial> (sdformat's defaults where it has none: 1 kg and a
// unit inertia, as SDFormat specifies).
void set_mass_properties(const sdf::Link& link, Body& body) {
  const ignition::math::Inertiald& inertial = link.Inertial();
  body.mass = inertial.MassMatrix().Mass();
  body.mass_center = vec3(inertial.Pose().Pos());
  const Mat3<double> r = rotation(inertial.Pose().Rot());
  const ignition::math::Matrix3d& moi = inertial.MassMatrix().Moi();
  Mat3<double> i;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) i(a, b) = moi(a, b);
  body.inertia = r * i * r.transpose();
  body.has_inertia = true;
}

struct Tree {
  std::map<std::string, const sdf::Link*> links;
  std::map<std::string, std::vector<const ScopedJoint*>> children;  // by parent link ("world")
  std::map<std::string, std::string> parent_joint;                  // of each child link
  std::map<const ScopedJoint*, std::pair<std::string, std::string>> ends;  // parent, child
};

Tree make_tree(const std::vector<ScopedLink>& links, const std::vector<ScopedJoint>& joints) {
  Tree tree;
  for (const ScopedLink& l : links) tree.links[l.name] = l.link;
  for (const ScopedJoint& j : joints) {
    std::string parent, child;
    check(j.joint->ResolveParentLink(parent), "joint '" + j.name + "' parent");
    check(j.joint->ResolveChildLink(child), "joint '" + j.name + "' child");
    if (parent != "world") parent = j.scope + parent;
    child = j.scope + child;
    const auto [seen, first] = tree.parent_joint.insert({child, j.name});
    if (!first)
      throw std::invalid_argument("link '" + child + "' is the child of two joints ('" +
                                  seen->second + "' and '" + j.name +
                                  "'): a closed loop, not a tree");
    tree.children[parent].push_back(&j);
    tree.ends[&j] = {parent, child};
  }
  return tree;
}

// The bodies of joint j (parent body `lower`): one at the joint frame, named after the child
// link when the child link's frame is the joint frame (and, for a universal joint, its axes are
// the frame's x and y), else `<link>__<joint>` followed by the link on a fixed joint.
void add_joint(const ScopedJoint& j, const std::string& parent, const std::string& child,
               const Pose& world_model, int lower, const sdf::Link& link, Model& model) {
  Pose parent_joint, child_joint;  // the joint frame in the parent's and in the child's frame
  if (parent == "world") {
    check(j.joint->SemanticPose().Resolve(parent_joint, "__model__"), "joint '" + j.name + "'");
    parent_joint = world_model * j.model_pose * parent_joint;
  } else {
    check(j.joint->SemanticPose().Resolve(parent_joint, parent.substr(j.scope.size())),
          "joint '" + j.name + "'");
  }
  check(j.joint->SemanticPose().Resolve(child_joint, child.substr(j.scope.size())),
        "joint '" + j.name + "'");
  Body body;
  body.lower = lower;
  body.joint.name = j.name;
  Mat3<double> turn;
  set_type(j, body.joint, turn);
  body.joint.offset = vec3(parent_joint.Pos());
  body.joint.rotation = rotation(parent_joint.Rot()) * turn;
  const bool same_frame = child_joint == Pose::Zero && turn == Mat3<double>::Identity();
  body.name = same_frame ? child : child + "__" + j.name;
  model.bodies.push_back(body);
  if (!same_frame) {  // the link in the joint frame (turned back for a universal joint)
    const Pose link_in_joint = child_joint.Inverse();
    Body fixed;
    fixed.name = child;
    fixed.joint.name = child + "__fixed";
    fixed.lower = model.body_count();
    fixed.joint.offset = turn.transpose() * vec3(link_in_joint.Pos());
    fixed.joint.rotation = turn.transpose() * rotation(link_in_joint.Rot());
    model.bodies.push_back(fixed);
  }
  set_mass_properties(link, model.bodies.back());
}

// A link no joint moves, fixed in the world at its place in the model placed in the world.
void add_fixed_root(const ScopedLink& l, const Pose& world_model, Model& model) {
  Pose in_model;
  check(l.link->SemanticPose().Resolve(in_model, "__model__"), "link '" + l.name + "'");
  const Pose in_world = world_model * l.model_pose * in_model;
  Body body;
  body.name = l.name;
  body.joint.name = l.name + "__fixed";
  body.joint.offset = vec3(in_world.Pos());
  body.joint.rotation = rotation(in_world.Rot());
  set_mass_properties(*l.link, body);
  model.bodies.push_back(body);
}

Model build_model(const sdf::Model& top) {
  std::vector<ScopedLink> links;
  std::vector<ScopedJoint> joints;
  collect(top, "", Pose::Zero, links, joints);
  if (links.empty()) throw std::invalid_argument("model '" + top.Name() + "' has no link");
  const Tree tree = make_tree(links, joints);
  std::vector<const ScopedLink*> roots;
  for (const ScopedLink& l : links)
    if (!tree.parent_joint.count(l.name)) roots.push_back(&l);
  // One link no joint moves: R, as a URDF's root link. Else R is the world, and links no joint
  // moves are fixed in it where the model places them.
  const bool world = tree.children.count("world") > 0 || roots.size() != 1;
  Model model;
  model.frame = world ? "world" : roots.front()->name;
  model.bodies.resize(1);
  model.bodies[0].name = model.frame;
  if (!world) set_mass_properties(*roots.front()->link, model.bodies[0]);
  std::vector<std::pair<std::string, int>> queue = {{world ? "world" : model.frame, 0}};
  if (world && !roots.empty()) {
    std::string names;
    for (const ScopedLink* r : roots) {
      add_fixed_root(*r, top.RawPose(), model);
      queue.push_back({r->name, model.body_count()});
      names += (names.empty() ? "'" : ", '") + r->name + "'";
    }
    model.warnings.push_back("link" + std::string(roots.size() == 1 ? " " : "s ") + names +
                             " moved by no joint: fixed in the world where the model places "
                             "them");
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const auto it = tree.children.find(queue[head].first);
    if (it == tree.children.end()) continue;
    for (const ScopedJoint* j : it->second) {
      const auto& [parent, child] = tree.ends.at(j);
      add_joint(*j, parent, child, top.RawPose(), queue[head].second, *tree.links.at(child), model);
      queue.push_back({child, model.body_count()});
    }
  }
  if (queue.size() != links.size() + (world ? 1 : 0))
    throw std::invalid_argument(
        "the joints form a loop: " + std::to_string(links.size() + (world ? 1 : 0) - queue.size()) +
        " links are not reached from the root");
  finalize_model(model);
  return model;
}

Model read(const std::string& path_or_text, bool text, const std::string& source) {
  sdf::Console::Instance()->SetQuiet(true);  // its errors come back as sdf::Errors
  sdf::Root root;
  const sdf::Errors errors = text ? root.LoadSdfString(path_or_text) : root.Load(path_or_text);
  if (!errors.empty())
    throw std::invalid_argument(source + ": sdformat refuses the model: " + first_error(errors));
  try {
    Model model = build_model(the_model(root));
    for (std::string& warning : model.warnings) warning = source + ": " + warning;
    return model;
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(source + ": " + e.what());
  }
}

}  // namespace
}  // namespace mbk

extern "C" bool mbk_read_sdformat(const std::string& path_or_text, bool text,
                                  const std::string& source, mbk::Model& model,
                                  std::string& error) {
  try {  // messages hold names and sdformat's text: control characters escaped
    model = mbk::read(path_or_text, text, source);
    for (std::string& warning : model.warnings) warning = mbk::printable(warning);
    return true;
  } catch (const std::exception& e) {
    error = mbk::printable(e.what());
    return false;
  }
}
