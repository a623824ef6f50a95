// Shared by the tests: random trees with mixed joint types and smooth joint trajectories.
#pragma once

#include <random>
#include <string>

#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/state.h"

namespace mbk_test {

// Path of a file in the source tree, e.g. source_path("config/ten_body.yaml").
std::string source_path(const std::string& relative);

// A random tree of n bodies: lower bodies drawn so that depth and branching vary, joints of
// every type (random axes, offsets, C_k rotations), random mass centers and masses.
mbk::Model random_tree(int n, unsigned seed,
                       mbk::SpeedKind speeds = mbk::SpeedKind::kCoordinateDerivatives);

// A chain of n bodies on revolute joints about alternating axes, links of length 1 along x.
mbk::Model revolute_chain(int n);

// Smooth trajectory q_i(t) = b_i + a_i sin(w_i t + p_i) in every coordinate (Euler parameters
// stay away from zero norm), with exact first and second derivatives. Speeds are coordinate
// derivatives; for a model with angular-velocity speeds use state_at_with_speeds.
struct Trajectory {
  Trajectory(const mbk::Model& model, unsigned seed);
  template <typename S>
  mbk::JointState<S> at(double t) const;

  const mbk::Model* model;
  Eigen::VectorXd b, a, w, p;
};

// Like Trajectory::at, for models whose Euler joints use angular velocity speeds: the speeds are
// the relative angular velocity components w_k = W(e) e' and w_k' = W e'' + W' e', computed from
// the coordinate trajectory of the same model with coordinate-derivative speeds.
mbk::JointState<double> state_with_angular_speeds(const mbk::Model& quasi_model,
                                                  const mbk::Model& coordinate_model,
                                                  const Trajectory& trajectory, double t);

}  // namespace mbk_test
