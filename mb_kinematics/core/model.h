// The model: lower body array, joints, mass centers and masses (doc/method.md 8). Plain data, built
// by the loaders (or by hand) and made consistent by finalize_model; the algorithms take it
// const. Whoever changes a field afterwards (the node sets `speeds` once, at load) must call
// finalize_model again before using it.
#pragma once

#include <string>
#include <vector>

#include "mb_kinematics/core/body_step.h"
#include "mb_kinematics/core/joint.h"
#include "mb_kinematics/core/types.h"

namespace mbk {

struct Body {
  std::string name;
  int lower = 0;                                    // L(k); 0 = the inertial frame R
  Joint joint;                                      // connection to the lower body
  Vec3<double> mass_center = Vec3<double>::Zero();  // r_k: O_k -> G_k, components in Bk
  double mass = 0.0;
  Mat3<double> inertia = Mat3<double>::Zero();  // I_k: about G_k, in Bk's axes, if has_inertia
  bool has_inertia = false;                     // the scene or URDF gave I_k
  int q_index = 0;  // first coordinate of the joint in the state's position vector
  int v_index = 0;  // first generalized speed of the joint
  int depth = 0;    // number of joints from R to Bk (set by finalize_model)
};

// A coordinate that follows another: q[coordinate] = multiplier * q[source] + offset (URDF mimic).
struct Mimic {
  int coordinate = 0;
  int source = 0;
  double multiplier = 1.0;
  double offset = 0.0;
};

struct Model {
  std::string frame = "R";  // name of the inertial frame R
  SpeedKind speeds = SpeedKind::kCoordinateDerivatives;
  std::vector<Body> bodies;  // bodies[k] is Bk for k = 1..N; bodies[0] stands for R
  std::vector<Mimic> mimics;
  int nq = 0;                                 // number of coordinates
  int nv = 0;                                 // number of generalized speeds
  std::vector<std::string> coordinate_names;  // nq names (doc/method.md 8)
  std::vector<std::string> speed_names;       // nv names; equal to coordinate_names unless
                                              // Euler joints use angular velocity speeds
  BodySteps steps;  // what each update does per body (body_step.h), set by finalize_model
  std::vector<std::string> warnings;  // what the loader let through but reports, one line each

  int body_count() const { return static_cast<int>(bodies.size()) - 1; }
  std::vector<int> lower_body_array() const;            // L(1..N)
  int body_index(const std::string& name) const;        // -1 if absent
  int coordinate_index(const std::string& name) const;  // -1 if absent
  int speed_index(const std::string& name) const;       // -1 if absent
};

// The steps of a model whose bodies, joints and indices are final (finalize_model calls it;
// body_step.cc).
BodySteps make_body_steps(const Model& model, KernelChoice choice = KernelChoice::kFast);

// Validates a model whose bodies[1..N] (name, lower, joint, mass_center, mass) and mimics are
// filled in, normalizes joint axes and assigns coordinate/speed indices and names. Throws
// std::invalid_argument with a one-line message naming the body and the field at fault.
// bodies[0] is (re)set to stand for R.
void finalize_model(Model& model);

// A model of the bare lower body array: every body on a joint of the given type, unit
// offsets along x from its lower body, mass centers half way, unit masses.
Model make_bare_model(const std::vector<int>& lower, JointType type);

}  // namespace mbk
