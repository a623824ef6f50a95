// Each body's kinematics in its own axes, and its motion relative to its lower body (the
// segment frames and joint motion of biomechanics; doc/method.md 10). Data holds every vector in
// R components; these read them in Bk's axes (n_k1, n_k2, n_k3) and in Bj's, j = L(k). The one
// place they are computed: the Python batch, `mbk eval` and `mbk bag --csv` call these.
// ROS-free (Eigen only).
#pragma once

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/model.h"

namespace mbk {

// x (R components) in Bk's axes: S0K^T x.
template <typename S>
Vec3<S> in_body_axes(const Data<S>& data, int k, const Vec3<S>& x) {
  return detail::transpose_product<S>(data.rotation[k], x);
}

// Bk relative to Bj = L(k) (R for a body on R: then these are Bk's absolute rotation, omega and
// alpha in R): SJK = S0J^T S0K; the relative angular velocity omega_k - omega_j in Bj's axes; and
// its rate as Bj sees it, alpha_k - alpha_j - omega_j x (omega_k - omega_j), in Bj's axes, which
// is the time derivative of the components of `omega` (doc/method.md 10).
template <typename S>
struct RelativeMotion {
  Mat3<S> rotation;
  Vec3<S> omega;
  Vec3<S> alpha;
};

// Its parts, each alone (the batch writes a field at a time). S0J^T is made a matrix before the
// products: Eigen sums a b and a^T b in different orders (types.h), and these are the numbers
// `mbk eval` has always written.
template <typename S>
Mat3<S> relative_rotation(const Model& model, const Data<S>& data, int k) {
  const Mat3<S> sj_t = data.rotation[model.bodies[k].lower].transpose();
  return detail::product<S>(sj_t, data.rotation[k]);
}

template <typename S>
Vec3<S> relative_omega(const Model& model, const Data<S>& data, int k) {
  const int j = model.bodies[k].lower;
  const Mat3<S> sj_t = data.rotation[j].transpose();
  return detail::product<S>(sj_t, Vec3<S>(data.omega[k] - data.omega[j]));
}

template <typename S>
Vec3<S> relative_alpha(const Model& model, const Data<S>& data, int k) {
  const int j = model.bodies[k].lower;
  const Mat3<S> sj_t = data.rotation[j].transpose();
  const Vec3<S> w = data.omega[k] - data.omega[j];
  return detail::product<S>(sj_t, Vec3<S>(data.alpha[k] - data.alpha[j] - data.omega[j].cross(w)));
}

template <typename S>
RelativeMotion<S> relative_motion(const Model& model, const Data<S>& data, int k) {
  return {relative_rotation(model, data, k), relative_omega(model, data, k),
          relative_alpha(model, data, k)};
}

}  // namespace mbk
