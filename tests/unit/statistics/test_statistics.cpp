// SPDX-License-Identifier: Apache-2.0
// Descriptive statistics: hand-computed values, empty inputs, the two
// percentile definitions, and the position-error statistics of series with
// known spread and correlation.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/statistics/statistics.hpp"

namespace gnssemu::statistics {
namespace {

TEST(Statistics, MeanRmsSpread) {
  const std::vector<double> v{1.0, -2.0, 3.0, 6.0};
  EXPECT_DOUBLE_EQ(mean(v), 2.0);
  EXPECT_DOUBLE_EQ(rms(v), std::sqrt(50.0 / 4.0));
  EXPECT_DOUBLE_EQ(max_abs(v), 6.0);
  EXPECT_DOUBLE_EQ(variance(v, 2.0), (1.0 + 16.0 + 1.0 + 16.0) / 4.0);
  EXPECT_DOUBLE_EQ(std_dev(v, 2.0), std::sqrt(34.0 / 4.0));
}

TEST(Statistics, EmptyIsNaN) {
  const std::vector<double> none;
  EXPECT_TRUE(std::isnan(mean(none)));
  EXPECT_TRUE(std::isnan(rms(none)));
  EXPECT_TRUE(std::isnan(max_abs(none)));
  EXPECT_TRUE(std::isnan(variance(none, 0.0)));
  EXPECT_TRUE(std::isnan(percentile_nearest_rank(none, 0.5)));
  EXPECT_TRUE(std::isnan(quantile_linear(none, 0.5)));
}

TEST(Statistics, NearestRankPercentile) {
  // Unsorted on purpose: 1..20.
  std::vector<double> v;
  for (int i = 20; i >= 1; --i) v.push_back(i);
  EXPECT_EQ(percentile_nearest_rank(v, 0.95), 19.0);  // ceil(0.95 * 20) = 19th smallest
  EXPECT_EQ(percentile_nearest_rank(v, 0.5), 10.0);
  EXPECT_EQ(percentile_nearest_rank(v, 1.0), 20.0);
  EXPECT_EQ(percentile_nearest_rank(v, 0.001), 1.0);  // rank held at >= 1
  EXPECT_EQ(percentile_nearest_rank({7.0}, 0.95), 7.0);
}

TEST(Statistics, LinearQuantile) {
  const std::vector<double> v{4.0, 1.0, 3.0, 2.0};
  EXPECT_DOUBLE_EQ(quantile_linear(v, 0.5), 2.5);  // between the 2nd and 3rd
  EXPECT_DOUBLE_EQ(quantile_linear(v, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(quantile_linear(v, 1.0), 4.0);
  EXPECT_DOUBLE_EQ(quantile_linear(v, 0.95), 3.0 + 0.85);  // pos 2.85
}

TEST(Statistics, PositionErrorStatsOfAKnownSeries) {
  // e alternates +-1 (white, mean 0), n is 2 + 0 (constant), u a slow ramp;
  // one missing epoch.
  std::vector<Enu> err;
  for (int i = 0; i < 200; ++i) err.emplace_back(i % 2 == 0 ? 1.0 : -1.0, 2.0, 0.01 * i);
  err[50] = Enu(NAN, NAN, NAN);
  const PositionErrorStats s = position_error_stats(err, 1.0);
  EXPECT_EQ(s.n, 199);
  EXPECT_NEAR(s.mean_e_m, -1.0 / 199.0, 1e-12);  // the missing sample was a +1
  EXPECT_DOUBLE_EQ(s.mean_n_m, 2.0);
  EXPECT_DOUBLE_EQ(s.sigma_n_m, 0.0);
  EXPECT_NEAR(s.sigma_e_m, 1.0, 1e-4);
  EXPECT_DOUBLE_EQ(s.cep50_m, std::hypot(1.0, 2.0));  // every horizontal error is sqrt(5)
  EXPECT_DOUBLE_EQ(s.cep95_m, std::hypot(1.0, 2.0));
  // At lag 1: e -1, n nothing (no variance), the ramp in u almost 1: the
  // mean is near 0, below 1/e within the first lag.
  EXPECT_GT(s.corr_time_s, 0.0);
  EXPECT_LT(s.corr_time_s, 1.0);
}

TEST(Statistics, CorrelationTimeOfAnExponentialSeries) {
  // A deterministic AR(1)-like sequence is not needed: a slow sine of period
  // 400 s has its autocorrelation cos(2 pi k / 400), which reaches 1/e at
  // k = 400 acos(1/e) / (2 pi) = 76.4 s (slightly earlier over a finite span).
  std::vector<Enu> err;
  for (int i = 0; i < 4000; ++i) {
    const double x = std::sin(2.0 * M_PI * i / 400.0);
    err.emplace_back(x, x, x);
  }
  const PositionErrorStats s = position_error_stats(err, 1.0);
  EXPECT_NEAR(s.corr_time_s, 400.0 * std::acos(std::exp(-1.0)) / (2.0 * M_PI), 3.0);
  // No finite sample: zeros.
  const PositionErrorStats none = position_error_stats({Enu(NAN, 0.0, 0.0)}, 1.0);
  EXPECT_EQ(none.n, 0);
  EXPECT_EQ(none.corr_time_s, 0.0);
}

}  // namespace
}  // namespace gnssemu::statistics
