#include "mb_kinematics/core/finite_kinematics.h"

#include <cstring>

namespace mbk {
namespace {

// n numbers from x.
struct Numbers {
  const double* x;
  long n;
};

// Every number of the `count` arrays finite. x * 0 is 0 for a finite x and NaN for Inf or NaN, so
// one sum tells: packs of kWidth doubles (GNU vectors), four sums in flight over all the arrays,
// no branch per number, one reduction at the end. With FMA the compiler makes each x * 0 + sum
// one fused multiply-add (-ffp-contract=fast, GCC's default): x * 0 is exact, the same verdict.
template <int kWidth>
__attribute__((always_inline)) inline bool finite_numbers(const Numbers* arrays, int count) {
  typedef double Pack __attribute__((vector_size(kWidth * sizeof(double))));
  Pack sum[4] = {};
  double total = 0;
  for (int a = 0; a < count; ++a) {
    const double* x = arrays[a].x;
    const long n = arrays[a].n;
    long i = 0;
    for (; i + 4 * kWidth <= n; i += 4 * kWidth)
      for (int p = 0; p < 4; ++p) {
        Pack v;
        std::memcpy(&v, x + i + p * kWidth, sizeof v);
        sum[p] += v * 0.0;
      }
    for (; i < n; ++i) total += x[i] * 0.0;
  }
  for (const Pack& p : sum) {
    double lanes[kWidth];
    std::memcpy(lanes, &p, sizeof lanes);
    for (double lane : lanes) total += lane;
  }
  return total == 0.0;
}

#if defined(__x86_64__)
__attribute__((target("avx2,fma"))) bool finite_numbers_avx2_fma(const Numbers* arrays, int count) {
  return finite_numbers<4>(arrays, count);
}
#endif

bool finite_numbers_on_cpu(const Numbers* arrays, int count) {
#if defined(__x86_64__)
  static const bool avx2_fma = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  if (avx2_fma) return finite_numbers_avx2_fma(arrays, count);
#endif
  return finite_numbers<2>(arrays, count);
}

// The numbers of bodies 1..N in one of Data's arrays.
template <typename M>
Numbers numbers(const std::vector<M>& a) {
  constexpr int size = M::SizeAtCompileTime;
  static_assert(sizeof(M) == size * sizeof(double), "Data's arrays hold bare numbers");
  if (a.size() < 2) return {nullptr, 0};
  return {a[1].data(), size * (static_cast<long>(a.size()) - 1)};
}

}  // namespace

bool finite_kinematics(const Data<double>& d, Level level) {
  const Numbers arrays[] = {numbers(d.rotation),
                            numbers(d.origin),
                            numbers(d.mass_center),
                            numbers(d.omega),
                            numbers(d.mass_center_velocity),
                            numbers(d.origin_velocity),
                            numbers(d.alpha),
                            numbers(d.mass_center_acceleration),
                            numbers(d.origin_acceleration)};
  const int count = level == Level::kPose ? 3 : level == Level::kVelocity ? 6 : 9;
  return finite_numbers_on_cpu(arrays, count);
}

bool finite_kinematics(const Data<double>& d, int k, Level level) {
  bool ok = d.rotation[k].allFinite() && d.origin[k].allFinite() && d.mass_center[k].allFinite();
  if (level != Level::kPose)
    ok = ok && d.omega[k].allFinite() && d.mass_center_velocity[k].allFinite() &&
         d.origin_velocity[k].allFinite();
  if (level == Level::kAcceleration)
    ok = ok && d.alpha[k].allFinite() && d.mass_center_acceleration[k].allFinite() &&
         d.origin_acceleration[k].allFinite();
  return ok;
}

}  // namespace mbk
