#pragma once
// CPU timing on std::chrono::steady_clock (monotonic: never jumps with the wall clock).
// Milliseconds as double everywhere, the unit every Sylva stats record uses.
//
//   sylva::Samples update_ms;
//   { sylva::ScopedTimer t(update_ms); drawable.update(ctx); }   // adds one sample
//
// GPU time is measured with the render module's timer queries, not here.

#include <chrono>

namespace sylva {

class Stopwatch {
 public:
  using Clock = std::chrono::steady_clock;

  Stopwatch() : start_(Clock::now()) {}
  void restart() { start_ = Clock::now(); }
  // Milliseconds since construction or the last restart.
  double elapsed_ms() const { return std::chrono::duration<double, std::milli>(Clock::now() - start_).count(); }
  double elapsed_s() const { return elapsed_ms() * 1e-3; }
  // Returns elapsed_ms() and restarts: for consecutive laps without a gap.
  double lap_ms() {
    const Clock::time_point now = Clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - start_).count();
    start_ = now;
    return ms;
  }

 private:
  Clock::time_point start_;
};

// Anything with add(double ms): Samples, RunningStats.
template <class A>
concept SampleSink = requires(A& a, double ms) { a.add(ms); };

// Adds the milliseconds of its lifetime to a sink when it goes out of scope. The sink must
// outlive the timer. Not copyable or movable (a moved timer would add twice).
template <SampleSink A>
class ScopedTimer {
 public:
  explicit ScopedTimer(A& sink) : sink_(sink) {}
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;
  ~ScopedTimer() { sink_.add(watch_.elapsed_ms()); }

  double elapsed_ms() const { return watch_.elapsed_ms(); }

 private:
  A& sink_;
  Stopwatch watch_;
};

// Adds into a plain double (a per-frame total of several timed pieces).
class ScopedTimerMs {
 public:
  explicit ScopedTimerMs(double& total_ms) : total_(total_ms) {}
  ScopedTimerMs(const ScopedTimerMs&) = delete;
  ScopedTimerMs& operator=(const ScopedTimerMs&) = delete;
  ~ScopedTimerMs() { total_ += watch_.elapsed_ms(); }

 private:
  double& total_;
  Stopwatch watch_;
};

}  // namespace sylva
