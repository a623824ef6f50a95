#include "mb_kinematics/estimation/base_accelerations.h"

namespace mbk {

void base_accelerations(const std::vector<BaseSample>& samples, const OfflineEstimator& estimator,
                        double max_gap, std::vector<Vec3<double>>& linear_acceleration,
                        std::vector<Vec3<double>>& angular_acceleration, std::vector<int>& valid) {
  const size_t n = samples.size();
  std::vector<double> t(n), x(n), first, second;
  std::vector<int> ok;
  for (size_t i = 0; i < n; ++i) t[i] = samples[i].t;
  linear_acceleration.assign(n, Vec3<double>::Zero());
  angular_acceleration.assign(n, Vec3<double>::Zero());
  valid.assign(n, 1);
  for (int angular = 0; angular < 2; ++angular)
    for (int c = 0; c < 3; ++c) {
      for (size_t i = 0; i < n; ++i) {  // the twist in R components
        const BaseSample& s = samples[i];
        x[i] = (s.orientation * (angular ? s.angular : s.linear))[c];
      }
      estimate_offline(estimator, t, x, max_gap, first, second, ok);
      for (size_t i = 0; i < n; ++i) {
        (angular ? angular_acceleration : linear_acceleration)[i][c] = ok[i] >= 1 ? first[i] : 0;
        valid[i] = valid[i] && ok[i] >= 1;
      }
    }
}

}  // namespace mbk
