// mbk::sized_for, the check every algorithm asserts at entry (mb_kinematics/core/data.h).
#include "mb_kinematics/core/data.h"

#include <gtest/gtest.h>

TEST(Data, SizedForItsOwnModelOnly) {
  const mbk::Model three = mbk::make_bare_model({0, 1, 2}, mbk::JointType::kRevolute);
  const mbk::Model four = mbk::make_bare_model({0, 1, 2, 1}, mbk::JointType::kRevolute);
  const mbk::Data<double> data(three);
  EXPECT_TRUE(mbk::sized_for(data, three));
  EXPECT_FALSE(mbk::sized_for(data, four));
  EXPECT_TRUE(mbk::sized_for(mbk::Data<float>(four), four));
  // The same bodies on joints without angles: the angles' sines and cosines would not fit.
  const mbk::Model fixed = mbk::make_bare_model({0, 1, 2}, mbk::JointType::kFixed);
  EXPECT_FALSE(mbk::sized_for(mbk::Data<double>(fixed), three));
}
