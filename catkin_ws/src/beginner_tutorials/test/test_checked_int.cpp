#include <gtest/gtest.h>

#include <limits>

#include "beginner_tutorials/checked_int.h"

using beginner_tutorials::checkedAdd;
using beginner_tutorials::parseInt64;

namespace
{
const int64_t kMax = std::numeric_limits<int64_t>::max();
const int64_t kMin = std::numeric_limits<int64_t>::min();
}  // namespace

TEST(ParseInt64, AcceptsSignedDecimals)
{
  int64_t value = 0;
  EXPECT_TRUE(parseInt64("42", &value));
  EXPECT_EQ(value, 42);
  EXPECT_TRUE(parseInt64("-7", &value));
  EXPECT_EQ(value, -7);
  EXPECT_TRUE(parseInt64("+3", &value));
  EXPECT_EQ(value, 3);
  EXPECT_TRUE(parseInt64("9223372036854775807", &value));
  EXPECT_EQ(value, kMax);
  EXPECT_TRUE(parseInt64("-9223372036854775808", &value));
  EXPECT_EQ(value, kMin);
}

TEST(ParseInt64, RejectsEverythingElse)
{
  int64_t value = 0;
  for (const char* text : { "", "-", "+", "1.5", "abc", "12abc", " 1", "1 ", "0x10", "1e3", "9223372036854775808",
                            "-9223372036854775809", "99999999999999999999" })
    EXPECT_FALSE(parseInt64(text, &value)) << "accepted '" << text << "'";
}

TEST(CheckedAdd, AddsWithinRange)
{
  int64_t sum = 0;
  EXPECT_TRUE(checkedAdd(1, 2, &sum));
  EXPECT_EQ(sum, 3);
  EXPECT_TRUE(checkedAdd(kMax, kMin, &sum));
  EXPECT_EQ(sum, -1);
  EXPECT_TRUE(checkedAdd(kMax - 1, 1, &sum));
  EXPECT_EQ(sum, kMax);
}

TEST(CheckedAdd, RefusesOverflow)
{
  int64_t sum = 0;
  EXPECT_FALSE(checkedAdd(kMax, 1, &sum));
  EXPECT_FALSE(checkedAdd(kMin, -1, &sum));
  EXPECT_FALSE(checkedAdd(kMax, kMax, &sum));
  EXPECT_FALSE(checkedAdd(kMin, kMin, &sum));
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
