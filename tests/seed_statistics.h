// Statistics over seeds for the distribution tests: a per-seed series' mean and spread, and the
// difference of two series' means in standard errors (Welch).
#pragma once

#include <cmath>
#include <vector>

namespace scallop {

inline double Mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

// Sample standard deviation (n - 1 in the denominator).
inline double Spread(const std::vector<double>& values) {
  const double mean = Mean(values);
  double sum = 0.0;
  for (double v : values) sum += (v - mean) * (v - mean);
  return std::sqrt(sum / static_cast<double>(values.size() - 1));
}

// |mean(a) - mean(b)| in standard errors of that difference (Welch). Exactly equal constant
// series (g below d is 0 for everyone) count as 0.
inline double ZScore(const std::vector<double>& a, const std::vector<double>& b) {
  const double difference = Mean(a) - Mean(b);
  const double standard_error = std::sqrt(Spread(a) * Spread(a) / static_cast<double>(a.size()) +
                                          Spread(b) * Spread(b) / static_cast<double>(b.size()));
  if (difference == 0.0) return 0.0;
  return standard_error > 0.0 ? std::abs(difference) / standard_error : INFINITY;
}

}  // namespace scallop
