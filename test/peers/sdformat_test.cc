// Peer check against libsdformat12's own frame resolution: an SDFormat model loaded by
// io/sdf_model.h places every link where sdformat's semantic pose API places it, at the zero
// state and moved. Each link's pose is composed here from sdformat's resolved poses (the joint
// frame relative to the parent link, the child link relative to the joint frame, nested models
// relative to their parent model, the model in the world) and the joint motions as SDFormat
// defines them (revolute: about the axis resolved in the joint frame; prismatic: along it;
// ball: the rotation of the Euler parameters; universal: about axis, then about axis2, both in
// the joint frame), with ignition math, and compared with our origins and rotations to 1e-12
// (metres, and rotation matrix entries), on sdformat's own test models (test/robots/sdf/) and on
// test/io/data/sdf_features.sdf.
#include <gtest/gtest.h>

#include <ignition/math/Pose3.hh>
#include <map>
#include <random>
#include <sdf/Joint.hh>
#include <sdf/JointAxis.hh>
#include <sdf/Link.hh>
#include <sdf/Model.hh>
#include <sdf/Root.hh>
#include <string>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/kinematics_double.h"
#include "mb_kinematics/core/state.h"
#include "mb_kinematics/io/sdf_model.h"
#include "test/support/test_models.h"

namespace {

using Pose = ignition::math::Pose3d;
using Quaternion = ignition::math::Quaterniond;
using Vector = ignition::math::Vector3d;

constexpr double kTolerance = 1e-12;

struct Link {
  const sdf::Link* link;
  Pose model_pose;  // its model's frame in the top model's
};
struct JointEnds {
  const sdf::Joint* joint;
  std::string scope, parent, child;  // scoped link names; parent "world" for the world
  Pose model_pose;
};

void collect(const sdf::Model& model, const std::string& scope, const Pose& model_pose,
             std::map<std::string, Link>& links, std::map<std::string, JointEnds>& joints) {
  for (uint64_t i = 0; i < model.LinkCount(); ++i)
    links[scope + model.LinkByIndex(i)->Name()] = {model.LinkByIndex(i), model_pose};
  for (uint64_t i = 0; i < model.JointCount(); ++i) {
    const sdf::Joint* j = model.JointByIndex(i);
    std::string parent, child;
    EXPECT_TRUE(j->ResolveParentLink(parent).empty());
    EXPECT_TRUE(j->ResolveChildLink(child).empty());
    joints[scope + j->Name()] = {j, scope, parent == "world" ? parent : scope + parent,
                                 scope + child, model_pose};
  }
  for (uint64_t i = 0; i < model.ModelCount(); ++i) {
    const sdf::Model& nested = *model.ModelByIndex(i);
    Pose pose;
    EXPECT_TRUE(nested.SemanticPose().Resolve(pose).empty());
    collect(nested, scope + nested.Name() + "::", model_pose * pose, links, joints);
  }
}

Pose resolve(const sdf::SemanticPose& pose, const std::string& frame) {
  Pose out;
  const sdf::Errors errors = pose.Resolve(out, frame);
  EXPECT_TRUE(errors.empty()) << (errors.empty() ? "" : errors.front().Message());
  return out;
}

Vector axis(const JointEnds& j, unsigned index) {
  Vector xyz;
  EXPECT_TRUE(j.joint->Axis(index)->ResolveXyz(xyz).empty());
  return xyz.Normalized();
}

// The joint's motion in its frame, from our coordinates of it (by name).
Pose motion(const JointEnds& j, const std::string& name, const mbk::Model& model,
            const mbk::JointState<double>& s) {
  const auto q = [&](const std::string& suffix) {
    const int i = model.coordinate_index(suffix.empty() ? name : name + "/" + suffix);
    EXPECT_GE(i, 0) << name << " " << suffix;
    return i < 0 ? 0.0 : s.position[i];
  };
  switch (j.joint->Type()) {
    case sdf::JointType::REVOLUTE:
    case sdf::JointType::CONTINUOUS:
      return Pose(Vector::Zero, Quaternion(axis(j, 0), q("")));
    case sdf::JointType::PRISMATIC:
      return Pose(axis(j, 0) * q(""), Quaternion::Identity);
    case sdf::JointType::BALL:
      return Pose(Vector::Zero, Quaternion(q("e4"), q("e1"), q("e2"), q("e3")));
    case sdf::JointType::UNIVERSAL:
      return Pose(Vector::Zero,
                  Quaternion(axis(j, 0), q("alpha")) * Quaternion(axis(j, 1), q("beta")));
    default:
      return Pose::Zero;
  }
}

// Every link's pose in the top model's frame, composed along the joints from the world and from
// the links no joint moves (at their place in the model).
std::map<std::string, Pose> link_poses(const std::map<std::string, Link>& links,
                                       const std::map<std::string, JointEnds>& joints,
                                       const mbk::Model& model, const mbk::JointState<double>& s) {
  std::map<std::string, Pose> pose;
  for (const auto& [name, l] : links) {
    bool moved = false;
    for (const auto& [jn, j] : joints) moved = moved || j.child == name;
    if (!moved) pose[name] = l.model_pose * resolve(l.link->SemanticPose(), "__model__");
  }
  for (std::size_t round = 0; round < joints.size(); ++round) {
    for (const auto& [name, j] : joints) {
      if (pose.count(j.child)) continue;
      Pose parent_joint;
      if (j.parent == "world") {
        parent_joint = j.model_pose * resolve(j.joint->SemanticPose(), "__model__");
      } else if (pose.count(j.parent)) {
        parent_joint =
            pose[j.parent] * resolve(j.joint->SemanticPose(), j.parent.substr(j.scope.size()));
      } else {
        continue;
      }
      const Pose joint_child =
          resolve(j.joint->SemanticPose(), j.child.substr(j.scope.size())).Inverse();
      pose[j.child] = parent_joint * motion(j, name, model, s) * joint_child;  // X_OP * X_PQ
    }
  }
  return pose;
}

void expect_links_where_sdformat_puts_them(const std::string& path, int samples) {
  SCOPED_TRACE(path);
  sdf::Root root;
  const sdf::Errors errors = root.Load(path);
  ASSERT_TRUE(errors.empty()) << errors.front().Message();
  const sdf::Model& top = *root.Model();
  std::map<std::string, Link> links;
  std::map<std::string, JointEnds> joints;
  collect(top, "", Pose::Zero, links, joints);
  const mbk::Model model = mbk::load_sdf_file(path);
  mbk::Data<double> data(model);
  std::mt19937 rng(3);
  for (int n = 0; n < samples; ++n) {
    mbk::JointState<double> s =
        n == 0 ? mbk::JointState<double>(model) : mbk::random_state(model, rng);
    mbk::forward_kinematics(model, s, data, mbk::Level::kPose);
    const std::map<std::string, Pose> pose = link_poses(links, joints, model, s);
    // Our R: the world (the model placed by its pose) or the one link no joint moves.
    const Pose r = model.frame == "world" ? top.RawPose().Inverse() : pose.at(model.frame);
    for (const auto& [name, p] : pose) {
      const int k = model.body_index(name);
      if (name == model.frame) continue;
      ASSERT_GT(k, 0) << name;
      const Pose in_r = r.Inverse() * p;
      const Vector& o = in_r.Pos();
      EXPECT_LE((data.origin[k] - mbk::Vec3<double>(o.X(), o.Y(), o.Z())).cwiseAbs().maxCoeff(),
                kTolerance)
          << name << " sample " << n;
      const Quaternion& q = in_r.Rot();
      const mbk::Mat3<double> rotation =
          Eigen::Quaterniond(q.W(), q.X(), q.Y(), q.Z()).toRotationMatrix();
      EXPECT_LE((data.rotation[k] - rotation).cwiseAbs().maxCoeff(), kTolerance)
          << name << " sample " << n;
    }
    EXPECT_EQ(pose.size(), links.size());
  }
}

TEST(SdformatPeer, LinksAreWhereSdformatPutsThem) {
  for (const char* file :
       {"test/robots/sdf/double_pendulum.sdf", "test/robots/sdf/joint_parent_world.sdf",
        "test/robots/sdf/joint_child_frame.sdf",
        "test/robots/sdf/model_joint_axis_expressed_in.sdf", "test/io/data/sdf_features.sdf"})
    expect_links_where_sdformat_puts_them(mbk_test::source_path(file), 20);
}

}  // namespace
