// Small statistics and CPU timers, checked against known answers.

#include <sylva/core/stats.hpp>
#include <sylva/core/timer.hpp>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <thread>
#include <vector>

namespace {

std::vector<double> one_to(int n) {
  std::vector<double> v(static_cast<std::size_t>(n));
  std::iota(v.begin(), v.end(), 1.0);
  return v;
}

TEST(Stats, KnownAnswersOneToHundred) {
  std::vector<double> v = one_to(100);
  std::shuffle(v.begin(), v.end(), std::mt19937(3));  // order must not matter
  EXPECT_DOUBLE_EQ(sylva::mean(v), 50.5);
  EXPECT_DOUBLE_EQ(sylva::median(v), 50.5);
  // Type-7 interpolation: h = 99 * p / 100.
  EXPECT_DOUBLE_EQ(sylva::percentile(v, 99.0), 99.01);
  EXPECT_DOUBLE_EQ(sylva::percentile(v, 90.0), 90.1);
  EXPECT_DOUBLE_EQ(sylva::percentile(v, 25.0), 25.75);
  EXPECT_DOUBLE_EQ(sylva::percentile(v, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(sylva::percentile(v, 100.0), 100.0);
  EXPECT_DOUBLE_EQ(sylva::min_value(v), 1.0);
  EXPECT_DOUBLE_EQ(sylva::max_value(v), 100.0);
  // Sample standard deviation of 1..n is sqrt(n (n + 1) / 12).
  EXPECT_DOUBLE_EQ(sylva::stddev(v), std::sqrt(100.0 * 101.0 / 12.0));
}

TEST(Stats, SmallCases) {
  const std::vector<double> odd = {5.0, 1.0, 3.0};
  EXPECT_DOUBLE_EQ(sylva::median(odd), 3.0);
  const std::vector<double> even = {4.0, 1.0, 3.0, 2.0};
  EXPECT_DOUBLE_EQ(sylva::median(even), 2.5);
  const std::vector<double> single = {7.0};
  EXPECT_DOUBLE_EQ(sylva::mean(single), 7.0);
  EXPECT_DOUBLE_EQ(sylva::median(single), 7.0);
  EXPECT_DOUBLE_EQ(sylva::percentile(single, 99.0), 7.0);
  EXPECT_DOUBLE_EQ(sylva::stddev(single), 0.0);
  const std::vector<double> two = {0.0, 10.0};
  EXPECT_DOUBLE_EQ(sylva::percentile(two, 99.0), 9.9);
  EXPECT_DOUBLE_EQ(sylva::stddev(two), std::sqrt(50.0));
}

TEST(Stats, EmptyInputIsNaN) {
  const std::vector<double> empty;
  EXPECT_TRUE(std::isnan(sylva::mean(empty)));
  EXPECT_TRUE(std::isnan(sylva::median(empty)));
  EXPECT_TRUE(std::isnan(sylva::percentile(empty, 99.0)));
  EXPECT_TRUE(std::isnan(sylva::min_value(empty)));
  EXPECT_TRUE(std::isnan(sylva::max_value(empty)));
  EXPECT_TRUE(std::isnan(sylva::stddev(empty)));
  const sylva::SampleSummary s = sylva::summarize(empty);
  EXPECT_EQ(s.count, 0u);
  EXPECT_TRUE(std::isnan(s.mean));
  EXPECT_TRUE(std::isnan(s.p99));
}

TEST(Stats, NaNSamplePropagates) {
  std::vector<double> v = one_to(10);
  v[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(sylva::mean(v)));
  EXPECT_TRUE(std::isnan(sylva::median(v)));
  EXPECT_TRUE(std::isnan(sylva::percentile(v, 99.0)));
  EXPECT_TRUE(std::isnan(sylva::min_value(v)));
  EXPECT_TRUE(std::isnan(sylva::stddev(v)));
  const sylva::SampleSummary s = sylva::summarize(v);
  EXPECT_EQ(s.count, 10u);
  EXPECT_TRUE(std::isnan(s.p50));
  sylva::RunningStats r;
  for (double x : v) r.add(x);
  EXPECT_TRUE(std::isnan(r.mean()));
  EXPECT_TRUE(std::isnan(r.max()));
  EXPECT_TRUE(std::isnan(r.sum()));
}

TEST(Stats, InfinitySamplesAreOrdered) {
  const std::vector<double> v = {1.0, std::numeric_limits<double>::infinity(), 2.0};
  EXPECT_EQ(sylva::max_value(v), std::numeric_limits<double>::infinity());
  EXPECT_DOUBLE_EQ(sylva::median(v), 2.0);
}

TEST(StatsDeathTest, PercentileOutsideRangeAsserts) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const std::vector<double> v = {1.0};
  EXPECT_DEATH((void)sylva::percentile(v, 101.0), "percentile p=101");
  EXPECT_DEATH((void)sylva::percentile(v, -1.0), "percentile p=-1");
}

TEST(Stats, SummaryMatchesTheSingleFunctions) {
  std::mt19937 rng(11);
  std::lognormal_distribution<double> frame_ms(2.0, 0.4);
  std::vector<double> v(1000);
  for (double& x : v) x = frame_ms(rng);
  const sylva::SampleSummary s = sylva::summarize(v);
  EXPECT_EQ(s.count, 1000u);
  EXPECT_DOUBLE_EQ(s.mean, sylva::mean(v));
  EXPECT_DOUBLE_EQ(s.stddev, sylva::stddev(v));
  EXPECT_DOUBLE_EQ(s.min, sylva::min_value(v));
  EXPECT_DOUBLE_EQ(s.max, sylva::max_value(v));
  EXPECT_DOUBLE_EQ(s.p50, sylva::median(v));
  EXPECT_DOUBLE_EQ(s.p90, sylva::percentile(v, 90.0));
  EXPECT_DOUBLE_EQ(s.p99, sylva::percentile(v, 99.0));
  EXPECT_LE(s.min, s.p50);
  EXPECT_LE(s.p50, s.p90);
  EXPECT_LE(s.p90, s.p99);
  EXPECT_LE(s.p99, s.max);
}

TEST(Stats, SummaryJson) {
  nlohmann::json j = sylva::summarize(one_to(100));
  EXPECT_EQ(j["count"], 100);
  EXPECT_DOUBLE_EQ(j["mean"].get<double>(), 50.5);
  EXPECT_DOUBLE_EQ(j["p50"].get<double>(), 50.5);
  EXPECT_DOUBLE_EQ(j["p99"].get<double>(), 99.01);
  EXPECT_DOUBLE_EQ(j["max"].get<double>(), 100.0);
  nlohmann::json empty = sylva::summarize({});
  EXPECT_EQ(empty["count"], 0);
  EXPECT_TRUE(empty["mean"].is_null());  // NaN is null, so the file stays valid JSON
  EXPECT_EQ(empty.dump().find("NaN"), std::string::npos);
}

TEST(RunningStats, MatchesBatchResults) {
  sylva::RunningStats r;
  EXPECT_EQ(r.count(), 0u);
  EXPECT_TRUE(std::isnan(r.mean()));
  EXPECT_TRUE(std::isnan(r.variance()));
  EXPECT_TRUE(std::isnan(r.min()));
  const std::vector<double> v = one_to(100);
  for (double x : v) r.add(x);
  EXPECT_EQ(r.count(), 100u);
  EXPECT_DOUBLE_EQ(r.mean(), 50.5);
  EXPECT_DOUBLE_EQ(r.sum(), 5050.0);
  EXPECT_DOUBLE_EQ(r.stddev(), sylva::stddev(v));
  EXPECT_DOUBLE_EQ(r.variance(), 100.0 * 101.0 / 12.0);
  EXPECT_EQ(r.min(), 1.0);
  EXPECT_EQ(r.max(), 100.0);
  r.reset();
  EXPECT_EQ(r.count(), 0u);
  r.add(3.0);
  EXPECT_EQ(r.variance(), 0.0);
}

TEST(RunningStats, MergeEqualsAddingEverything) {
  std::mt19937 rng(5);
  std::normal_distribution<double> dist(10.0, 3.0);
  sylva::RunningStats all, a, b, empty;
  for (int i = 0; i < 1000; ++i) {
    const double x = dist(rng);
    all.add(x);
    (i % 3 == 0 ? a : b).add(x);
  }
  sylva::RunningStats merged = a;
  merged.merge(b);
  merged.merge(empty);
  EXPECT_EQ(merged.count(), all.count());
  EXPECT_NEAR(merged.mean(), all.mean(), 1e-12);
  EXPECT_NEAR(merged.variance(), all.variance(), 1e-9);
  EXPECT_EQ(merged.min(), all.min());
  EXPECT_EQ(merged.max(), all.max());
  sylva::RunningStats from_empty;
  from_empty.merge(a);
  EXPECT_EQ(from_empty.count(), a.count());
  EXPECT_EQ(from_empty.mean(), a.mean());
}

TEST(RunningStats, StableForLargeOffsets) {
  // Invariant: the variance of values 1e9 + {4, 7, 13, 16} is 30 despite the offset (a naive
  // sum-of-squares formula loses every digit here).
  sylva::RunningStats r;
  for (double x : {4.0, 7.0, 13.0, 16.0}) r.add(1e9 + x);
  EXPECT_NEAR(r.variance(), 30.0, 1e-6);
  const std::vector<double> v = {1e9 + 4, 1e9 + 7, 1e9 + 13, 1e9 + 16};
  EXPECT_NEAR(sylva::stddev(v), std::sqrt(30.0), 1e-9);
  EXPECT_DOUBLE_EQ(sylva::mean(v), 1e9 + 10);
}

TEST(Samples, AccumulatesAndSummarises) {
  sylva::Samples s;
  EXPECT_TRUE(s.empty());
  for (double x : one_to(100)) s.add(x);
  EXPECT_EQ(s.count(), 100u);
  EXPECT_DOUBLE_EQ(s.summary().p99, 99.01);
  s.clear();
  EXPECT_EQ(s.summary().count, 0u);
}

// Only bounds that hold however long the machine stalls us: sleep_for waits at least its time,
// and a watch started later reads less than one started earlier, read after it.
TEST(Timer, StopwatchMeasuresSleep) {
  sylva::Stopwatch w;
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const double ms = w.elapsed_ms();
  EXPECT_GE(ms, 20.0);
  const double s = w.elapsed_s();
  EXPECT_GE(s, ms * 1e-3);
  const double later_ms = w.elapsed_ms();
  EXPECT_LE(s, later_ms * 1e-3);
  // Each pair is read in order: the watch under test first, the earlier-started one after it.
  const sylva::Stopwatch before_lap;
  const double lap = w.lap_ms();
  EXPECT_GE(lap, ms);
  const double since_lap = w.elapsed_ms();
  EXPECT_LE(since_lap, before_lap.elapsed_ms()) << "lap_ms restarts the watch";
  const sylva::Stopwatch before_restart;
  w.restart();
  const double since_restart = w.elapsed_ms();
  EXPECT_LE(since_restart, before_restart.elapsed_ms()) << "restart restarts the watch";
}

TEST(Timer, ElapsedIsMonotonic) {
  sylva::Stopwatch w;
  double last = 0.0;
  for (int i = 0; i < 1000; ++i) {
    const double now = w.elapsed_ms();
    ASSERT_GE(now, last);
    last = now;
  }
}

TEST(Timer, ScopedTimerAddsOneSample) {
  sylva::Samples samples;
  sylva::RunningStats running;
  double total_ms = 0.0;
  for (int i = 0; i < 3; ++i) {
    sylva::ScopedTimer a(samples);
    sylva::ScopedTimer b(running);
    sylva::ScopedTimerMs c(total_ms);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_EQ(samples.count(), 3u);
  EXPECT_EQ(running.count(), 3u);
  for (double ms : samples.values()) EXPECT_GE(ms, 2.0);
  EXPECT_GE(running.min(), 2.0);
  EXPECT_GE(total_ms, 6.0);
}

}  // namespace
