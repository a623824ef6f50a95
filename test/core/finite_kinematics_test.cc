// finite_kinematics (core/finite_kinematics.h): a NaN or Inf in any quantity the level computes
// is found, in whichever body and component; quantities above the level are not looked at.
#include "mb_kinematics/core/finite_kinematics.h"

#include <gtest/gtest.h>

#include <limits>

#include "mb_kinematics/core/kinematics_double.h"
#include "test/support/test_models.h"

namespace {

TEST(FiniteKinematics, FindsEveryNonFiniteNumberOfItsLevel) {
  const mbk::Model model = mbk_test::random_tree(9, 4);
  const mbk_test::Trajectory trajectory(model, 4);
  mbk::Data<double> data(model);
  mbk::forward_kinematics(model, trajectory.at<double>(0.3), data, mbk::Level::kAcceleration);
  ASSERT_TRUE(mbk::finite_kinematics(data, mbk::Level::kAcceleration));
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::infinity(),
                        -std::numeric_limits<double>::infinity()};
  // Each array with the first level that computes it.
  const std::vector<std::pair<double* (*)(mbk::Data<double>&, int), mbk::Level>> arrays = {
      {[](mbk::Data<double>& d, int k) { return d.rotation[k].data(); }, mbk::Level::kPose},
      {[](mbk::Data<double>& d, int k) { return d.origin[k].data(); }, mbk::Level::kPose},
      {[](mbk::Data<double>& d, int k) { return d.mass_center[k].data(); }, mbk::Level::kPose},
      {[](mbk::Data<double>& d, int k) { return d.omega[k].data(); }, mbk::Level::kVelocity},
      {[](mbk::Data<double>& d, int k) { return d.mass_center_velocity[k].data(); },
       mbk::Level::kVelocity},
      {[](mbk::Data<double>& d, int k) { return d.origin_velocity[k].data(); },
       mbk::Level::kVelocity},
      {[](mbk::Data<double>& d, int k) { return d.alpha[k].data(); }, mbk::Level::kAcceleration},
      {[](mbk::Data<double>& d, int k) { return d.mass_center_acceleration[k].data(); },
       mbk::Level::kAcceleration},
      {[](mbk::Data<double>& d, int k) { return d.origin_acceleration[k].data(); },
       mbk::Level::kAcceleration}};
  for (size_t a = 0; a < arrays.size(); ++a)
    for (int k : {1, 5, model.body_count()})
      for (int i : {0, 2})
        for (double b : bad) {
          mbk::Data<double> d = data;
          arrays[a].first(d, k)[i] = b;
          for (mbk::Level level :
               {mbk::Level::kPose, mbk::Level::kVelocity, mbk::Level::kAcceleration}) {
            const bool looked_at = level >= arrays[a].second;
            EXPECT_EQ(mbk::finite_kinematics(d, level), !looked_at)
                << "array " << a << " body " << k << " entry " << i << " value " << b;
            EXPECT_EQ(mbk::finite_kinematics(d, k, level), !looked_at) << a << " " << k;
            EXPECT_TRUE(mbk::finite_kinematics(d, k == 1 ? 2 : 1, level)) << a << " " << k;
          }
        }
}

}  // namespace
