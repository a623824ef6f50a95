#include "mb_kinematics/core/finite_kinematics.h"

#include <cstring>

namespace mbk {
namespace {

// Every one of x[0, n) finite. x * 0 is 0 for a finite x and NaN for Inf or NaN, so one sum
// tells: packs of kWidth doubles (GNU vectors), four sums in flight, no branch per number.
template <int kWidth>
__attribute__((always_inline)) inline bool finite_numbers(const double* x, long n) {
  typedef double Pack __attribute__((vector_size(kWidth * sizeof(double))));
  Pack sum[4] = {};
  long i = 0;
  for (; i + 4 * kWidth <= n; i += 4 * kWidth)
    for (int p = 0; p < 4; ++p) {
      Pack v;
      std::memcpy(&v, x + i + p * kWidth, sizeof v);
      sum[p] += v * 0.0;
    }
  double total = 0;
  for (; i < n; ++i) total += x[i] * 0.0;
  for (const Pack& p : sum) {
    double lanes[kWidth];
    std::memcpy(lanes, &p, sizeof lanes);
    for (double lane : lanes) total += lane;
  }
  return total == 0.0;
}

#if defined(__x86_64__)
__attribute__((target("avx2"))) bool finite_numbers_avx2(const double* x, long n) {
  return finite_numbers<4>(x, n);
}
#endif

// Every number of bodies 1..N in one of Data's arrays finite.
template <typename M>
bool finite(const std::vector<M>& a) {
  constexpr int size = M::SizeAtCompileTime;
  static_assert(sizeof(M) == size * sizeof(double), "Data's arrays hold bare numbers");
  if (a.size() < 2) return true;
  const long n = size * (static_cast<long>(a.size()) - 1);
#if defined(__x86_64__)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) return finite_numbers_avx2(a[1].data(), n);
#endif
  return finite_numbers<2>(a[1].data(), n);
}

}  // namespace

bool finite_kinematics(const Data<double>& d, Level level) {
  bool ok = finite(d.rotation) && finite(d.origin) && finite(d.mass_center);
  if (level != Level::kPose)
    ok = ok && finite(d.omega) && finite(d.mass_center_velocity) && finite(d.origin_velocity);
  if (level == Level::kAcceleration)
    ok = ok && finite(d.alpha) && finite(d.mass_center_acceleration) &&
         finite(d.origin_acceleration);
  return ok;
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
