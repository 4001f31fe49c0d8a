// Asynchronous GPU timer and counter queries (queries.hpp).
#include <sylva/render/queries.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/core/log.hpp>

#include <algorithm>
#include <chrono>

namespace sylva::render {
namespace {

// GL allows one active query per counting target; nesting would be a GL error.
int g_counting_scopes = 0;

GLuint new_query(GLenum target) {
  GLuint id = 0;
  glCreateQueries(target, 1, &id);
  return id;
}

bool available(GLuint query) {
  GLuint ready = GL_FALSE;
  glGetQueryObjectuiv(query, GL_QUERY_RESULT_AVAILABLE, &ready);
  return ready == GL_TRUE;
}

std::uint64_t result_u64(GLuint query) {
  GLuint64 v = 0;
  glGetQueryObjectui64v(query, GL_QUERY_RESULT, &v);
  return v;
}

double now_ms() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double, std::milli>(clock::now().time_since_epoch()).count();
}

}  // namespace

PassStats& PassStats::operator+=(const PassStats& o) {
  gpu_ms += o.gpu_ms;
  sync_ms += o.sync_ms;
  primitives += o.primitives;
  samples += o.samples;
  triangles += o.triangles;
  draw_calls += o.draw_calls;
  instances += o.instances;
  return *this;
}

PassQuery PassQuery::create(bool counters) {
  PassQuery q;
  q.counters_ = counters;
  q.created_ = true;  // query objects are made per use in begin()
  return q;
}

void PassQuery::begin(std::uint64_t frame) {
  SYLVA_ASSERT(created_, "PassQuery used before create()");
  SYLVA_ASSERT(!active_, "PassQuery::begin twice without end (frame {})", frame);
  Slot& slot = slots_[static_cast<std::size_t>(next_)];
  if (slot.pending) {
    // The GPU is kRingSize frames behind or nobody polls: drop the old result, never wait.
    slot.pending = false;
    ++dropped_;
  }
  if (counters_) {
    SYLVA_ASSERT(g_counting_scopes == 0, "a counting PassQuery is already open (counters do not nest), frame {}",
                 frame);
    ++g_counting_scopes;
  }
  // Fresh query objects for every use. Re-begun counter queries on Mesa llvmpipe (22.3)
  // came back late and with samples of later frames added in (tests/queries_gl_test.cpp
  // RingDeliversResultsWithoutWaiting caught it); new objects are cheap and always correct.
  if (counters_) {
    slot.primitives = GlHandle<QueryDeleter>(new_query(GL_PRIMITIVES_GENERATED));
    slot.samples = GlHandle<QueryDeleter>(new_query(GL_SAMPLES_PASSED));
  }
  slot.t0 = GlHandle<QueryDeleter>(new_query(GL_TIMESTAMP));
  slot.t1 = GlHandle<QueryDeleter>(new_query(GL_TIMESTAMP));
  slot.frame = frame;
  slot.order = ++begun_;
  glQueryCounter(slot.t0.get(), GL_TIMESTAMP);
  if (counters_) {
    glBeginQuery(GL_PRIMITIVES_GENERATED, slot.primitives.get());
    glBeginQuery(GL_SAMPLES_PASSED, slot.samples.get());
  }
  current_ = next_;
  next_ = (next_ + 1) % kRingSize;
  active_ = true;
}

void PassQuery::end() {
  SYLVA_ASSERT(active_, "PassQuery::end without begin");
  Slot& slot = slots_[static_cast<std::size_t>(current_)];
  if (counters_) {
    glEndQuery(GL_SAMPLES_PASSED);
    glEndQuery(GL_PRIMITIVES_GENERATED);
    --g_counting_scopes;
  }
  glQueryCounter(slot.t1.get(), GL_TIMESTAMP);
  slot.pending = true;
  active_ = false;
}

bool PassQuery::read_slot(Slot& slot, bool wait, PassQueryResult& out) {
  if (!slot.pending) return false;
  if (!wait) {
    if (!available(slot.t1.get()) || !available(slot.t0.get())) return false;
    if (counters_ && (!available(slot.primitives.get()) || !available(slot.samples.get()))) return false;
  }
  const std::uint64_t t0 = result_u64(slot.t0.get());
  const std::uint64_t t1 = result_u64(slot.t1.get());
  out.frame = slot.frame;
  out.gpu_ms = t1 >= t0 ? static_cast<double>(t1 - t0) * 1.0e-6 : 0.0;
  out.primitives = counters_ ? result_u64(slot.primitives.get()) : 0;
  out.samples = counters_ ? result_u64(slot.samples.get()) : 0;
  slot.pending = false;
  return true;
}

std::vector<PassQueryResult> PassQuery::collect(bool wait) {
  std::vector<Slot*> order;
  for (Slot& s : slots_) {
    // A slot still inside begin/end is not finished yet.
    if (s.pending && !(active_ && &s == &slots_[static_cast<std::size_t>(current_)])) order.push_back(&s);
  }
  std::sort(order.begin(), order.end(), [](const Slot* a, const Slot* b) { return a->order < b->order; });
  std::vector<PassQueryResult> results;
  for (Slot* s : order) {
    PassQueryResult r;
    if (read_slot(*s, wait, r)) {
      results.push_back(r);
    } else if (!wait) {
      break;  // later slots finish later; keep the order
    }
  }
  return results;
}

std::optional<PassQueryResult> PassQuery::poll() {
  std::vector<PassQueryResult> r = collect(false);
  if (r.empty()) return std::nullopt;
  return r.back();
}

std::optional<PassQueryResult> PassQuery::wait_all() {
  std::vector<PassQueryResult> r = collect(true);
  if (r.empty()) return std::nullopt;
  return r.back();
}

void FrameProfiler::begin_frame() {
  SYLVA_ASSERT(open_.empty(), "begin_frame with {} scope(s) still open", open_.size());
  ++frame_;
  frame_start_ms_ = now_ms();
  Pending& p = in_flight_[frame_];
  p.stats.frame = frame_;
}

void FrameProfiler::begin(const std::string& name, bool counters) {
  auto it = queries_.find(name);
  if (it == queries_.end()) it = queries_.emplace(name, PassQuery::create(counters)).first;
  Pending& p = in_flight_[frame_];
  if (open_.empty() && std::find(p.top_level.begin(), p.top_level.end(), name) == p.top_level.end()) {
    p.top_level.push_back(name);
  }
  p.stats.passes[name];  // the record exists even before GPU results arrive
  open_.push_back(name);
  if (synchronous_) glFinish();
  open_start_ms_.push_back(now_ms());
  it->second.begin(frame_);
}

void FrameProfiler::end(const std::string& name) {
  SYLVA_ASSERT(!open_.empty() && open_.back() == name, "end(\"{}\") does not match the innermost open scope", name);
  open_.pop_back();
  queries_.at(name).end();
  Pending& p = in_flight_[frame_];
  ++p.awaiting;
  if (synchronous_) {
    glFinish();
    p.stats.passes[name].sync_ms += now_ms() - open_start_ms_.back();
  }
  open_start_ms_.pop_back();
}

void FrameProfiler::add_cpu_counts(const std::string& name, const PassStats& counts) {
  PassStats& s = in_flight_[frame_].stats.passes[name];
  s.triangles += counts.triangles;
  s.draw_calls += counts.draw_calls;
  s.instances += counts.instances;
}

void FrameProfiler::end_frame() {
  SYLVA_ASSERT(open_.empty(), "end_frame with {} scope(s) still open", open_.size());
  Pending& p = in_flight_[frame_];
  p.stats.cpu_ms = now_ms() - frame_start_ms_;
  p.ended = true;
  collect(false);
}

void FrameProfiler::collect(bool wait) {
  for (auto& [name, query] : queries_) {
    for (const PassQueryResult& r : query.collect(wait)) {
      auto it = in_flight_.find(r.frame);
      if (it == in_flight_.end()) continue;
      PassStats& s = it->second.stats.passes[name];
      s.gpu_ms += r.gpu_ms;
      s.primitives += r.primitives;
      s.samples += r.samples;
      if (it->second.awaiting > 0) --it->second.awaiting;
    }
  }
  // The newest ended frame with every result in becomes `latest`; older ones are done with.
  for (auto it = in_flight_.rbegin(); it != in_flight_.rend(); ++it) {
    Pending& p = it->second;
    if (!p.ended || p.awaiting > 0) continue;
    p.stats.gpu_ms = 0.0;
    for (const std::string& top : p.top_level) p.stats.gpu_ms += p.stats.passes[top].gpu_ms;
    if (!latest_ || latest_->frame < p.stats.frame) latest_ = p.stats;
    in_flight_.erase(in_flight_.begin(), it.base());
    break;
  }
  // Frames whose query slots were recycled before their results came can never complete.
  const std::uint64_t horizon = static_cast<std::uint64_t>(PassQuery::kRingSize) + 2;
  while (!in_flight_.empty() && in_flight_.begin()->first + horizon < frame_) in_flight_.erase(in_flight_.begin());
}

std::optional<FrameStats> FrameProfiler::flush() {
  SYLVA_ASSERT(open_.empty(), "flush with {} scope(s) still open", open_.size());
  collect(true);
  return latest_;
}

}  // namespace sylva::render
