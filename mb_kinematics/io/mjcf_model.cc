#include "mb_kinematics/io/mjcf_model.h"

#include <algorithm>
#include <cstring>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "mb_kinematics/core/printable.h"
#include "mb_kinematics/io/mujoco_library.h"
#include "mb_kinematics/io/text_file.h"

#if __has_include(<mujoco/mujoco.h>)
#include <mujoco/mujoco.h>
#define MBK_HAVE_MUJOCO_HEADERS 1
#endif

namespace mbk {

bool is_mjcf_text(const std::string& xml) { return xml_root_is(xml, "mujoco"); }

#ifdef MBK_HAVE_MUJOCO_HEADERS
namespace {

struct ModelDeleter {
  void operator()(mjModel* m) const { mujoco_library().delete_model(m); }
};
using MjModel = std::unique_ptr<mjModel, ModelDeleter>;

std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

// MuJoCo's compiler stops at the first mesh file it cannot open ("could not open STL file
// 'x.stl'"): say that the kinematics does not need it, and how to go on.
std::string refusal(const std::string& source, const std::string& error) {
  std::string line = source + ": MuJoCo refuses the model: " + one_line(error);
  if (error.find("could not open") != std::string::npos &&
      error.find(" file '") != std::string::npos)
    line +=
        " (a mesh file is missing: kinematics does not need meshes; put them where the "
        "model's meshdir says, or remove the <mesh> assets and the geoms using them and keep "
        "each body's <inertial>)";
  return line;
}

// mj_loadXML of a file, or of `text` through MuJoCo's virtual file system. MuJoCo's parser keeps
// global state: one at a time.
MjModel compile(const std::string& path, const std::string* text, const std::string& source) {
  const MujocoLibrary& mj = mujoco_library();
  static std::mutex parser;
  std::lock_guard<std::mutex> lock(parser);
  char error[1000] = "";
  mjModel* model = nullptr;
  if (text) {
    if (text->empty()) throw std::invalid_argument(source + ": empty MJCF text");
    const auto vfs = std::make_unique<mjVFS>();
    mj.default_vfs(vfs.get());
    const char* name = "mbk_model.xml";
    if (mj.make_empty_file_vfs(vfs.get(), name, static_cast<int>(text->size())) != 0)
      throw std::invalid_argument(source + ": MuJoCo cannot hold the MJCF text");
    std::memcpy(vfs->filedata[mj.find_file_vfs(vfs.get(), name)], text->data(), text->size());
    model = mj.load_xml(name, vfs.get(), error, sizeof error);
    mj.delete_vfs(vfs.get());
  } else {
    model = mj.load_xml(path.c_str(), nullptr, error, sizeof error);
  }
  if (!model) throw std::invalid_argument(refusal(source, error));
  return MjModel(model);
}

Vec3<double> vec3(const mjtNum* v) { return Vec3<double>(v[0], v[1], v[2]); }

Mat3<double> quaternion_rotation(const mjtNum* q) {  // MuJoCo's order: w, x, y, z
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

std::string name_or(const mjModel& m, int address, const std::string& fallback) {
  const char* name = m.names + address;
  return *name ? std::string(name) : fallback;
}

std::string body_name(const mjModel& m, int b) {
  return name_or(m, m.name_bodyadr[b], "body" + std::to_string(b));
}

std::string joint_name(const mjModel& m, int j) {
  return name_or(m, m.name_jntadr[j], "joint" + std::to_string(j));
}

// What lies between the last joint placed and the next one: a translation (in the axes of the
// last body placed) and a rotation. Before a body's first joint, the body's pos and quat.
struct Between {
  Vec3<double> offset = Vec3<double>::Zero();
  Mat3<double> rotation = Mat3<double>::Identity();
  bool empty() const { return offset.isZero(0) && rotation == Mat3<double>::Identity(); }
};

// MuJoCo's joint j as one of ours placed at its anchor, after `between`, which becomes what
// lies between this joint's body and the next (mj_kinematics: a hinge or ball turns the body
// about its anchor jnt_pos; hinge and slide move by q - qpos0, so qpos0 goes into C_k or q_k).
void place_joint(const mjModel& m, int j, Between& between, Joint& joint) {
  const Vec3<double> anchor = vec3(m.jnt_pos + 3 * j), axis = vec3(m.jnt_axis + 3 * j);
  const double ref = m.qpos0[m.jnt_qposadr[j]];
  joint.offset = between.offset + between.rotation * anchor;
  joint.rotation = between.rotation;
  switch (m.jnt_type[j]) {
    case mjJNT_HINGE:
      joint.type = JointType::kRevolute;
      joint.axis = axis;
      joint.rotation = between.rotation * Eigen::AngleAxisd(-ref, axis.normalized()).matrix();
      between = {-anchor, Mat3<double>::Identity()};
      return;
    case mjJNT_BALL:
      joint.type = JointType::kBallEuler;
      between = {-anchor, Mat3<double>::Identity()};
      return;
    case mjJNT_SLIDE:
      joint.type = JointType::kPrismatic;
      joint.axis = axis;
      joint.offset = between.offset - ref * (between.rotation * axis);
      between = {};
      return;
    case mjJNT_FREE:  // qpos is the body's position and orientation in the world
      joint.type = JointType::kFreeEuler;
      joint.offset.setZero();
      joint.rotation.setIdentity();
      between = {};
      return;
  }
  throw std::invalid_argument("joint '" + joint_name(m, j) + "' has an unknown MuJoCo type " +
                              std::to_string(m.jnt_type[j]));
}

// m_k, r_k and I_k (body_inertia: principal moments in the inertial frame body_iquat).
void set_mass_properties(const mjModel& m, int b, Body& body) {
  body.mass = m.body_mass[b];
  body.mass_center = vec3(m.body_ipos + 3 * b);
  const Mat3<double> r = quaternion_rotation(m.body_iquat + 4 * b);
  body.inertia = r * vec3(m.body_inertia + 3 * b).asDiagonal() * r.transpose();
  body.has_inertia = true;
}

// MJCF body b as our bodies: one per joint, then the body itself unless its last joint's body
// already has its frame. Returns the body that stands for b. joint_body[j]: the body of joint j.
int add_bodies(const mjModel& m, int b, int lower, Model& model, std::vector<int>& joint_body) {
  const std::string name = body_name(m, b);
  Between between{vec3(m.body_pos + 3 * b), quaternion_rotation(m.body_quat + 4 * b)};
  const int joints = m.body_jntnum[b];
  for (int i = 0; i < joints; ++i) {
    const int j = m.body_jntadr[b] + i;
    if (m.jnt_type[j] == mjJNT_FREE && (joints != 1 || m.body_parentid[b] != 0))
      throw std::invalid_argument("body '" + name +
                                  "': a free joint with other joints or below "
                                  "another body does not map");
    Body body;
    body.lower = lower;
    body.joint.name = joint_name(m, j);
    place_joint(m, j, between, body.joint);
    body.name = i + 1 == joints && between.empty() ? name : name + "__" + body.joint.name;
    model.bodies.push_back(body);
    lower = joint_body[j] = model.body_count();
  }
  if (joints == 0 || !between.empty()) {  // welded to the last: a fixed joint named as the body
    Body body;
    body.name = body.joint.name = name;
    body.lower = lower;
    body.joint.offset = between.offset;
    body.joint.rotation = between.rotation;
    model.bodies.push_back(body);
  }
  set_mass_properties(m, b, model.bodies.back());
  return model.body_count();
}

const char* equality_kind(int type) {
  switch (type) {
    case mjEQ_CONNECT:
      return "connect";
    case mjEQ_WELD:
      return "weld";
    case mjEQ_JOINT:
      return "joint";
    case mjEQ_TENDON:
      return "tendon";
    case mjEQ_DISTANCE:
      return "distance";
  }
  return "unknown";
}

// An active joint equality q1 - qpos0_1 = c0 + c1 (q2 - qpos0_2) between two one-coordinate
// joints is a mimic of q2; one line names every other active constraint, which the open tree
// leaves out.
void add_mimics(const mjModel& m, const std::vector<int>& joint_body, const std::string& source,
                Model& model) {
  std::string left_out;
  for (int e = 0; e < m.neq; ++e) {
    if (!m.eq_active[e]) continue;
    const mjtNum* c = m.eq_data + mjNEQDATA * e;
    const int j1 = m.eq_obj1id[e], j2 = m.eq_obj2id[e];
    const auto scalar = [&](int j) {
      return j >= 0 && (m.jnt_type[j] == mjJNT_HINGE || m.jnt_type[j] == mjJNT_SLIDE);
    };
    if (m.eq_type[e] == mjEQ_JOINT && scalar(j1) && scalar(j2) && c[2] == 0 && c[3] == 0 &&
        c[4] == 0) {
      const double ref1 = m.qpos0[m.jnt_qposadr[j1]], ref2 = m.qpos0[m.jnt_qposadr[j2]];
      model.mimics.push_back({model.bodies[joint_body[j1]].q_index,
                              model.bodies[joint_body[j2]].q_index, c[1],
                              ref1 + c[0] - c[1] * ref2});
      continue;
    }
    left_out += (left_out.empty() ? "" : ", ") + std::string(equality_kind(m.eq_type[e])) + " '" +
                name_or(m, m.name_eqadr[e], "#" + std::to_string(e)) + "'";
  }
  if (!left_out.empty())
    model.warnings.push_back(source +
                             ": equality constraints left out (the kinematics is the open "
                             "tree's; only a linear coupling of two joints is kept, as a "
                             "mimic): " +
                             left_out);
}

Model build_model(const mjModel& m, const std::string& source) {
  Model model;
  model.frame = body_name(m, 0);
  model.bodies.resize(1);
  model.bodies[0].name = model.frame;
  std::vector<int> ours(m.nbody, 0), joint_body(m.njnt, 0);  // MuJoCo's ids to our bodies
  for (int b = 1; b < m.nbody; ++b)
    ours[b] = add_bodies(m, b, ours[m.body_parentid[b]], model, joint_body);
  finalize_model(model);
  add_mimics(m, joint_body, source, model);
  finalize_model(model);  // validates the mimics
  return model;
}

Model load(const std::string& path, const std::string* text, const std::string& source) {
  try {
    const MjModel m = compile(path, text, source);
    try {
      Model model = build_model(*m, source);
      for (std::string& warning : model.warnings) warning = printable(warning);
      return model;
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(source + ": " + e.what());
    }
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(printable(e.what()));
  }
}

}  // namespace

Model load_mjcf_file(const std::string& path) {
  read_text_file(path, "MJCF file");  // the project's message for a file that cannot be read
  return load(path, nullptr, path);
}

Model load_mjcf_string(const std::string& xml, const std::string& source) {
  return load("", &xml, source);
}

#else

Model load_mjcf_file(const std::string&) {
  mujoco_library();
  return {};
}
Model load_mjcf_string(const std::string&, const std::string&) {
  mujoco_library();
  return {};
}

#endif

}  // namespace mbk
