// Workspace of the per-update algorithms, sized once by the model (no allocation per update).
// Index k = 1..N is body Bk; index 0 is the inertial frame R (identity and zeros).
// Every vector is in R components.
#pragma once

#include <vector>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/types.h"

namespace mbk {

// How much of the kinematics an update computes.
enum class Level { kPose, kVelocity, kAcceleration };

template <typename S>
struct Data {
  std::vector<Mat3<S>> rotation;                  // S0K
  std::vector<Vec3<S>> origin;                    // O_k
  std::vector<Vec3<S>> mass_center;               // p_k: position of G_k
  std::vector<Vec3<S>> omega;                     // angular velocity omega_k
  std::vector<Vec3<S>> alpha;                     // angular acceleration alpha_k
  std::vector<Vec3<S>> mass_center_velocity;      // v_k: velocity of G_k
  std::vector<Vec3<S>> mass_center_acceleration;  // a_k: acceleration of G_k
  std::vector<Vec3<S>> origin_velocity;           // velocity of O_k
  std::vector<Vec3<S>> origin_acceleration;       // acceleration of O_k
  // forward_kinematics' workspace: the angles of BodySteps::angles, their sines and cosines.
  std::vector<S> angle, sine, cosine;

  explicit Data(const Model& model) {
    const size_t n = model.bodies.size();
    rotation.assign(n, Mat3<S>::Identity());
    for (auto* v : {&origin, &mass_center, &omega, &alpha, &mass_center_velocity,
                    &mass_center_acceleration, &origin_velocity, &origin_acceleration})
      v->assign(n, Vec3<S>::Zero());
    for (auto* v : {&angle, &sine, &cosine}) v->assign(model.steps.angles.size(), S(0));
  }
};

// Whether `data` was made for `model` (Data(model)): every algorithm asserts it at entry, so a
// Data of another model stops a debug build there instead of writing out of bounds. O(1): the
// constructor sizes every member alike. Release builds (NDEBUG) skip the assert.
template <typename S>
bool sized_for(const Data<S>& data, const Model& model) {
  return data.rotation.size() == model.bodies.size() &&
         data.mass_center_acceleration.size() == model.bodies.size() &&
         data.sine.size() == model.steps.angles.size();
}

}  // namespace mbk
