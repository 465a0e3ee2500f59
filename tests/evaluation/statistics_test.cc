// Statistics: the one quantile convention (Hyndman and Fan's definition 2) and the log error.
#include "trigrav/evaluation/statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace trigrav {
namespace {

TEST(Statistics, MedianOfAnEvenCountIsTheMeanOfTheTwoMiddleValues) {
  EXPECT_DOUBLE_EQ(Median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_DOUBLE_EQ(Median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_DOUBLE_EQ(Median({7.0}), 7.0);
  EXPECT_TRUE(std::isnan(Median({})));
}

TEST(Statistics, QuantileInvertsTheEmpiricalDistributionAveragingAtItsSteps) {
  const std::vector<double> ten = {10, 1, 9, 2, 8, 3, 7, 4, 6, 5};
  EXPECT_DOUBLE_EQ(Quantile(ten, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(Quantile(ten, 1.0), 10.0);
  EXPECT_DOUBLE_EQ(Quantile(ten, 0.9), 9.5);    // qn = 9: mean of x_9 and x_10
  EXPECT_DOUBLE_EQ(Quantile(ten, 0.95), 10.0);  // qn = 9.5: x_10
  EXPECT_DOUBLE_EQ(Quantile(ten, 0.25), 3.0);   // qn = 2.5: x_3
  EXPECT_DOUBLE_EQ(Quantile(ten, 0.5), Median(ten));
  EXPECT_TRUE(std::isnan(Quantile(ten, 1.5)));
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(Quantile({1.0, inf, 2.0}, 1.0), inf);
  EXPECT_DOUBLE_EQ(Quantile({1.0, inf, 2.0}, 0.5), 2.0);
}

TEST(Statistics, MeanAndLogError) {
  EXPECT_DOUBLE_EQ(Mean({1.0, 2.0, 6.0}), 3.0);
  EXPECT_TRUE(std::isnan(Mean({})));
  EXPECT_DOUBLE_EQ(Log10Error(1e-3), -3.0);
  EXPECT_DOUBLE_EQ(Log10Error(0.0), -17.0);
  EXPECT_DOUBLE_EQ(MeanLog10Error({1e-2, 1e-4, 0.0}), (-2.0 - 4.0 - 17.0) / 3.0);
}

}  // namespace
}  // namespace trigrav
