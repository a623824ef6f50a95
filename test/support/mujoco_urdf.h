// A URDF as MuJoCo 2.2.2 reads the same model, for the MuJoCo peer test and benchmark: MuJoCo's
// compiler options in the robot element (every link a body: fusestatic off; visuals dropped;
// massless links bounded to 1e-6 kg, as MuJoCo refuses moving bodies without mass; inertias that
// break the triangle inequality balanced, as MuJoCo refuses them: the kinematics reads no
// inertia), and every link without <inertial> given URDF's default one explicitly (origin at
// the link frame, no mass). The latter because MuJoCo's compiler, for a body with neither an
// inertial nor a geom, copies the body's pos and quat (its frame in its parent's) into its
// inertial frame (ipos, iquat, in the body's own frame): such a link's mass center would sit at
// its joint origin's offset from the link frame instead of at the link frame. MuJoCo's URDF
// import drops <mimic>: impose_mimics gives MuJoCo's state our mimic coordinates.
#pragma once

#include <mujoco/mujoco.h>

#include <cstring>
#include <memory>
#include <string>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

namespace mbk_test {

// `urdf` with each <link> that has no <inertial> given <inertial> at its frame with zero mass.
inline std::string with_explicit_inertials(const std::string& urdf) {
  static const std::string kInertial =
      "<inertial><origin xyz=\"0 0 0\" rpy=\"0 0 0\"/><mass value=\"0\"/><inertia ixx=\"0\" "
      "ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"/></inertial>";
  std::string out;
  std::size_t from = 0;
  for (std::size_t at = urdf.find("<link", from); at != std::string::npos;
       at = urdf.find("<link", from)) {
    const char next = urdf[at + 5];
    const std::size_t tag_end = urdf.find('>', at);
    if ((next != ' ' && next != '\t' && next != '\n') || tag_end == std::string::npos) {
      out += urdf.substr(from, at + 5 - from);
      from = at + 5;
      continue;
    }
    if (urdf[tag_end - 1] == '/') {  // <link name="x"/>
      out += urdf.substr(from, tag_end - 1 - from) + ">" + kInertial + "</link>";
      from = tag_end + 1;
      continue;
    }
    const std::size_t close = urdf.find("</link>", tag_end);
    const std::size_t inertial = urdf.find("<inertial", tag_end);
    out += urdf.substr(from, tag_end + 1 - from);
    if (close != std::string::npos && (inertial == std::string::npos || inertial > close))
      out += kInertial;
    from = tag_end + 1;
  }
  return out + urdf.substr(from);
}

// The URDF text MuJoCo is given (see the top of this file).
inline std::string urdf_for_mujoco(const std::string& urdf) {
  const std::string text = with_explicit_inertials(urdf);
  const std::size_t robot = text.find("<robot");
  const std::size_t end = text.find('>', robot);
  return text.substr(0, end + 1) +
         "<mujoco><compiler fusestatic=\"false\" discardvisual=\"true\" balanceinertia=\"true\" "
         "boundmass=\"1e-6\" "
         "boundinertia=\"1e-9\"/></mujoco>" +
         text.substr(end + 1);
}

// MuJoCo's model of a URDF text (urdf_for_mujoco applied), or null with MuJoCo's message in
// `error`.
inline mjModel* load_urdf_in_mujoco(const std::string& urdf, std::string* error) {
  const std::string text = urdf_for_mujoco(urdf);
  const auto vfs = std::make_unique<mjVFS>();  // megabytes: not on the stack
  mj_defaultVFS(vfs.get());
  mj_makeEmptyFileVFS(vfs.get(), "model.urdf", static_cast<int>(text.size()));
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), "model.urdf")], text.data(), text.size());
  char message[1000] = "";
  mjModel* m = mj_loadXML("model.urdf", vfs.get(), message, sizeof message);
  mj_deleteVFS(vfs.get());
  if (!m && error) *error = message;
  return m;
}

// MuJoCo's qpos, qvel and qacc of each joint that is a mimic coordinate of ours set to ours.
inline void impose_mimics(const mjModel* m, mjData* d, const mbk::Model& model,
                          const mbk::JointState<double>& state) {
  for (const mbk::Mimic& x : model.mimics) {
    const std::string& name = model.coordinate_names[x.coordinate];
    const int j = mj_name2id(m, mjOBJ_JOINT, name.c_str());
    if (j < 0) continue;
    d->qpos[m->jnt_qposadr[j]] = state.position[x.coordinate];
    d->qvel[m->jnt_dofadr[j]] = state.velocity[x.coordinate];
    d->qacc[m->jnt_dofadr[j]] = state.acceleration[x.coordinate];
  }
}

}  // namespace mbk_test
