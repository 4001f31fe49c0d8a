#pragma once
// Small statistics for measurements (frame times, benchmark samples): mean, median,
// percentiles, min/max, standard deviation, and accumulators.
//
// Conventions (tested in stats_test):
//  - Empty input gives NaN for every statistic (a mean of nothing is undefined; NaN shows up as
//    null in JSON instead of a plausible-looking 0). Check count first when that matters.
//  - A NaN sample makes every order statistic and moment NaN (sorting with NaN is undefined, and
//    a NaN timing is a broken measurement that must not be averaged away).
//  - percentile(p) interpolates linearly between closest ranks (Hyndman & Fan type 7, the
//    default of NumPy and R): h = (n - 1) * p / 100, x[floor h] + (h - floor h) *
//    (x[floor h + 1] - x[floor h]) over the sorted samples. So p50 of 1..100 is 50.5 and p99 is
//    99.01; p0 is the minimum and p100 the maximum.
//  - stddev is the sample standard deviation (divides by n - 1); 0 for a single sample.

#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <limits>
#include <span>
#include <vector>

namespace sylva {

double mean(std::span<const double> samples);
double median(std::span<const double> samples);
// p in [0, 100] (asserted).
double percentile(std::span<const double> samples, double p);
double min_value(std::span<const double> samples);
double max_value(std::span<const double> samples);
double stddev(std::span<const double> samples);

struct SampleSummary {
  std::size_t count = 0;
  double mean = std::numeric_limits<double>::quiet_NaN();
  double stddev = std::numeric_limits<double>::quiet_NaN();
  double min = std::numeric_limits<double>::quiet_NaN();
  double p50 = std::numeric_limits<double>::quiet_NaN();
  double p90 = std::numeric_limits<double>::quiet_NaN();
  double p99 = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();
};
// All of the above with one sort.
SampleSummary summarize(std::span<const double> samples);
// {"count", "mean", "stddev", "min", "p50", "p90", "p99", "max"}; NaN becomes null.
void to_json(nlohmann::json& j, const SampleSummary& s);

// O(1)-memory accumulator (Welford's algorithm: numerically stable for long runs of nearly equal
// values such as frame times). No percentiles; use Samples for those.
class RunningStats {
 public:
  void add(double x);
  void merge(const RunningStats& other);  // as if other's samples had been added here
  void reset() { *this = RunningStats(); }

  std::size_t count() const { return count_; }
  double mean() const;      // NaN when empty
  double variance() const;  // sample variance (n - 1); 0 for one sample, NaN when empty
  double stddev() const;
  double min() const;       // NaN when empty
  double max() const;
  double sum() const { return has_nan_ ? std::numeric_limits<double>::quiet_NaN() : sum_; }

 private:
  std::size_t count_ = 0;
  double mean_ = 0.0;
  double m2_ = 0.0;
  double sum_ = 0.0;
  double min_ = std::numeric_limits<double>::infinity();
  double max_ = -std::numeric_limits<double>::infinity();
  bool has_nan_ = false;
};

// Keeps every sample (for percentiles). add() is amortised O(1).
class Samples {
 public:
  void add(double x) { values_.push_back(x); }
  void reserve(std::size_t n) { values_.reserve(n); }
  void clear() { values_.clear(); }
  std::size_t count() const { return values_.size(); }
  bool empty() const { return values_.empty(); }
  std::span<const double> values() const { return values_; }
  SampleSummary summary() const { return summarize(values_); }

 private:
  std::vector<double> values_;
};

}  // namespace sylva
