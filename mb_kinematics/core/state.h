// Joint state (q, q', q'') sized by a model; the generalized speeds are the model's.
#pragma once

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/types.h"

namespace mbk {

template <typename S>
struct JointState {
  VecX<S> position;      // q: model.nq coordinates
  VecX<S> velocity;      // y: model.nv generalized speeds
  VecX<S> acceleration;  // y': model.nv

  explicit JointState(const Model& model)
      : position(VecX<S>::Zero(model.nq)),
        velocity(VecX<S>::Zero(model.nv)),
        acceleration(VecX<S>::Zero(model.nv)) {
    for (int k = 1; k <= model.body_count(); ++k) {
      const Body& body = model.bodies[k];
      if (uses_euler_parameters(body.joint.type))  // identity: e4 = 1
        position[body.q_index + first_euler_parameter(body.joint.type) + 3] = S(1);
    }
  }
};

// The same state in scalar S (exact when S is at least as wide as T): for a reference build of
// the same code in long double or quad precision, on exactly the inputs a double run got.
template <typename S, typename T>
JointState<S> cast_state(const Model& model, const JointState<T>& state) {
  JointState<S> out(model);
  out.position = state.position.template cast<S>();
  out.velocity = state.velocity.template cast<S>();
  out.acceleration = state.acceleration.template cast<S>();
  return out;
}

// Fills mimic coordinates from their sources (q = multiplier * q_source + offset; the
// derivatives scale by multiplier).
template <typename S>
void apply_mimic(const Mimic& m, JointState<S>& state) {
  state.position[m.coordinate] = S(m.multiplier) * state.position[m.source] + S(m.offset);
  state.velocity[m.coordinate] = S(m.multiplier) * state.velocity[m.source];
  state.acceleration[m.coordinate] = S(m.multiplier) * state.acceleration[m.source];
}

template <typename S>
void apply_mimics(const Model& model, JointState<S>& state) {
  for (const Mimic& m : model.mimics) apply_mimic(m, state);
}

}  // namespace mbk
