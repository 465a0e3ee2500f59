#ifndef TRIGRAV_EVALUATION_STATISTICS_H_
#define TRIGRAV_EVALUATION_STATISTICS_H_

// Summary statistics of error samples, with one quantile convention everywhere.

#include <vector>

namespace trigrav {

// The q-quantile (q in [0, 1]) of a sample of n values sorted as x_1 <= ... <= x_n: x_ceil(qn),
// and the mean of x_qn and x_qn+1 where qn is a whole number (Hyndman and Fan's definition 2, the
// inverse of the empirical distribution function with averaging at its steps). So the median (q =
// 0.5) is the mean of the two middle values for an even n, Quantile(x, 0) is the minimum and
// Quantile(x, 1) the maximum. NaN for an empty sample; infinite values sort as usual.
double Quantile(std::vector<double> values, double q);

// Quantile(values, 0.5).
double Median(std::vector<double> values);

// Arithmetic mean; NaN for an empty sample.
double Mean(const std::vector<double>& values);

// log10 of an error, with errors below kMinLoggedError (an exact zero among them) shown at
// log10(kMinLoggedError) = -17, so that log-error densities and means stay finite.
inline constexpr double kMinLoggedError = 1e-17;
double Log10Error(double error);

// Mean of Log10Error over the sample; NaN for an empty sample.
double MeanLog10Error(const std::vector<double>& values);

}  // namespace trigrav

#endif  // TRIGRAV_EVALUATION_STATISTICS_H_
