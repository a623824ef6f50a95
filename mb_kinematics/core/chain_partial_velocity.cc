#include "mb_kinematics/core/chain_partial_velocity.h"

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/core/kinematics.h"
#include "mb_kinematics/core/own_column.h"

namespace mbk {
namespace {

using V = Vec3<double>;

// One column of a body's own joint, at that body b (own_column.h), and its speed's index.
struct ChainColumn : OwnColumn<double> {
  int speed;
};

// A body of the chains: S0K, O_k, omega_k, the velocity of O_k (doc/method.md 4), and its own
// columns own[first .. first + count - 1].
struct ChainBody {
  int body, lower;  // lower: the position of L(k) among the chain bodies, -1 for R
  Mat3<double> rotation;
  V origin, omega, origin_velocity;
  int first, count;
};

// The bodies on the chains of `bodies`, ascending (so L(k) comes before k).
std::vector<int> chain_union(const Model& model, const std::vector<int>& bodies) {
  std::unordered_set<int> seen;
  std::vector<int> chain;
  for (int k : bodies)
    for (int u = k; u > 0 && seen.insert(u).second; u = model.bodies[u].lower) chain.push_back(u);
  std::sort(chain.begin(), chain.end());
  return chain;
}

int position(const std::vector<int>& chain, int k) {
  return k == 0 ? -1
                : static_cast<int>(std::lower_bound(chain.begin(), chain.end(), k) - chain.begin());
}

// Body k from its lower body (doc/method.md 4, 5): pose, omega_k, the velocity of O_k, and its
// own joint's columns appended to `own`.
ChainBody chain_body(const Model& model, const JointState<double>& state, int k,
                     const ChainBody* lower, std::vector<ChainColumn>& own) {
  const Body& body = model.bodies[k];
  const BodyStep& b = model.steps.steps[k];
  JointMotion<double> m;
  joint_motion(body.joint, model.speeds, state.position.data() + body.q_index,
               state.velocity.data() + body.v_index, m);
  const Mat3<double> s0j = lower ? lower->rotation : Mat3<double>::Identity();
  const V zero = V::Zero();
  const V& omega_j = lower ? lower->omega : zero;
  ChainBody c{k, -1, s0j * m.rotation, zero, omega_j, zero, static_cast<int>(own.size()), m.speeds};
  if (b.reorthonormalize) detail::reorthonormalize(c.rotation);  // as forward_kinematics
  const V d = s0j * (b.offset + m.translation);                  // eq. 4.6.2
  c.origin = (lower ? lower->origin : zero) + d;
  c.origin_velocity = (lower ? lower->origin_velocity : zero) + omega_j.cross(d);
  for (int i = 0; i < m.speeds; ++i) {
    const ChainColumn o{own_column(m, i, joint_column(m, i, s0j), s0j, omega_j), body.v_index + i};
    const double y = state.velocity[body.v_index + i];
    if (i < m.linear_speeds)
      c.origin_velocity += o.origin_velocity * y;
    else
      c.omega += o.omega * y;  // eq. 4.4.6
    own.push_back(o);
  }
  return c;
}

// The column of independent speed r in `columns`, appended if new. Without mimics every speed
// comes once: no lookup.
SpeedColumn& column_of(int r, std::vector<SpeedColumn>& columns,
                       std::unordered_map<int, size_t>& folded, bool mimics) {
  const auto at = mimics ? folded.emplace(r, columns.size()) : std::make_pair(folded.end(), true);
  if (at.second) columns.push_back({r, V::Zero(), V::Zero(), V::Zero(), V::Zero()});
  return at.second ? columns.back() : columns[at.first->second];
}

// Body k's columns from its chain's own columns, from R outward. A column r of the joint of
// body b on the chain is constant outward in omega (omega_kr = omega_br), and the recursion
// vO_kr = vO_jr + omega_jr x d_k sums to vO_kr = vO_br + omega_br x (O_k - O_b); its derivative
// to vO_br' + omega_br' x (O_k - O_b) + omega_br x (vO_k - vO_b) (doc/method.md 5).
std::vector<SpeedColumn> body_columns(const Model& model, const std::vector<ChainBody>& chain,
                                      const std::vector<ChainColumn>& own, int p) {
  const ChainBody& k = chain[p];
  const V rho = k.rotation * model.bodies[k.body].mass_center;  // S0K r_k
  const V omega_rho = k.omega.cross(rho);
  std::vector<int> path;
  for (int u = p; u >= 0; u = chain[u].lower) path.push_back(u);
  size_t count = 0;
  for (int u : path) count += chain[u].count;
  std::vector<SpeedColumn> columns;
  columns.reserve(count);
  std::unordered_map<int, size_t> folded;  // independent speed -> its column (mimics only)
  for (auto u = path.rbegin(); u != path.rend(); ++u) {
    const ChainBody& b = chain[*u];
    const V dp = k.origin - b.origin, dv = k.origin_velocity - b.origin_velocity;
    for (int i = b.first; i < b.first + b.count; ++i) {
      const ChainColumn& o = own[i];
      const V vo = o.origin_velocity + o.omega.cross(dp);
      const V vo_dot = o.origin_velocity_dot + o.omega_dot.cross(dp) + o.omega.cross(dv);
      double f = 1.0;
      const int r = model.mimics.empty() ? o.speed : independent_speed(model, o.speed, f);
      SpeedColumn& c = column_of(r, columns, folded, !model.mimics.empty());
      c.omega += f * o.omega;
      c.velocity += f * (vo + o.omega.cross(rho));  // v_kr = vO_kr + omega_kr x rho_k
      c.omega_dot += f * o.omega_dot;
      c.velocity_dot += f * (vo_dot + o.omega_dot.cross(rho) + o.omega.cross(omega_rho));
    }
  }
  return columns;
}

}  // namespace

std::vector<long> chain_speed_counts(const Model& model) {
  std::vector<long> count(model.bodies.size(), 0);
  for (int k = 1; k <= model.body_count(); ++k)
    count[k] = count[model.bodies[k].lower] + speed_count(model.bodies[k].joint.type, model.speeds);
  return count;
}

std::vector<std::vector<SpeedColumn>> chain_partial_velocities(const Model& model,
                                                               const JointState<double>& state,
                                                               const std::vector<int>& bodies) {
  const std::vector<int> union_bodies = chain_union(model, bodies);
  std::vector<ChainBody> chain;
  std::vector<ChainColumn> own;
  chain.reserve(union_bodies.size());
  size_t speeds = 0;
  for (int k : union_bodies) speeds += speed_count(model.bodies[k].joint.type, model.speeds);
  own.reserve(speeds);
  for (int k : union_bodies) {
    const int lower = position(union_bodies, model.bodies[k].lower);
    chain.push_back(chain_body(model, state, k, lower < 0 ? nullptr : &chain[lower], own));
    chain.back().lower = lower;
  }
  std::vector<std::vector<SpeedColumn>> out;
  out.reserve(bodies.size());
  for (int k : bodies) out.push_back(body_columns(model, chain, own, position(union_bodies, k)));
  return out;
}

}  // namespace mbk
