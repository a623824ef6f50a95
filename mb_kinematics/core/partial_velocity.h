// Absolute kinematics through the partial velocity arrays omega_krm, v_krm and their time
// derivatives (doc/method.md 5, eq. 4.4.20-4.4.32, 4.7.7-4.7.12, 4.8). Stored sparse: body k keeps
// only the columns of the speeds of its own joint and its ancestors' joints.
#pragma once

#include <algorithm>
#include <cassert>
#include <vector>

#include "mb_kinematics/core/data.h"
#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/core/kinematics.h"
#include "mb_kinematics/core/model.h"
#include "mb_kinematics/core/own_column.h"
#include "mb_kinematics/core/state.h"

namespace mbk {

// Body k's columns are begin[k] .. begin[k] + count[k] - 1 in the flat arrays below: first its
// lower body's columns (same order), then its own joint's. speed[i] is the generalized speed
// index r of flat column i. All vectors in R components.
// Streamed (made with kStreamed): a body's columns live in a slot of the largest body's size only
// from its computation until its last child's, and partial_velocity_kinematics hands each body
// to a callback as it is done: memory for the bodies alive at once (2 on a chain, about a
// breadth-first level of a tree) instead of sum_k count[k], N x depth / 2 on a chain.
struct Streamed {};
constexpr Streamed kStreamed{};

template <typename S>
struct PartialVelocities {
  std::vector<int> begin, count, speed;
  std::vector<Vec3<S>> omega;                // omega_kr
  std::vector<Vec3<S>> origin_velocity;      // partial velocity of O_k
  std::vector<Vec3<S>> velocity;             // v_kr, of the mass center G_k
  std::vector<Vec3<S>> omega_dot;            // d/dt omega_kr
  std::vector<Vec3<S>> origin_velocity_dot;  // d/dt of the O_k partial velocity
  std::vector<Vec3<S>> velocity_dot;         // d/dt v_kr

  explicit PartialVelocities(const Model& model) {
    const int n = model.body_count();
    begin.assign(n + 1, 0);
    count.assign(n + 1, 0);
    int total = 0;
    for (int k = 1; k <= n; ++k) {
      const Body& body = model.bodies[k];
      begin[k] = total;
      count[k] = count[body.lower] + speed_count(body.joint.type, model.speeds);
      for (int i = 0; i < count[body.lower]; ++i) speed.push_back(speed[begin[body.lower] + i]);
      for (int i = count[body.lower]; i < count[k]; ++i)
        speed.push_back(body.v_index + i - count[body.lower]);
      total += count[k];
    }
    resize(total);
  }

  PartialVelocities(const Model& model, Streamed) : streamed(true) {
    const int n = model.body_count();
    begin.assign(n + 1, 0);
    count.assign(n + 1, 0);
    last_child.assign(n + 1, 0);
    for (int k = 1; k <= n; ++k) {
      const Body& body = model.bodies[k];
      count[k] = count[body.lower] + speed_count(body.joint.type, model.speeds);
      slot_size = std::max(slot_size, count[k]);
      last_child[body.lower] = k;
    }
    int alive = 0, slots = 0;  // as open() and close() will go
    for (int k = 1; k <= n; ++k) {
      slots = std::max(slots, ++alive);
      alive -= (last_child[k] == 0) +
               (model.bodies[k].lower > 0 && last_child[model.bodies[k].lower] == k);
    }
    for (int slot = slots - 1; slot >= 0; --slot) free_slots.push_back(slot);
    speed.assign(static_cast<std::size_t>(slots) * slot_size, 0);
    resize(speed.size());
  }

  // Streamed: body k's slot, its lower body's speeds then its own joint's.
  void open(const Model& model, int k) {
    const Body& body = model.bodies[k];
    begin[k] = free_slots.back() * slot_size;
    free_slots.pop_back();
    const int j = body.lower, nj = count[j];
    for (int i = 0; i < nj; ++i) speed[begin[k] + i] = speed[begin[j] + i];
    for (int i = nj; i < count[k]; ++i) speed[begin[k] + i] = body.v_index + i - nj;
  }
  // Streamed: body k is done; its slot and its lower body's go when no child needs them.
  void close(const Model& model, int k) {
    const int j = model.bodies[k].lower;
    if (last_child[k] == 0) free_slots.push_back(begin[k] / slot_size);
    if (j > 0 && last_child[j] == k) free_slots.push_back(begin[j] / slot_size);
  }
  // The entries the arrays hold (six 3-vectors and a speed index each).
  std::size_t entries() const { return speed.size(); }

  bool streamed = false;
  std::vector<int> last_child;  // streamed: per body, its last child (0: none)
  std::vector<int> free_slots;
  int slot_size = 0;

 private:
  void resize(std::size_t total) {
    for (auto* v :
         {&omega, &origin_velocity, &velocity, &omega_dot, &origin_velocity_dot, &velocity_dot})
      v->assign(total, Vec3<S>::Zero());
  }
};

struct NoCallback {
  void operator()(int) const {}
};

// What partial_velocity_kinematics sums into Data beyond the poses and the columns: every
// velocity and acceleration (kAll), or omega_k alone (kOmega: the columns' users, e.g.
// core/body_errors.h, need no other sum; data's other velocities and accelerations are left as
// they were). The columns and omega_k are the same bits either way.
enum class DataSums { kAll, kOmega };

// Same outputs as forward_kinematics, through the partial velocity arrays: omega_k = sum_r
// omega_kr y_r, v_k = sum_r v_kr y_r, alpha_k = sum_r (omega_kr y_r' + omega_kr' y_r),
// a_k = sum_r (v_kr y_r' + v_kr' y_r). No allocation. At Level::kAcceleration, done(k) is called
// as each body k is complete (its columns and data's entries); a streamed pv needs it there.
template <typename S, typename Done = NoCallback>
void partial_velocity_kinematics(const Model& model, const JointState<S>& state,
                                 PartialVelocities<S>& pv, Data<S>& data,
                                 Level level = Level::kAcceleration, Done done = {},
                                 DataSums sums = DataSums::kAll) {
  assert(sized_for(data, model) && pv.begin.size() == model.bodies.size() &&
         "partial_velocity_kinematics: Data or PartialVelocities made for another model");
  assert((!pv.streamed || level == Level::kAcceleration) &&
         "partial_velocity_kinematics: a streamed PartialVelocities needs every level");
  JointMotion<S> m;
  const bool velocities = level != Level::kPose;
  const bool accelerations = level == Level::kAcceleration;
  const S* y = state.velocity.data();
  const S* yd = state.acceleration.data();
  detail::angle_sines(model, state.position.data(), data);  // for pose_step
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    const int j = body.lower;
    if (velocities || detail::uses_joint_motion<S>(model.steps.steps[k].kernel))  // else unused
      joint_motion(body.joint, model.speeds, state.position.data() + body.q_index,
                   velocities ? y + body.v_index : nullptr, m);
    if (pv.streamed) pv.open(model, k);
    Vec3<S> d = Vec3<S>::Zero(), rho;  // d: set by pose_step (zero for GCC's warning)
    detail::BallFrame<S> f;
    detail::pose_step(model, k, state.position.data(), m, data, d, rho, f);
    if (!velocities) continue;

    const Mat3<S>& s0j = data.rotation[j];
    const Vec3<S>& omega_j = data.omega[j];
    const int bj = pv.begin[j], nj = pv.count[j], bk = pv.begin[k], nk = pv.count[k];
    Vec3<S> sd = Vec3<S>::Zero();  // s_k' in Bj
    for (int c = 0; c < m.linear_speeds; ++c) sd += m.linear[c] * y[body.v_index + c];
    const Vec3<S> d_dot = omega_j.cross(d) + s0j * sd;
    for (int i = 0; i < nj; ++i) {  // ancestors' columns (eq. 4.4.25-4.4.32)
      pv.omega[bk + i] = pv.omega[bj + i];
      pv.origin_velocity[bk + i] = pv.origin_velocity[bj + i] + pv.omega[bj + i].cross(d);
      if (!accelerations) continue;
      pv.omega_dot[bk + i] = pv.omega_dot[bj + i];
      pv.origin_velocity_dot[bk + i] = pv.origin_velocity_dot[bj + i] +
                                       pv.omega_dot[bj + i].cross(d) +
                                       pv.omega[bj + i].cross(d_dot);
    }
    const BodyStep& step = model.steps.steps[k];
    const bool ball = is_ball_or_free(step.kernel);
    const S* e = state.position.data() + body.q_index + m.linear_speeds;  // Euler parameters
    for (int c = 0; c < m.speeds; ++c) {  // the joint's own columns (own_column.h)
      const int i = bk + nj + c;
      // In R as the recursion sums them (ball and free joints: through M = S0J C_k).
      const Vec3<S> column =
          ball ? detail::ball_column(step, model.speeds, f, e, c) : joint_column(m, c, s0j);
      const OwnColumn<S> own = own_column(m, c, column, s0j, omega_j);
      pv.omega[i] = own.omega;
      pv.origin_velocity[i] = own.origin_velocity;
      if (!accelerations) continue;
      pv.omega_dot[i] = own.omega_dot;
      pv.origin_velocity_dot[i] = own.origin_velocity_dot;
    }
    const bool all = sums == DataSums::kAll;  // else omega_k alone
    Vec3<S> omega = Vec3<S>::Zero(), v = Vec3<S>::Zero(), vo = Vec3<S>::Zero();
    for (int i = bk; i < bk + nk; ++i) {
      pv.velocity[i] = pv.origin_velocity[i] + pv.omega[i].cross(rho);
      const S yr = y[pv.speed[i]];
      omega += pv.omega[i] * yr;
      if (!all) continue;
      v += pv.velocity[i] * yr;
      vo += pv.origin_velocity[i] * yr;
    }
    data.omega[k] = omega;
    if (all) data.mass_center_velocity[k] = v, data.origin_velocity[k] = vo;
    if (!accelerations) continue;

    Vec3<S> alpha = Vec3<S>::Zero(), a = Vec3<S>::Zero(), ao = Vec3<S>::Zero();
    for (int i = bk; i < bk + nk; ++i) {
      pv.velocity_dot[i] = pv.origin_velocity_dot[i] + pv.omega_dot[i].cross(rho) +
                           pv.omega[i].cross(omega.cross(rho));
      if (!all) continue;
      const S yr = y[pv.speed[i]], ydr = yd[pv.speed[i]];
      alpha += pv.omega[i] * ydr + pv.omega_dot[i] * yr;
      a += pv.velocity[i] * ydr + pv.velocity_dot[i] * yr;
      ao += pv.origin_velocity[i] * ydr + pv.origin_velocity_dot[i] * yr;
    }
    if (all) {
      data.alpha[k] = alpha;
      data.mass_center_acceleration[k] = a;
      data.origin_acceleration[k] = ao;
    }
    done(k);
    if (pv.streamed) pv.close(model, k);
  }
}

}  // namespace mbk
