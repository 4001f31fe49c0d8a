#pragma once
// GPU measurements without pipeline stalls (DESIGN.md §2 "Measurements are first-class").
//
// A PassQuery measures one named piece of GPU work per frame: GPU time from two GL_TIMESTAMP
// queries (timestamps nest, so a module's scope may sit inside a pass's scope), and optionally
// GL_PRIMITIVES_GENERATED and GL_SAMPLES_PASSED (these do not nest: at most one counting scope
// is active at a time, asserted). Each frame uses the next slot of a ring (the slot gets fresh
// query objects each time: re-begun objects gave wrong counts on llvmpipe);
// poll() reads only slots whose results are available (GL_QUERY_RESULT_AVAILABLE), so results
// arrive a few frames late and the CPU never waits for the GPU. wait_all() is the one
// deliberate stall, for tests and the end of a benchmark run.

#include <sylva/render/gl_handle.hpp>

#include <epoxy/gl.h>

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace sylva::render {

// Counters for one pass (or one module within a pass) in one frame. GPU values come from
// queries; draw_calls, instances and triangles are counted by the code that issues the draws.
struct PassStats {
  double gpu_ms = 0.0;             // GPU time between the scope's begin and end [ms]
  double sync_ms = 0.0;            // wall time with glFinish around the scope [ms]; only filled
                                   // by FrameProfiler in synchronous mode (see below)
  std::uint64_t primitives = 0;    // GL_PRIMITIVES_GENERATED (after tessellation/geometry)
  std::uint64_t samples = 0;       // GL_SAMPLES_PASSED (fragments that passed depth/stencil)
  std::uint64_t triangles = 0;     // submitted by the CPU side
  std::uint64_t draw_calls = 0;
  std::uint64_t instances = 0;

  PassStats& operator+=(const PassStats& o);
};

// One frame's statistics: CPU time of the frame and per-pass records (by pass/module name).
struct FrameStats {
  std::uint64_t frame = 0;
  double cpu_ms = 0.0;
  double gpu_ms = 0.0;  // sum of the top-level passes
  std::map<std::string, PassStats> passes;
};

struct QueryDeleter {
  void operator()(GLuint id) const { glDeleteQueries(1, &id); }
};

struct PassQueryResult {
  std::uint64_t frame = 0;  // the frame number given to begin()
  double gpu_ms = 0.0;
  std::uint64_t primitives = 0;  // 0 unless counters were on
  std::uint64_t samples = 0;
};

class PassQuery {
 public:
  static constexpr int kRingSize = 6;  // frames in flight before a slot is reused

  // counters: also count primitives generated and samples passed (non-nesting).
  static PassQuery create(bool counters = true);
  PassQuery() = default;

  // Brackets GPU work. begin() on a slot whose previous result was never read drops that
  // result (counted in dropped()) rather than waiting.
  void begin(std::uint64_t frame);
  void end();
  bool active() const { return active_; }

  // Every result that completed since the last call, oldest first. Never waits unless `wait`
  // (which stalls until all outstanding slots are done).
  std::vector<PassQueryResult> collect(bool wait = false);
  // Newest result whose queries have completed, if any new one completed since the last call.
  // Never waits.
  std::optional<PassQueryResult> poll();
  // Waits for every outstanding slot (stalls!) and returns the newest result.
  std::optional<PassQueryResult> wait_all();

  std::uint64_t dropped() const { return dropped_; }
  bool counters() const { return counters_; }

 private:
  struct Slot {
    GlHandle<QueryDeleter> t0, t1, primitives, samples;
    std::uint64_t frame = 0;
    std::uint64_t order = 0;
    bool pending = false;
  };
  bool read_slot(Slot& slot, bool wait, PassQueryResult& out);
  std::uint64_t begun_ = 0;  // begin() calls, orders slots for collect()

  std::array<Slot, kRingSize> slots_{};
  int next_ = 0;
  int current_ = -1;
  bool active_ = false;
  bool counters_ = true;
  bool created_ = false;
  std::uint64_t dropped_ = 0;
};

// Per-frame profiler: named PassQuery scopes plus CPU frame time. Names are created on first
// use. Typical frame:
//   profiler.begin_frame();
//   profiler.begin("opaque"); ...draws...; profiler.end("opaque");
//   profiler.end_frame();
//   if (auto s = profiler.latest()) ...   // a few frames old
class FrameProfiler {
 public:
  // Synchronous mode wraps every scope in glFinish and records its wall time as sync_ms. It
  // stalls the pipeline, so it is for benchmarks only, and it exists because timer queries on
  // llvmpipe underestimate: its timestamps are taken per tile by the rasteriser threads, and a
  // 1280x720 sky pass measured 12-40 ms by GL_TIME_ELAPSED took about 130 ms of wall time.
  void set_synchronous(bool on) { synchronous_ = on; }
  bool synchronous() const { return synchronous_; }

  void begin_frame();
  // counters: whether this scope counts primitives/samples (only one counting scope may be
  // open at a time; nested module scopes inside a counting pass pass false).
  void begin(const std::string& name, bool counters = true);
  void end(const std::string& name);
  // Adds CPU-side counts (draw calls, instances, triangles) to the current frame's record.
  void add_cpu_counts(const std::string& name, const PassStats& counts);
  void end_frame();

  // The newest frame whose GPU results have all arrived (never waits).
  const std::optional<FrameStats>& latest() const { return latest_; }
  // Stalls until every outstanding query is done, then returns the newest complete frame.
  std::optional<FrameStats> flush();

  std::uint64_t frame() const { return frame_; }

 private:
  struct Pending {
    FrameStats stats;
    std::size_t awaiting = 0;             // scopes whose GPU results are still missing
    std::vector<std::string> top_level;   // scopes begun while no other was open
    bool ended = false;
  };
  void collect(bool wait);

  std::map<std::string, PassQuery> queries_;
  std::map<std::uint64_t, Pending> in_flight_;  // by frame number
  std::vector<std::string> open_;              // scopes currently open, innermost last
  std::vector<double> open_start_ms_;          // synchronous mode: wall clock at begin()
  bool synchronous_ = false;
  std::uint64_t frame_ = 0;
  double frame_start_ms_ = 0.0;
  std::optional<FrameStats> latest_;
};

}  // namespace sylva::render
