#include "mb_kinematics/analysis/stability.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>

#include "mb_kinematics/analysis/model_generators.h"
#include "mb_kinematics/analysis/reference_kinematics.h"
#include "mb_kinematics/core/error_indicators.h"
#include "mb_kinematics/core/joint_motion.h"
#include "mb_kinematics/core/state_check.h"
#include "mb_kinematics/estimation/derivative_estimator.h"

namespace mbk {

TermScales term_scales(const Model& model, const JointState<double>& state) {
  const int n = model.body_count();
  TermScales t;
  for (auto& s : t.scale) s.assign(n + 1, 0.0);
  t.depth.assign(n + 1, 0);
  std::vector<double> origin(n + 1, 0.0), origin_velocity(n + 1, 0.0),
      origin_acceleration(n + 1, 0.0);
  auto& omega = t.scale[ErrorQuantity::kOmega];
  auto& alpha = t.scale[ErrorQuantity::kAlpha];
  JointMotion<double> m;
  for (int k = 1; k <= n; ++k) {
    const Body& body = model.bodies[k];
    const int j = body.lower;
    const double* y = state.velocity.data() + body.v_index;
    const double* yd = state.acceleration.data() + body.v_index;
    joint_motion(body.joint, model.speeds, state.position.data() + body.q_index, y, m);
    t.depth[k] = t.depth[j] + 1;
    const double d = body.joint.offset.norm() + m.translation.norm(), r = body.mass_center.norm();
    double sd = 0, sdd = 0, w = 0, wd = 0, rates = 0, columns = 0;
    for (int c = 0; c < m.linear_speeds; ++c) {
      sd += m.linear[c].norm() * std::abs(y[c]);
      sdd += m.linear[c].norm() * std::abs(yd[c]);
    }
    for (int c = m.linear_speeds; c < m.speeds; ++c) {
      rates += std::abs(y[c]);
      columns = std::max(columns, m.angular[c].norm());
    }
    for (int c = m.linear_speeds; c < m.speeds; ++c) {
      w += m.angular[c].norm() * std::abs(y[c]);
      // |w_k'| terms; 2 |y_c| sum|y| max|column|^2 bounds the rate products inside the column
      // derivatives (1-2-3: <= sum|y|; Euler: <= 1.5 |e'| |column|^2) before any cancellation.
      wd += m.angular[c].norm() * std::abs(yd[c]) + m.angular_dot[c].norm() * std::abs(y[c]) +
            2 * std::abs(y[c]) * rates * columns * columns;
    }
    origin[k] = origin[j] + d;
    omega[k] = omega[j] + w;
    alpha[k] = alpha[j] + wd + omega[j] * w;
    origin_velocity[k] = origin_velocity[j] + omega[j] * d + sd;
    origin_acceleration[k] =
        origin_acceleration[j] + alpha[j] * d + omega[j] * omega[j] * d + 2 * omega[j] * sd + sdd;
    t.scale[ErrorQuantity::kOrientation][k] = 1;
    t.scale[ErrorQuantity::kPosition][k] = origin[k] + r;
    t.scale[ErrorQuantity::kVelocity][k] = origin_velocity[k] + omega[k] * r;
    t.scale[ErrorQuantity::kAcceleration][k] =
        origin_acceleration[k] + alpha[k] * r + omega[k] * omega[k] * r;
  }
  return t;
}

double StabilityError::max_per_link() const {
  return *std::max_element(per_link.begin(), per_link.end());
}

template <typename R>
StabilityError stability_error(const Model& model, const JointState<double>& state, Level level) {
  using L = long double;
  Data<double> data(model);
  Data<R> reference(model);
  forward_kinematics(model, state, data, level);
  forward_kinematics(model, cast_state<R>(model, state), reference, level);
  const TermScales t = term_scales(model, state);
  StabilityError e;
  const KinematicsError relative = kinematics_error(data, reference, level);
  e.relative = relative.relative;
  for (int q = 0; q < ErrorQuantity::kCount; ++q) {
    const bool wanted = q == ErrorQuantity::kOrientation || q == ErrorQuantity::kPosition ||
                        (q == ErrorQuantity::kOmega || q == ErrorQuantity::kVelocity
                             ? level != Level::kPose
                             : level == Level::kAcceleration);
    if (!wanted) continue;
    for (int k = 1; k <= model.body_count(); ++k) {
      L err;
      if (q == ErrorQuantity::kOrientation) {
        err =
            (data.rotation[k].template cast<L>() - reference.rotation[k].template cast<L>()).norm();
      } else {
        err = (detail::quantity_vectors(data, q)[k].template cast<L>() -
               detail::quantity_vectors(reference, q)[k].template cast<L>())
                  .norm();
      }
      const double scale = t.scale[q][k];
      double s = std::isfinite(double(err)) ? double(err) : INFINITY;
      s = s == 0 ? 0 : (scale > 0 ? s / scale : INFINITY);
      e.scaled[q] = std::max(e.scaled[q], s);
      e.per_link[q] = std::max(e.per_link[q], s / t.depth[k]);
    }
  }
  return e;
}

template StabilityError stability_error<Quad>(const Model&, const JointState<double>&, Level);
template StabilityError stability_error<long double>(const Model&, const JointState<double>&,
                                                     Level);

namespace {

std::string fmt(const char* format, double x) {
  char text[64];
  std::snprintf(text, sizeof text, format, x);
  return text;
}

int worst(const std::array<double, ErrorQuantity::kCount>& a) {
  return static_cast<int>(std::max_element(a.begin(), a.end()) - a.begin());
}

// A kinematics row: the worst per-link error over the quantities against kLinkBound.
StabilityRow kinematics_row(const std::string& group, const std::string& name,
                            const StabilityError& e, const std::string& note = "") {
  const int q = worst(e.per_link);
  StabilityRow row{group,         name,       std::string("per link, worst: ") + quantity_name(q),
                   e.per_link[q], kLinkBound, ""};
  row.note =
      "rel. to max|Q|: " + fmt("%.1e", *std::max_element(e.relative.begin(), e.relative.end()));
  if (!note.empty()) row.note += "; " + note;
  return row;
}

// Applies f(value, is_angle, is_translation) to every coordinate.
void for_each_coordinate(const Model& model, JointState<double>& state,
                         const std::function<void(double&, bool, bool)>& f) {
  for (int k = 1; k <= model.body_count(); ++k) {
    const Body& body = model.bodies[k];
    for (int i = 0; i < coordinate_count(body.joint.type); ++i)
      f(state.position[body.q_index + i],
        coordinate_kind(body.joint.type, i) == CoordinateKind::kAngle,
        coordinate_kind(body.joint.type, i) == CoordinateKind::kTranslation);
  }
}

// ---------------------------------------------------------------------------- gimbal lock
// A chain of four free 1-2-3 joints at beta = +-pi/2 + delta, with large rates that cancel at
// the lock (alpha' = -gamma' = 1e3 rad/s: omega ~ (alpha' + gamma') e1 there) and angular
// accelerations of 1e6 rad/s^2. The lock is a singularity of the rate map (angles' from omega),
// not of the rotation or of omega from (angles, rates): the per-link bound holds unchanged
// (T includes |rates|, so the bound is relative to them). proper: the chain's angles are in a
// proper Euler order, whose lock is at beta = 0 and pi (euler_order.h).
JointState<double> gimbal_state(const Model& model, double delta, unsigned seed, bool proper) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  JointState<double> s = random_state(model, rng);
  for (int k = 1; k <= model.body_count(); ++k) {
    const int a = model.bodies[k].q_index + 3, v = model.bodies[k].v_index + 3;
    const double lock = proper ? (k % 2 ? 0.0 : M_PI) : (k % 2 ? M_PI_2 : -M_PI_2);
    s.position[a + 1] = lock + (k % 3 ? delta : -delta);
    const double rate = 1e3 * (1 + 0.1 * u(rng));
    s.velocity[v] = rate, s.velocity[v + 1] = 1e3 * u(rng), s.velocity[v + 2] = -rate;
    for (int c = 0; c < 3; ++c) s.acceleration[v + c] = 1e6 * u(rng);
  }
  return s;
}

std::vector<StabilityRow> gimbal_lock() {
  std::vector<StabilityRow> rows;
  const Model model = make_chain(4, JointType::kFree123);
  const Model euler = with_euler_parameters(model, SpeedKind::kCoordinateDerivatives);
  Model zxz = model;
  for (Body& body : zxz.bodies) body.joint.euler_order = EulerOrder::kZXZ;
  finalize_model(zxz);
  for (double delta : {0.0, 1e-12, 1e-9, 1e-6}) {
    const std::string name =
        delta == 0 ? "beta = +-pi/2 (double nearest)" : "beta = +-pi/2 +- " + fmt("%g", delta);
    const JointState<double> state = gimbal_state(model, delta, 11, false);
    rows.push_back(
        kinematics_row("gimbal_lock", "1-2-3 " + name, stability_error<Quad>(model, state)));
    const std::string proper_name =
        delta == 0 ? "beta = 0, pi (double nearest)" : "beta = 0, pi +- " + fmt("%g", delta);
    rows.push_back(kinematics_row("gimbal_lock", "ZXZ (proper Euler) " + proper_name,
                                  stability_error<Quad>(zxz, gimbal_state(zxz, delta, 11, true))));
    // The same motion in Euler parameters: e, e', e'' computed in quad, rounded to double (the
    // double inputs), the reference on those.
    const JointState<Quad> exact = euler_state(model, euler, cast_state<Quad>(model, state));
    JointState<double> e(euler);
    for (int i = 0; i < euler.nq; ++i) e.position[i] = double(exact.position[i]);
    for (int i = 0; i < euler.nv; ++i)
      e.velocity[i] = double(exact.velocity[i]), e.acceleration[i] = double(exact.acceleration[i]);
    rows.push_back(kinematics_row("gimbal_lock", "Euler parameters, " + name,
                                  stability_error<Quad>(euler, e)));
  }
  return rows;
}

// ---------------------------------------------------------------------- Euler parameters
std::vector<StabilityRow> euler_parameters() {
  std::vector<StabilityRow> rows;
  for (SpeedKind speeds : {SpeedKind::kCoordinateDerivatives, SpeedKind::kAngularVelocity}) {
    const std::string kind =
        speeds == SpeedKind::kAngularVelocity ? " (angular velocity speeds)" : "";
    const Model model = with_euler_parameters(make_random_tree(40, 5), speeds);
    std::mt19937 rng(5);
    const JointState<double> unit = random_state(model, rng);
    // Scaling e (and, with coordinate-derivative speeds, e' and e'') by s describes the same
    // motion: the formulas divide by |e|^2. |e|^2 = 1e-11 is just above kMinEulerNormSquared.
    for (double norm : {0.5, 2.0, 1 + 1e-9, std::sqrt(1e-11)}) {
      JointState<double> s = unit;
      for (int k = 1; k <= model.body_count(); ++k) {
        const Body& b = model.bodies[k];
        if (!uses_euler_parameters(b.joint.type)) continue;
        const int t = translation_count(b.joint.type);
        for (int i = 0; i < 4; ++i) s.position[b.q_index + t + i] *= norm;
        if (speeds == SpeedKind::kAngularVelocity) continue;
        for (int i = 0; i < 4; ++i) {
          s.velocity[b.v_index + t + i] *= norm;
          s.acceleration[b.v_index + t + i] *= norm;
        }
      }
      rows.push_back(kinematics_row("euler_parameters", "|e| = " + fmt("%.10g", norm) + kind,
                                    stability_error<Quad>(model, s)));
    }
    // Sign flip: (e, e', e'') and (-e, -e', -e'') are the same motion; the formulas are even in
    // them (products of two), and negation is exact: the results must be identical bit for bit.
    JointState<double> flipped = unit;
    for (int k = 1; k <= model.body_count(); ++k) {
      const Body& b = model.bodies[k];
      if (!uses_euler_parameters(b.joint.type)) continue;
      const int t = translation_count(b.joint.type);
      for (int i = 0; i < 4; ++i) flipped.position[b.q_index + t + i] *= -1;
      if (speeds == SpeedKind::kAngularVelocity) continue;
      for (int i = 0; i < 4; ++i)
        flipped.velocity[b.v_index + t + i] *= -1, flipped.acceleration[b.v_index + t + i] *= -1;
    }
    Data<double> a(model), b(model);
    forward_kinematics(model, unit, a);
    forward_kinematics(model, flipped, b);
    double diff = 0;
    for (int k = 1; k <= model.body_count(); ++k) {
      diff = std::max(diff, (a.rotation[k] - b.rotation[k]).cwiseAbs().maxCoeff());
      for (int q = ErrorQuantity::kOmega; q < ErrorQuantity::kCount; ++q)
        diff =
            std::max(diff, (detail::quantity_vectors(a, q)[k] - detail::quantity_vectors(b, q)[k])
                               .cwiseAbs()
                               .maxCoeff());
    }
    rows.push_back({"euler_parameters", "sign flip e -> -e" + kind, "max |difference|", diff, 0.0,
                    "negation is exact and the formulas are even in e"});
    // Near zero norm: rejected by check_state below kMinEulerNormSquared (1e-12).
    JointState<double> tiny = unit;
    for (int k = 1; k <= model.body_count(); ++k) {
      const Body& b = model.bodies[k];
      if (!uses_euler_parameters(b.joint.type)) continue;
      const int t = translation_count(b.joint.type);
      for (int i = 0; i < 4; ++i) tiny.position[b.q_index + t + i] *= std::sqrt(1e-13);
    }
    const std::string message = check_state(model, tiny);
    rows.push_back({"euler_parameters", "|e|^2 = 1e-13" + kind, "accepted (must be rejected)",
                    message.find("below 1e-12") == std::string::npos ? 1.0 : 0.0, 0.0,
                    "check_state: " + message});
  }
  return rows;
}

// --------------------------------------------------------------------- large coordinates
// Angles of 1e3, 1e6, 1e9 rad on a chain of 1-2-3 joints: glibc's sin/cos (and quad's) reduce
// the argument correctly, so against the reference on the same double input only the per-link
// rounding remains. Against the intended angle, the input's own representability ulp(x)/2
// (1e9 rad: 6e-8 rad) dominates: see the note.
std::vector<StabilityRow> large_coordinates() {
  std::vector<StabilityRow> rows;
  const Model model = make_chain(10, JointType::kBall123);
  for (double scale : {1e3, 1e6, 1e9}) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(1.0, 2.0);
    JointState<double> s = random_state(model, rng);
    for (int i = 0; i < model.nq; ++i) s.position[i] = scale * u(rng);
    const double ulp = std::nextafter(2 * scale, INFINITY) - 2 * scale;
    rows.push_back(
        kinematics_row("large_coordinates", "angles ~" + fmt("%g", scale) + " rad",
                       stability_error<Quad>(model, s),
                       "input representability ulp/2 = " + fmt("%.1e", ulp / 2) + " rad"));
  }
  // Prismatic travel of 1e6 m (every translation coordinate of a random tree).
  const Model tree = make_random_tree(60, 9);
  std::mt19937 rng(9);
  JointState<double> s = random_state(tree, rng);
  for_each_coordinate(tree, s, [](double& x, bool, bool translation) {
    if (translation) x *= 1e6 / M_PI;
  });
  rows.push_back(
      kinematics_row("large_coordinates", "translations ~1e6 m", stability_error<Quad>(tree, s)));
  return rows;
}

// -------------------------------------------------------------------------- mixed scales
std::vector<StabilityRow> mixed_scales() {
  std::vector<StabilityRow> rows;
  // Lengths from 1e-9 m to 1e6 m in one tree: every offset, mass center and translation
  // coordinate scaled by 10^u, u uniform in [-9, 6]. T_k is per body, so the bound is relative to
  // each body's own path: a small body far out is only known to ulp(its distance from R)
  // (1e6 m: 1.2e-10 m) in R coordinates, which T_k (the path length) accounts for.
  Model model = make_random_tree(80, 13);
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-9.0, 6.0);
  for (int k = 1; k <= model.body_count(); ++k) {
    model.bodies[k].joint.offset *= std::pow(10.0, u(rng));
    model.bodies[k].mass_center *= std::pow(10.0, u(rng));
  }
  finalize_model(model);
  JointState<double> s = random_state(model, rng);
  for_each_coordinate(model, s, [&](double& x, bool, bool translation) {
    if (translation) x *= std::pow(10.0, u(rng));
  });
  rows.push_back(
      kinematics_row("mixed_scales", "lengths 1e-9 .. 1e6 m", stability_error<Quad>(model, s)));
  // Masses from 1e-9 to 1e9 kg: kinematics does not use masses; results must be identical.
  Model heavy = model;
  for (int k = 1; k <= heavy.body_count(); ++k) heavy.bodies[k].mass = std::pow(10.0, k % 19 - 9);
  // (Not finalized again: finalize_model re-normalizes the axes, which can move them by an ulp.)
  Data<double> a(model), b(heavy);
  forward_kinematics(model, s, a);
  forward_kinematics(heavy, s, b);
  double diff = 0;
  for (int k = 1; k <= model.body_count(); ++k)
    for (int q = ErrorQuantity::kOmega; q < ErrorQuantity::kCount; ++q)
      diff = std::max(diff, (detail::quantity_vectors(a, q)[k] - detail::quantity_vectors(b, q)[k])
                                .cwiseAbs()
                                .maxCoeff());
  rows.push_back({"mixed_scales", "masses 1e-9 .. 1e9 kg", "max |difference|", diff, 0.0,
                  "masses do not enter the kinematics"});
  return rows;
}

// -------------------------------------------------------------------------- stiff motion
std::vector<StabilityRow> stiff_motion() {
  std::vector<StabilityRow> rows;
  {
    // A 10 m body turning at 1e-2 rad/s carries a 1 mm body spinning at 1e4 rad/s: time
    // scales 1e6 apart. Per body, per link: no loss (each body's terms are its own scale).
    Model model = make_chain(2, JointType::kBall123);
    model.bodies[1].mass_center = Vec3<double>(5, 0.3, 0);
    model.bodies[2].joint.offset = Vec3<double>(10, 0.2, 0.1);
    model.bodies[2].mass_center = Vec3<double>(1e-3, 0, 0);
    finalize_model(model);
    JointState<double> s(model);
    s.position << 0.2, 0.3, 0.1, 0.4, -0.7, 1.1;
    s.velocity << 1e-2, -0.5e-2, 0.7e-2, 1e4, 0.3, -0.2;
    s.acceleration << 1e-4, 2e-4, -1e-4, 1e2, -3, 2;
    rows.push_back(kinematics_row("stiff_motion", "1e4 rad/s spin on a 1e-2 rad/s body",
                                  stability_error<Quad>(model, s)));
  }
  {
    // Near-cancelling acceleration: body 2 turns with body 1 (rate w) plus 1e-8 w, its mass
    // center sits on body 1's axis: a_2 = -w^2 d + (w (1 + 1e-8))^2 d ~ 2e-8 w^2 d, from terms of
    // w^2 d. The error is bounded by the terms (per link), not by |a_2|: relative to |a_2| it is
    // ~ (terms / |a_2|) eps ~ 5e7 eps, the conditioning of a_2 with respect to the angle inputs.
    Model model = make_chain(2, JointType::kRevolute);
    for (int k = 1; k <= 2; ++k) model.bodies[k].joint.axis = Vec3<double>::UnitZ();
    model.bodies[1].mass_center = Vec3<double>(0.5, 0, 0);
    model.bodies[2].joint.offset = Vec3<double>(1, 0, 0);
    model.bodies[2].mass_center = Vec3<double>(1, 0, 0);
    finalize_model(model);
    JointState<double> s(model);
    s.position << 0.3, M_PI;  // G_2 on body 1's axis
    s.velocity << 100.0, 100.0 * 1e-8;
    const StabilityError e = stability_error<Quad>(model, s);
    Data<double> d(model);
    Data<Quad> r(model);
    forward_kinematics(model, s, d);
    forward_kinematics(model, cast_state<Quad>(model, s), r);
    const Vec3<Quad> a2 = r.mass_center_acceleration[2];
    const double own = double((d.mass_center_acceleration[2].cast<Quad>() - a2).norm() / a2.norm());
    const double terms = term_scales(model, s).scale[ErrorQuantity::kAcceleration][2];
    rows.push_back(kinematics_row("stiff_motion", "near-cancelling acceleration", e,
                                  "rel. to |a_2| itself: " + fmt("%.1e", own) +
                                      " (terms/|a_2| = " + fmt("%.1e", terms / double(a2.norm())) +
                                      ": the conditioning)"));
  }
  // Estimators near Nyquist: x = sin(2 pi f t) sampled at fs = 1 kHz.
  const double fs = 1000, h = 1 / fs;
  {
    // f = 0.45 fs: the backward difference is a fixed linear filter; its output is
    // (3 x_n - 4 x_{n-1} + x_{n-2}) / (2h) with h the nominal step. Against that formula in long
    // double on the same samples: rounding <= 8 eps of sum |c_i x_i| <= 8 / (2h), plus the
    // stamps' own rounding (t_n = n h: ulp(t_max) / h relative in each step, twice):
    // bound kSafety * (8 eps + 2 ulp(t_max) / h) * 4 / h.
    const double f = 0.45 * fs, w = 2 * M_PI * f;
    auto est = make_derivative_estimator("backward_difference");
    double worst = 0;
    std::vector<double> x;
    for (int n = 0; n < 200; ++n) {
      const double t = n * h;
      x.push_back(std::sin(w * t));
      est->add(t, x.back());
      double first = 0, second = 0;
      if (est->estimate(first, second) < 2) continue;
      const long double exact =
          (3.0L * x[n] - 4.0L * x[n - 1] + x[n - 2]) / (2.0L * (long double)h);
      worst = std::max(worst, double(std::abs(first - exact)));
    }
    const double t_max = 199 * h, ulp = std::nextafter(t_max, 1.0) - t_max;
    rows.push_back({"stiff_motion", "backward difference at 0.45 fs", "|x' - filter formula|",
                    worst, kSafety * (8 * kEps + 2 * ulp / h) * 4 / h,
                    "a 3-point filter: at 0.45 fs its gain is far from i w (no estimator can "
                    "do better than its filter)"});
  }
  {
    // f = 0.55 fs: the samples are exactly those of fs - f = 0.45 fs negated, up to the rounding
    // of the sines (args <= 2 pi f t ~ 700 rad: <= 2 ulp(700) + 1 ulp = 3e-13): no estimator
    // can tell the two apart, so none recovers the derivative above Nyquist.
    double worst = 0, arg = 0;
    for (int n = 0; n < 200; ++n) {
      const double t = n * h;
      arg = std::max(arg, 2 * M_PI * 0.55 * fs * t);
      worst = std::max(
          worst, std::abs(std::sin(2 * M_PI * 0.55 * fs * t) + std::sin(2 * M_PI * 0.45 * fs * t)));
    }
    rows.push_back({"stiff_motion", "samples at 0.55 fs vs 0.45 fs (aliasing)",
                    "max |x_0.55 + x_0.45|", worst, kSafety * 4 * kEps * arg,
                    "identical samples (negated): derivatives above Nyquist are not recoverable"});
  }
  return rows;
}

// ------------------------------------------------------------------------ size and shape
// Chains of 1e3, 1e4, 1e5 revolute bodies (axes alternating z, y; random angles, speeds): per
// link bound; the growth exponent of max_k |err_k| / T_k with depth, fitted on log-log, must
// be <= 1 (the worst case, linear) + 0.25. Pose and velocity: the quad reference for 1e5
// bodies at acceleration level costs too much for the suite; 1e5 uses long double (64-bit
// significand: its own error is 2^-11 of double's, checked against quad at 1e4).
std::vector<StabilityRow> size_shape() {
  std::vector<StabilityRow> rows;
  std::vector<double> depth, err;
  for (int n : {1000, 10000, 100000}) {
    const Model model = make_chain(n, JointType::kRevolute);
    std::mt19937 rng(17);
    const JointState<double> s = random_state(model, rng);
    const StabilityError e = n < 100000 ? stability_error<Quad>(model, s, Level::kVelocity)
                                        : stability_error<long double>(model, s, Level::kVelocity);
    rows.push_back(kinematics_row("size_shape", "chain of " + fmt("%g", n) + " bodies", e,
                                  n < 100000 ? "quad reference" : "long double reference"));
    depth.push_back(n);
    err.push_back(*std::max_element(e.scaled.begin(), e.scaled.end()));
    if (n == 10000) {  // long double as a reference: its own error against quad
      Data<long double> ld(model);
      Data<Quad> q(model);
      forward_kinematics(model, cast_state<long double>(model, s), ld, Level::kVelocity);
      forward_kinematics(model, cast_state<Quad>(model, s), q, Level::kVelocity);
      const double ld_err = kinematics_error(ld, q, Level::kVelocity).max();
      rows.push_back({"size_shape", "long double reference, chain of 1e4", "rel. error vs quad",
                      ld_err, kSafety * kRoundingsPerLink * n * 0x1p-64,
                      "per-link bound with long double's eps 2^-64"});
    }
  }
  double mx = 0, my = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < depth.size(); ++i) mx += std::log(depth[i]), my += std::log(err[i]);
  mx /= depth.size(), my /= depth.size();
  for (size_t i = 0; i < depth.size(); ++i) {
    const double dx = std::log(depth[i]) - mx;
    sxx += dx * dx, sxy += dx * (std::log(err[i]) - my);
  }
  char note[96];
  std::snprintf(note, sizeof note, "max_k err/T_k: %.1e, %.1e, %.1e", err[0], err[1], err[2]);
  rows.push_back({"size_shape", "chain error growth with depth", "exponent (log-log fit)",
                  sxy / sxx, 1.25, note});
  {
    // Orthonormality of S0K along a chain of 1e5: S0K = S0J SJK adds a few eps of drift per
    // joint (<= 10 eps: three rounded terms per entry, twice); the Newton-Schulz step every
    // kReorthonormalizeEvery joints (mb_kinematics/core/kinematics.h) squares it away, so the
    // drift stays below kReorthonormalizeEvery * 10 eps, times the safety factor. Without the
    // step it grows with depth (1.8e-13 at 1e4 before the fix).
    const Model model = make_chain(100000, JointType::kRevolute);
    std::mt19937 rng(17);
    Data<double> data(model);
    forward_kinematics(model, random_state(model, rng), data, Level::kPose);
    rows.push_back({"size_shape", "rotation orthonormality drift, chain of 1e5",
                    "max |S0K^T S0K - I|", orthonormality_drift(data),
                    kSafety * detail::kReorthonormalizeEvery * 10 * 0x1p-53,
                    "one Newton-Schulz step every 32 joints of depth"});
  }
  {
    // A star: body 1 (free) with 1e4 children: depth 2 everywhere, the per-link bound holds
    // whatever N.
    std::vector<int> lower(10001, 1);
    lower[0] = 0;
    Model model = make_bare_model(lower, JointType::kBall123);
    model.bodies[1].joint.type = JointType::kFree123;
    finalize_model(model);
    std::mt19937 rng(19);
    rows.push_back(kinematics_row("size_shape", "star, 1e4 children",
                                  stability_error<Quad>(model, random_state(model, rng))));
  }
  for (unsigned seed : {21u, 22u}) {
    const Model model = make_random_tree(3000, seed);
    std::mt19937 rng(seed);
    const TermScales t = term_scales(model, random_state(model, rng));
    std::mt19937 again(seed);
    rows.push_back(kinematics_row(
        "size_shape", "random deep tree, 3000 bodies (seed " + std::to_string(seed) + ")",
        stability_error<Quad>(model, random_state(model, again)),
        "depth " + std::to_string(*std::max_element(t.depth.begin(), t.depth.end()))));
  }
  return rows;
}

// ------------------------------------------------------------------------ input extremes
std::vector<StabilityRow> input_extremes() {
  std::vector<StabilityRow> rows;
  const Model model = make_random_tree(40, 23);
  std::mt19937 rng(23);
  const JointState<double> base = random_state(model, rng);
  auto non_finite = [&](const JointState<double>& s) {
    Data<double> d(model);
    forward_kinematics(model, s, d);
    int bad = 0;
    for (int k = 1; k <= model.body_count(); ++k)
      bad += !(d.rotation[k].allFinite() && d.origin[k].allFinite() &&
               d.mass_center[k].allFinite() && d.omega[k].allFinite() && d.alpha[k].allFinite() &&
               d.mass_center_velocity[k].allFinite() && d.mass_center_acceleration[k].allFinite());
    return bad;
  };
  {
    // Denormals everywhere but the Euler parameters (which check_state would reject): the
    // results underflow gracefully; they must be finite and the state accepted.
    JointState<double> s = base;
    for_each_coordinate(model, s, [](double& x, bool, bool) { x *= 1e-310; });
    for (int k = 1; k <= model.body_count(); ++k)
      if (uses_euler_parameters(model.bodies[k].joint.type))
        s.position[model.bodies[k].q_index + coordinate_count(model.bodies[k].joint.type) - 1] = 1;
    s.velocity *= 1e-310;
    s.acceleration *= 1e-310;
    const bool accepted = check_state(model, s).empty();
    rows.push_back({"input_extremes", "denormal coordinates, speeds, accelerations",
                    "bodies not finite + rejected", double(non_finite(s) + !accepted), 0.0,
                    "accepted and finite"});
  }
  {
    // Angles at the largest finite double: sin/cos are fine; accepted and finite.
    JointState<double> s = base;
    for_each_coordinate(model, s, [](double& x, bool angle, bool) {
      if (angle) x = std::copysign(std::numeric_limits<double>::max(), x);
    });
    const bool accepted = check_state(model, s).empty();
    rows.push_back({"input_extremes", "angles = +-DBL_MAX", "bodies not finite + rejected",
                    double(non_finite(s) + !accepted), 0.0, "accepted and finite"});
  }
  {
    // Translations of 1e308 m overflow in the sums (shown by the note: bodies not
    // finite without the check); check_state rejects them (limit 1e50).
    JointState<double> s = base;
    for_each_coordinate(model, s, [](double& x, bool, bool translation) {
      if (translation) x = 1e308;
    });
    const std::string message = check_state(model, s);
    rows.push_back(
        {"input_extremes", "translations = 1e308 m", "accepted (must be rejected)",
         message.find("above the limit") == std::string::npos ? 1.0 : 0.0, 0.0,
         "check_state: " + message + "; unchecked: " + fmt("%g bodies not finite", non_finite(s))});
  }
  {
    // NaN and Inf in every single slot of the state: check_state rejects each, naming it.
    int missed = 0, total = 0;
    for (double bad : {double(NAN), double(INFINITY), -double(INFINITY)}) {
      for (int part = 0; part < 3; ++part) {
        const int size = part == 0 ? model.nq : model.nv;
        for (int i = 0; i < size; ++i) {
          JointState<double> s = base;
          (part == 0 ? s.position : part == 1 ? s.velocity : s.acceleration)[i] = bad;
          const std::string message = check_state(model, s);
          const std::string& name = part == 0 ? model.coordinate_names[i] : model.speed_names[i];
          missed += message.find("not finite") == std::string::npos ||
                    message.find(name) == std::string::npos;
          ++total;
        }
      }
    }
    rows.push_back({"input_extremes",
                    "NaN, +Inf, -Inf in each of " + std::to_string(total / 3) + " slots",
                    "not rejected by name", double(missed), 0.0, ""});
  }
  {
    // Euler parameters of norm 1e200: |e|^2 overflows (the rotation would be Inf/Inf = NaN).
    JointState<double> s = base;
    for (int k = 1; k <= model.body_count(); ++k) {
      const Body& b = model.bodies[k];
      if (!uses_euler_parameters(b.joint.type)) continue;
      for (int i = 0; i < 4; ++i)
        s.position[b.q_index + coordinate_count(b.joint.type) - 4 + i] *= 1e200;
    }
    const std::string message = check_state(model, s);
    rows.push_back(
        {"input_extremes", "Euler parameters of norm 1e200", "accepted (must be rejected)",
         message.find("above the limit") == std::string::npos ? 1.0 : 0.0, 0.0,
         "check_state: " + message + "; unchecked: " + fmt("%g bodies not finite", non_finite(s))});
  }
  return rows;
}

// ------------------------------------------------------------------------ estimator time
// Every estimator of derivative_estimator_names().
std::vector<StabilityRow> estimator_time() {
  std::vector<StabilityRow> rows;
  const auto& names = derivative_estimator_names();
  auto quadratic = [](double t, int order) {
    return order == 0 ? 1 + 2 * t + 3 * t * t : order == 1 ? 2 + 6 * t : 6.0;
  };
  {
    // Duplicate stamps: a repeated stamp replaces the sample (derivative_estimator.h), so
    // feeding (t, wrong) then (t, right) must give exactly what feeding (t, right) gives.
    int differ = 0;
    std::string which;
    for (const std::string& name : names) {
      auto a = make_derivative_estimator(name), b = make_derivative_estimator(name);
      for (int n = 0; n < 40; ++n) {
        const double t = 1e-3 * n;
        if (n % 7 == 3) a->add(t, 5.0);  // a wrong value at the same stamp first
        a->add(t, quadratic(t, 0));
        b->add(t, quadratic(t, 0));
        double fa = 0, sa = 0, fb = 0, sb = 0;
        if (a->estimate(fa, sa) != b->estimate(fb, sb) || fa != fb || sa != sb) {
          ++differ;
          if (which.find(name) == std::string::npos) which += (which.empty() ? "" : ", ") + name;
        }
      }
    }
    rows.push_back({"estimator_time", "duplicate stamps", "estimates that differ", double(differ),
                    0.0, which.empty() ? "all replace the sample" : "differ: " + which});
  }
  {
    // Backwards stamps: add returns false, the history is reset (no estimate until enough
    // new samples), and nothing is non-finite.
    int wrong = 0;
    for (const std::string& name : names) {
      auto e = make_derivative_estimator(name);
      for (int n = 0; n < 40; ++n) e->add(1e-3 * n, quadratic(1e-3 * n, 0));
      double f = 0, s = 0;
      wrong += e->add(0.01, quadratic(0.01, 0)) != false;
      wrong += e->estimate(f, s) != 0;
    }
    rows.push_back(
        {"estimator_time", "stamps going backwards", "not reset", double(wrong), 0.0, ""});
  }
  // Jitter (+-20% at 1 kHz) and gaps (3 s every 0.1 s) on x = 1 + 2t + 3t^2, t in [0, 4] s.
  // Every polynomial fit of order >= 2 reproduces a quadratic exactly on any stamps: only
  // rounding remains. For the 3-point estimators (exact interpolation, coefficients |c_i| <=
  // 2/h_min for x', <= 2/h_min^2 for x''), rounding is <= 8 eps sum|c_i x_i| plus the stamp
  // differences' own rounding (ulp(t)/h_min relative): bound kSafety * 8 eps (3 X * 2/h_min^k
  // + |x^(k)| t_max/h_min). The wider fits and the Kalman filter: finite (reported).
  for (int gaps = 0; gaps < 2; ++gaps) {
    std::mt19937 rng(29);
    std::uniform_real_distribution<double> u(-0.2, 0.2);
    std::vector<double> stamps;
    double t = 0;
    while (t < 4) {
      stamps.push_back(t);
      t += 1e-3 * (1 + u(rng));
      if (gaps && stamps.size() % 100 == 0) t += 3.0;
    }
    const double t_max = stamps.back(), h_min = 0.8e-3, X = quadratic(t_max, 0);
    int not_finite = 0;
    double worst3 = 0;
    std::string others;
    for (const std::string& name : names) {
      auto e = make_derivative_estimator(name);
      double worst_other = 0;
      for (size_t n = 0; n < stamps.size(); ++n) {
        e->add(stamps[n], quadratic(stamps[n], 0));
        double f = 0, s = 0;
        const int valid = e->estimate(f, s);
        if (valid < 2) continue;
        not_finite += !std::isfinite(f) || !std::isfinite(s);
        const double te = stamps[n - e->latency()];
        const double bf = kSafety * 8 * kEps * (3 * X * 2 / h_min + 6 * t_max / h_min * t_max),
                     bs = kSafety * 8 * kEps * (3 * X * 2 / (h_min * h_min) + 6 * t_max / h_min);
        const double r =
            std::max(std::abs(f - quadratic(te, 1)) / bf, std::abs(s - quadratic(te, 2)) / bs);
        if (name == "backward_difference" || name == "central_difference")
          worst3 = std::max(worst3, r);
        else
          worst_other = std::max(worst_other, std::abs(s - 6.0) / 6.0);
      }
      if (name != "backward_difference" && name != "central_difference")
        others += (others.empty() ? "" : ", ") + name + " " + fmt("%.0e", worst_other);
    }
    const std::string what = gaps ? "gaps of 3 s" : "jitter +-20% at 1 kHz";
    rows.push_back({"estimator_time", what + ": 3-point estimators on a quadratic",
                    "error / derived bound", worst3, 1.0, ""});
    rows.push_back({"estimator_time", what + ": all estimators", "non-finite estimates",
                    double(not_finite), 0.0, "x'' rel. error: " + others});
  }
  return rows;
}

}  // namespace

const std::vector<std::string>& stability_groups() {
  static const std::vector<std::string> groups = {
      "gimbal_lock",  "euler_parameters", "large_coordinates", "mixed_scales",
      "stiff_motion", "size_shape",       "input_extremes",    "estimator_time"};
  return groups;
}

std::vector<StabilityRow> stability_cases(const std::string& group) {
  if (group == "gimbal_lock") return gimbal_lock();
  if (group == "euler_parameters") return euler_parameters();
  if (group == "large_coordinates") return large_coordinates();
  if (group == "mixed_scales") return mixed_scales();
  if (group == "stiff_motion") return stiff_motion();
  if (group == "size_shape") return size_shape();
  if (group == "input_extremes") return input_extremes();
  if (group == "estimator_time") return estimator_time();
  return {};
}

std::string format_stability_table(const std::vector<StabilityRow>& rows) {
  std::string out = "| case | quantity | measured | bound | note |\n|---|---|---|---|---|\n";
  for (const StabilityRow& r : rows)
    out += "| " + r.name + " | " + r.quantity + " | " + fmt("%.2g", r.measured) + " | " +
           fmt("%.2g", r.bound) + " | " + r.note + " |\n";
  return out;
}

}  // namespace mbk
