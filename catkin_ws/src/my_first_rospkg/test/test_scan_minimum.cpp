// Unit tests of the ROS-free scan minimum (twin of test/unit/test_scan.py).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "my_first_rospkg/scan_minimum.h"

using my_first_rospkg::findScanMinimum;

namespace
{
const float kInf = std::numeric_limits<float>::infinity();
const float kNaN = std::numeric_limits<float>::quiet_NaN();
}  // namespace

TEST(ScanMinimum, FindsSmallestWithAngle)
{
  const auto m = findScanMinimum({ 3.0f, 1.5f, 0.75f, 2.0f }, -1.0, 0.5, 0.1, 10.0);
  ASSERT_TRUE(m.found);
  EXPECT_FALSE(m.too_close);
  EXPECT_DOUBLE_EQ(m.distance, 0.75);
  EXPECT_DOUBLE_EQ(m.angle, 0.0);
  EXPECT_EQ(m.index, 2u);
}

TEST(ScanMinimum, SkipsNaNPositiveInfinityAndOutOfRange)
{
  const auto m = findScanMinimum({ kNaN, kInf, 0.05f, 12.0f, 4.0f }, 0.0, 0.1, 0.1, 10.0);
  ASSERT_TRUE(m.found);
  EXPECT_DOUBLE_EQ(m.distance, 4.0);
  EXPECT_EQ(m.index, 4u);
}

TEST(ScanMinimum, NegativeInfinityIsCloserThanRangeMin)
{
  const auto m = findScanMinimum({ 0.5f, -kInf, 0.2f }, 0.0, 0.1, 0.1, 10.0);
  ASSERT_TRUE(m.found);
  EXPECT_TRUE(m.too_close);
  EXPECT_DOUBLE_EQ(m.distance, 0.1);
  EXPECT_EQ(m.index, 1u);
}

TEST(ScanMinimum, NothingUsable)
{
  EXPECT_FALSE(findScanMinimum({ kNaN, kInf }, 0.0, 0.1, 0.1, 10.0).found);
  EXPECT_FALSE(findScanMinimum({}, 0.0, 0.1, 0.1, 10.0).found);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
