#include "mb_kinematics/core/euler_order.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

namespace mbk {
namespace {

TEST(EulerOrderTest, TwelveOrdersRoundTripThroughTheirNames) {
  std::set<std::string> names;
  for (int i = 0; i <= static_cast<int>(EulerOrder::kLast); ++i) {
    const auto order = static_cast<EulerOrder>(i);
    const std::array<int, 3> a = euler_axes(order);
    EXPECT_NE(a[0], a[1]);
    EXPECT_NE(a[1], a[2]);
    EXPECT_EQ(euler_order_from_string(to_string(order)), order);
    EXPECT_EQ(euler_order_from_axes(a), order);
    EXPECT_EQ(is_tait_bryan(order), a[0] != a[2]);
    names.insert(to_string(order));
  }
  EXPECT_EQ(names.size(), 12u);
}

TEST(EulerOrderTest, DigitsAndLowerCaseAreRead) {
  EXPECT_EQ(euler_order_from_string("123"), EulerOrder::kXYZ);
  EXPECT_EQ(euler_order_from_string("313"), EulerOrder::kZXZ);
  EXPECT_EQ(euler_order_from_string("zxy"), EulerOrder::kZXY);
}

TEST(EulerOrderTest, BadOrdersAreRefusedByName) {
  for (const char* bad : {"XXY", "XY", "XYZW", "ABC", "112", ""}) {
    try {
      euler_order_from_string(bad);
      ADD_FAILURE() << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("'") + bad + "'"), std::string::npos);
    }
  }
  EXPECT_THROW(euler_order_from_axes({0, 0, 1}), std::invalid_argument);
}

}  // namespace
}  // namespace mbk
