#include "trigrav/evaluation/statistics.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>

namespace trigrav {

double Quantile(std::vector<double> values, double q) {
  if (values.empty() || !(q >= 0.0 && q <= 1.0)) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = values.size();
  std::sort(values.begin(), values.end());
  const double rank = q * static_cast<double>(n);  // the 1-based rank qn
  const double whole = std::floor(rank);
  if (rank == whole) {
    // x_qn and x_qn+1, clamped to the sample at q = 0 and q = 1.
    const std::size_t lower = static_cast<std::size_t>(std::max(whole, 1.0)) - 1;
    const std::size_t upper = std::min(static_cast<std::size_t>(whole), n - 1);
    return 0.5 * (values[lower] + values[upper]);
  }
  return values[std::min(static_cast<std::size_t>(whole), n - 1)];  // x_ceil(qn)
}

double Median(std::vector<double> values) { return Quantile(std::move(values), 0.5); }

double Mean(const std::vector<double>& values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

double Log10Error(double error) { return std::log10(std::max(error, kMinLoggedError)); }

double MeanLog10Error(const std::vector<double>& values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  for (const double v : values) sum += Log10Error(v);
  return sum / static_cast<double>(values.size());
}

}  // namespace trigrav
