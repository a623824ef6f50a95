// The chapter's Tables 4.2.1 and 4.2.2 reproduced from the lower body arrays (doc/method.md 1).
#include "mb_kinematics/core/lower_body_array.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "mb_kinematics/io/lower_body_text.h"

namespace {

using Table = std::vector<std::vector<int>>;

const std::vector<int> kTenBody = {0, 1, 2, 1, 1, 5, 2, 7, 8, 9};
const std::vector<int> kHuman = {0, 1, 2, 3, 4, 5, 4, 7, 4, 9, 2, 11, 12, 2, 14, 15};

TEST(LowerBodyArray, Table421TenBodySystem) {
  // Table 4.2.1 with its blanks (chain already at R) written as zeros.
  const Table expected = {
      {1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, {0, 1, 2, 1, 1, 5, 2, 7, 8, 9},
      {0, 0, 1, 0, 0, 1, 1, 2, 7, 8},  {0, 0, 0, 0, 0, 0, 0, 1, 2, 7},
      {0, 0, 0, 0, 0, 0, 0, 0, 1, 2},  {0, 0, 0, 0, 0, 0, 0, 0, 0, 1},
      {0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
  };
  EXPECT_EQ(mbk::lower_body_table(kTenBody), expected);
}

TEST(LowerBodyArray, Table422HumanBodyModel) {
  // Table 4.2.2 (16 bodies, body 1 implicit in the chapter's print: doc/method.md 7).
  const Table expected = {
      {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16},
      {0, 1, 2, 3, 4, 5, 4, 7, 4, 9, 2, 11, 12, 2, 14, 15},
      {0, 0, 1, 2, 3, 4, 3, 4, 3, 4, 1, 2, 11, 1, 2, 14},
      {0, 0, 0, 1, 2, 3, 2, 3, 2, 3, 0, 1, 2, 0, 1, 2},
      {0, 0, 0, 0, 1, 2, 1, 2, 1, 2, 0, 0, 1, 0, 0, 1},
      {0, 0, 0, 0, 0, 1, 0, 1, 0, 1, 0, 0, 0, 0, 0, 0},
      {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
  };
  EXPECT_EQ(mbk::lower_body_table(kHuman), expected);
}

TEST(LowerBodyArray, PowersAndAncestors) {
  EXPECT_EQ(mbk::lower_body_power(kTenBody, 10, 0), 10);
  EXPECT_EQ(mbk::lower_body_power(kTenBody, 10, 3), 7);
  EXPECT_EQ(mbk::lower_body_power(kTenBody, 10, 6), 0);
  EXPECT_TRUE(mbk::is_ancestor_or_self(kTenBody, 2, 10));
  EXPECT_TRUE(mbk::is_ancestor_or_self(kTenBody, 0, 10));
  EXPECT_FALSE(mbk::is_ancestor_or_self(kTenBody, 5, 10));
  EXPECT_TRUE(mbk::is_ancestor_or_self(kTenBody, 5, 6));
  EXPECT_FALSE(mbk::is_ancestor_or_self(kTenBody, 4, 6));  // the chapter's Table 4.4.1 erratum
}

void expect_invalid(const std::vector<int>& lower, const std::string& fragment) {
  try {
    mbk::validate_lower_body_array(lower);
    ADD_FAILURE() << "accepted an invalid array";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(LowerBodyArray, ValidationNamesTheBody) {
  EXPECT_NO_THROW(mbk::validate_lower_body_array(kTenBody));
  expect_invalid({}, "empty");
  expect_invalid({0, 2}, "body 2 has L(2) = 2");
  expect_invalid({0, 1, 5}, "body 3 has L(3) = 5");
  expect_invalid({0, -1}, "body 2 has L(2) = -1");
  expect_invalid({1}, "body 1 has L(1) = 1");
}

TEST(LowerBodyArray, Parse) {
  EXPECT_EQ(mbk::parse_lower_body_array("0, 1,2"), (std::vector<int>{0, 1, 2}));
  EXPECT_THROW(mbk::parse_lower_body_array("0,x,2"), std::invalid_argument);
  EXPECT_THROW(mbk::parse_lower_body_array("0,1.5"), std::invalid_argument);
}

}  // namespace
