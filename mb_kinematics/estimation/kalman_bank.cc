#include "mb_kinematics/estimation/kalman_bank.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <stdexcept>

// The vector helpers below are always inlined (V4 into the AVX2 copy alone): no vector crosses a
// call, so GCC's note on the ABI of 32-byte vectors without AVX does not apply.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace mbk {
namespace {

// One filter's state and covariance (upper triangle); T: double, or a vector of filters.
template <typename T>
struct Filter {
  T s0, s1, s2, p00, p01, p02, p11, p12, p22;
};

// s <- F s, P <- F P F^T + q Q over dt, with F = [1 dt h; 0 1 dt; 0 0 1] (constant
// acceleration, h = dt^2 / 2) and Q the white jerk's discretized covariance; then the update by
// the position x of noise variance r: gain K = P e1 / (P00 + r), s += K (x - s0),
// P -= K P.row(0). F P F^T multiplied out on the upper triangle of the symmetric P: a third of
// the products of the 3x3 form (the node runs one filter per coordinate and sample;
// doc/speed.md "The node's load").
template <typename T>
__attribute__((always_inline)) inline void predict_update(Filter<T>& f, const T& dt, const T& x,
                                                          double q, double r) {
  const T d2 = dt * dt, h = d2 / 2.0, d3 = d2 * dt;
  f.s0 += dt * f.s1 + h * f.s2;
  f.s1 += dt * f.s2;
  // Rows of A = F P: a0j = p0j + dt p1j + h p2j, a1j = p1j + dt p2j (j >= row), a2j = p2j.
  const T a00 = f.p00 + dt * f.p01 + h * f.p02;
  const T a01 = f.p01 + dt * f.p11 + h * f.p12;
  const T a02 = f.p02 + dt * f.p12 + h * f.p22;
  const T a11 = f.p11 + dt * f.p12, a12 = f.p12 + dt * f.p22;
  // (A F^T)ij = ai0 + dt ai1 + h ai2, ai1 + dt ai2, ai2 for j = 0, 1, 2.
  f.p00 = a00 + dt * a01 + h * a02 + q * (d3 * d2 / 20.0);
  f.p01 = a01 + dt * a02 + q * (d2 * d2 / 8.0);
  f.p02 = a02 + q * (d3 / 6.0);
  f.p11 = a11 + dt * a12 + q * (d3 / 3.0);
  f.p12 = a12 + q * (d2 / 2.0);
  f.p22 += q * dt;
  const T innovation = x - f.s0, variance = f.p00 + r;
  const T r0 = f.p00, r1 = f.p01, r2 = f.p02;  // row 0 of P
  const T g0 = r0 / variance, g1 = r1 / variance, g2 = r2 / variance;
  f.s0 += g0 * innovation;
  f.s1 += g1 * innovation;
  f.s2 += g2 * innovation;
  f.p00 = f.p00 - g0 * r0;
  f.p01 = f.p01 - g0 * r1;
  f.p02 = f.p02 - g0 * r2;
  f.p11 = f.p11 - g1 * r1;
  f.p12 = f.p12 - g1 * r2;
  f.p22 = f.p22 - g2 * r2;
}

// The arrays of KalmanBank's Lanes.
struct LanePointers {
  double *t, *s0, *s1, *s2, *p00, *p01, *p02, *p11, *p12, *p22;
};

// The arrays of KalmanBank's Lanes `l`.
template <typename Lanes>
LanePointers lane_pointers(Lanes& l) {
  return {l.t.data(),   l.s0.data(),  l.s1.data(),  l.s2.data(),  l.p00.data(),
          l.p01.data(), l.p02.data(), l.p11.data(), l.p12.data(), l.p22.data()};
}

// Filter i of the lanes (its stamp apart), and back with its stamp t.
Filter<double> filter_at(const LanePointers& l, int i) {
  return {l.s0[i], l.s1[i], l.s2[i], l.p00[i], l.p01[i], l.p02[i], l.p11[i], l.p12[i], l.p22[i]};
}

void set_filter(const LanePointers& l, int i, double t, const Filter<double>& f) {
  l.t[i] = t, l.s0[i] = f.s0, l.s1[i] = f.s1, l.s2[i] = f.s2;
  l.p00[i] = f.p00, l.p01[i] = f.p01, l.p02[i] = f.p02;
  l.p11[i] = f.p11, l.p12[i] = f.p12, l.p22[i] = f.p22;
}

// Two or four filters (GCC vector extensions): SSE2 (or NEON), AVX2.
typedef double V2 __attribute__((vector_size(16)));
typedef double V4 __attribute__((vector_size(32)));

template <typename T>
__attribute__((always_inline)) inline T load(const double* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

template <typename T>
__attribute__((always_inline)) inline void store(double* p, const T& v) {
  std::memcpy(p, &v, sizeof v);
}

template <typename V>
__attribute__((always_inline)) inline V splat(double x) {
  double lanes[sizeof(V) / sizeof(double)];
  std::fill(std::begin(lanes), std::end(lanes), x);
  return load<V>(lanes);
}

// Every lane of a comparison's mask set.
template <typename M>
__attribute__((always_inline)) inline bool every_lane(const M& m) {
  long lanes[sizeof(M) / sizeof(long)];
  std::memcpy(lanes, &m, sizeof lanes);
  bool every = true;
  for (const long lane : lanes) every = every && lane != 0;
  return every;
}

// predict_update at t with x[i] on each filter i with step[i] != 0, its state before kept in
// `before`: the filters of a vector V at a time, each operation once on all (those not to
// update discarded by a blend), the last ones one by one.
template <typename V>
__attribute__((always_inline)) inline void step_all(double t, const double* x, const double* step,
                                                    double q, double r, int n,
                                                    const LanePointers& now,
                                                    const LanePointers& before) {
  constexpr int kWidth = sizeof(V) / sizeof(double);
  int i = 0;
  for (; i + kWidth <= n; i += kWidth) {
    const auto m = load<V>(step + i) != 0.0;
    const V t_old = load<V>(now.t + i);
    const Filter<V> old{load<V>(now.s0 + i),  load<V>(now.s1 + i),  load<V>(now.s2 + i),
                        load<V>(now.p00 + i), load<V>(now.p01 + i), load<V>(now.p02 + i),
                        load<V>(now.p11 + i), load<V>(now.p12 + i), load<V>(now.p22 + i)};
    Filter<V> f = old;
    const V dt = t - t_old, xi = load<V>(x + i);
    predict_update<V>(f, dt, xi, q, r);
    const auto write = [&](const auto& keep) {
      keep(before.t, t_old);
      keep(before.s0, old.s0), keep(before.s1, old.s1), keep(before.s2, old.s2);
      keep(before.p00, old.p00), keep(before.p01, old.p01), keep(before.p02, old.p02);
      keep(before.p11, old.p11), keep(before.p12, old.p12), keep(before.p22, old.p22);
      keep(now.t, splat<V>(t));
      keep(now.s0, f.s0), keep(now.s1, f.s1), keep(now.s2, f.s2);
      keep(now.p00, f.p00), keep(now.p01, f.p01), keep(now.p02, f.p02);
      keep(now.p11, f.p11), keep(now.p12, f.p12), keep(now.p22, f.p22);
    };
    if (every_lane(m))  // the common case: stored as they are, nothing to blend
      write([&](double* p, const V& v) { store(p + i, v); });
    else
      write([&](double* p, const V& v) { store(p + i, m ? v : load<V>(p + i)); });
  }
  for (; i < n; ++i) {
    if (step[i] == 0) continue;
    Filter<double> f = filter_at(now, i);
    set_filter(before, i, now.t[i], f);
    predict_update<double>(f, t - now.t[i], x[i], q, r);
    set_filter(now, i, t, f);
  }
}

void step_all_portable(double t, const double* x, const double* step, double q, double r, int n,
                       const LanePointers& now, const LanePointers& before) {
  step_all<V2>(t, x, step, q, r, n, now, before);
}

#if defined(__x86_64__)
// Each operation on 256 bits; no fused multiply-add, so bit for bit the SSE2 results.
__attribute__((target("avx2"))) void step_all_avx2(double t, const double* x, const double* step,
                                                   double q, double r, int n,
                                                   const LanePointers& now,
                                                   const LanePointers& before) {
  step_all<V4>(t, x, step, q, r, n, now, before);
}
#endif

// Marks in `step` (1 or 0) the filters step_all updates: used, with samples before (count > 0),
// a finite t after their latest stamp, a finite x; counts their sample. Returns whether some used
// filter is not among them. A loop without branches, of ints (|x| <= DBL_MAX: x finite), which
// the compiler vectorizes.
__attribute__((always_inline)) inline int mark_plain(double t, const double* x, const char* use,
                                                     int n, const double* last, int* count,
                                                     double* step) {
  const int finite_t = std::isfinite(t);
  int others = 0;
  for (int i = 0; i < n; ++i) {
    const int used = use[i] != 0;
    const int plain = used & finite_t & (count[i] > 0) & (t > last[i]) &
                      (std::abs(x[i]) <= std::numeric_limits<double>::max());
    step[i] = plain;
    count[i] += plain;
    others |= used & !plain;
  }
  return others;
}

// Some used filter with 3 samples or more (estimates) has its first estimate (and with
// `both` its second) beyond `bound` or NaN: likewise a loop without branches.
__attribute__((always_inline)) inline int beyond(const char* use, const int* count,
                                                 const double* s1, const double* s2, int n,
                                                 int both, double bound) {
  int outside = 0;
  for (int i = 0; i < n; ++i) {
    const int estimated = (use[i] != 0) & (count[i] >= 3);
    const int first = std::abs(s1[i]) <= bound;  // NaN: false
    const int second = !both | (std::abs(s2[i]) <= bound);
    outside |= estimated & !(first & second);
  }
  return outside;
}

#if defined(__x86_64__)
// The same loops on 256-bit vectors.
__attribute__((target("avx2"))) int mark_plain_avx2(double t, const double* x, const char* use,
                                                    int n, const double* last, int* count,
                                                    double* step) {
  return mark_plain(t, x, use, n, last, count, step);
}

__attribute__((target("avx2"))) int beyond_avx2(const char* use, const int* count, const double* s1,
                                                const double* s2, int n, int both, double bound) {
  return beyond(use, count, s1, s2, n, both, bound);
}

bool has_avx2() {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
}
#endif

// mark_plain and beyond, on 256-bit vectors where the CPU has them.
int mark_plain_on_cpu(double t, const double* x, const char* use, int n, const double* last,
                      int* count, double* step) {
#if defined(__x86_64__)
  if (has_avx2()) return mark_plain_avx2(t, x, use, n, last, count, step);
#endif
  return mark_plain(t, x, use, n, last, count, step);
}

int beyond_on_cpu(const char* use, const int* count, const double* s1, const double* s2, int n,
                  int both, double bound) {
#if defined(__x86_64__)
  if (has_avx2()) return beyond_avx2(use, count, s1, s2, n, both, bound);
#endif
  return beyond(use, count, s1, s2, n, both, bound);
}

}  // namespace

KalmanBank::Lanes::Lanes(int n)
    : t(n), s0(n), s1(n), s2(n), p00(n), p01(n), p02(n), p11(n), p12(n), p22(n) {}

KalmanBank::KalmanBank(double jerk_density, double position_noise, int n)
    : q_(jerk_density),
      r_(position_noise * position_noise),
      count_(n, 0),
      now_(n),
      before_(n),
      step_(n, 0.0) {
  if (!(std::isfinite(jerk_density) && jerk_density > 0 && std::isfinite(position_noise) &&
        position_noise > 0))
    throw std::invalid_argument("kalman: jerk density and position noise must be finite and > 0");
}

double KalmanBank::position_noise() const { return std::sqrt(r_); }

bool KalmanBank::add(int i, double t, double x) {
  if (!std::isfinite(t) || !std::isfinite(x)) return false;
  const LanePointers a = lane_pointers(now_), b = lane_pointers(before_);
  if (count_[i] > 0 && t == a.t[i]) {  // a repeated stamp replaces the sample
    if (count_[i] == 1) {
      a.s0[i] = x;
      return true;
    }
    set_filter(a, i, b.t[i], filter_at(b, i));  // undo, redo with x
    --count_[i];
  }
  const bool forward = count_[i] == 0 || t > a.t[i];
  if (!forward) reset(i);  // stamps went back (a bag looping): start over
  if (count_[i] == 0) {
    // Position known, the rest not.
    set_filter(a, i, t, Filter<double>{x, 0, 0, r_, 0, 0, 1e6, 0, 1e12});
    count_[i] = 1;
    return forward;
  }
  Filter<double> f = filter_at(a, i);
  set_filter(b, i, a.t[i], f);
  predict_update<double>(f, t - a.t[i], x, q_, r_);
  set_filter(a, i, t, f);
  ++count_[i];
  return true;
}

int KalmanBank::estimate(int i, double& first, double& second) const {
  if (count_[i] < 3) return 0;
  first = now_.s1[i];
  second = now_.s2[i];
  return 2;
}

void KalmanBank::add(double t, const double* x, const char* use) {
  const int n = size();
  const int others = mark_plain_on_cpu(t, x, use, n, now_.t.data(), count_.data(), step_.data());
  for (int i = 0; others && i < n; ++i)  // the others used, one by one
    if (use[i] && step_[i] == 0) add(i, t, x[i]);
#if defined(__x86_64__)
  if (has_avx2())
    return step_all_avx2(t, x, step_.data(), q_, r_, n, lane_pointers(now_),
                         lane_pointers(before_));
#endif
  step_all_portable(t, x, step_.data(), q_, r_, n, lane_pointers(now_), lane_pointers(before_));
}

bool KalmanBank::bounded(const char* use, int derivatives, double bound) const {
  return !beyond_on_cpu(use, count_.data(), now_.s1.data(), now_.s2.data(), size(),
                        derivatives >= 2, bound);
}

bool KalmanBank::all_estimated(double* first, double* second) const {
  if (std::find_if(count_.begin(), count_.end(), [](int c) { return c < 3; }) != count_.end())
    return false;
  std::copy(now_.s1.begin(), now_.s1.end(), first);
  if (second) std::copy(now_.s2.begin(), now_.s2.end(), second);
  return true;
}

}  // namespace mbk
