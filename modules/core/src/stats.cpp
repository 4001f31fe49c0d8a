#include <sylva/core/stats.hpp>

#include <sylva/core/assert.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace sylva {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool has_nan(std::span<const double> samples) {
  return std::any_of(samples.begin(), samples.end(), [](double x) { return std::isnan(x); });
}

// Type-7 percentile over already sorted, NaN-free samples (see stats.hpp).
double sorted_percentile(std::span<const double> sorted, double p) {
  const double h = static_cast<double>(sorted.size() - 1) * p / 100.0;
  const std::size_t lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  const double t = h - static_cast<double>(lo);
  // Exact ranks and equal neighbours return the sample itself (also keeps an infinite neighbour
  // from turning 0 * inf into NaN).
  if (t == 0.0 || sorted[lo] == sorted[hi]) return sorted[lo];
  return sorted[lo] + t * (sorted[hi] - sorted[lo]);
}

std::vector<double> sorted_copy(std::span<const double> samples) {
  std::vector<double> v(samples.begin(), samples.end());
  std::sort(v.begin(), v.end());
  return v;
}

}  // namespace

double mean(std::span<const double> samples) {
  if (samples.empty()) return kNaN;
  // Compensated (Kahan) sum: frame-time runs can be long.
  double sum = 0.0;
  double c = 0.0;
  for (double x : samples) {
    const double y = x - c;
    const double t = sum + y;
    c = (t - sum) - y;
    sum = t;
  }
  return sum / static_cast<double>(samples.size());
}

double median(std::span<const double> samples) { return percentile(samples, 50.0); }

double percentile(std::span<const double> samples, double p) {
  SYLVA_ASSERT(p >= 0.0 && p <= 100.0, "percentile p={} is outside [0, 100]", p);
  if (samples.empty() || has_nan(samples)) return kNaN;
  const std::vector<double> sorted = sorted_copy(samples);
  return sorted_percentile(sorted, p);
}

double min_value(std::span<const double> samples) {
  if (samples.empty() || has_nan(samples)) return kNaN;
  return *std::min_element(samples.begin(), samples.end());
}

double max_value(std::span<const double> samples) {
  if (samples.empty() || has_nan(samples)) return kNaN;
  return *std::max_element(samples.begin(), samples.end());
}

double stddev(std::span<const double> samples) {
  if (samples.empty()) return kNaN;
  RunningStats r;
  for (double x : samples) r.add(x);
  return r.stddev();
}

SampleSummary summarize(std::span<const double> samples) {
  SampleSummary s;
  s.count = samples.size();
  if (samples.empty() || has_nan(samples)) return s;
  const std::vector<double> sorted = sorted_copy(samples);
  s.mean = mean(samples);
  s.stddev = stddev(samples);
  s.min = sorted.front();
  s.max = sorted.back();
  s.p50 = sorted_percentile(sorted, 50.0);
  s.p90 = sorted_percentile(sorted, 90.0);
  s.p99 = sorted_percentile(sorted, 99.0);
  return s;
}

void to_json(nlohmann::json& j, const SampleSummary& s) {
  const auto number = [](double x) -> nlohmann::json {
    if (std::isfinite(x)) return x;
    return nullptr;
  };
  j = nlohmann::json{{"count", s.count},  {"mean", number(s.mean)}, {"stddev", number(s.stddev)},
                     {"min", number(s.min)}, {"p50", number(s.p50)},   {"p90", number(s.p90)},
                     {"p99", number(s.p99)}, {"max", number(s.max)}};
}

void RunningStats::add(double x) {
  ++count_;
  if (std::isnan(x)) {
    has_nan_ = true;
    return;
  }
  sum_ += x;
  // Welford: mean and the sum of squared deviations updated without cancellation.
  const double delta = x - mean_;
  mean_ += delta / static_cast<double>(count_);
  m2_ += delta * (x - mean_);
  min_ = std::min(min_, x);
  max_ = std::max(max_, x);
}

void RunningStats::merge(const RunningStats& other) {
  if (other.count_ == 0) return;
  if (count_ == 0) {
    *this = other;
    return;
  }
  // Chan et al.'s parallel combination of two Welford states.
  const double n_a = static_cast<double>(count_);
  const double n_b = static_cast<double>(other.count_);
  const double n = n_a + n_b;
  const double delta = other.mean_ - mean_;
  mean_ += delta * n_b / n;
  m2_ += other.m2_ + delta * delta * n_a * n_b / n;
  count_ += other.count_;
  sum_ += other.sum_;
  min_ = std::min(min_, other.min_);
  max_ = std::max(max_, other.max_);
  has_nan_ = has_nan_ || other.has_nan_;
}

double RunningStats::mean() const { return count_ == 0 || has_nan_ ? kNaN : mean_; }

double RunningStats::variance() const {
  if (count_ == 0 || has_nan_) return kNaN;
  if (count_ == 1) return 0.0;
  return m2_ / static_cast<double>(count_ - 1);
}

double RunningStats::stddev() const { return std::sqrt(variance()); }

double RunningStats::min() const { return count_ == 0 || has_nan_ ? kNaN : min_; }

double RunningStats::max() const { return count_ == 0 || has_nan_ ? kNaN : max_; }

}  // namespace sylva
