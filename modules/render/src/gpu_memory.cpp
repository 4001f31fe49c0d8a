// Tracked GPU memory (gpu_memory.hpp).
#include <sylva/render/gpu_memory.hpp>

#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

namespace sylva::render {
namespace {

struct OwnerCounters {
  std::string name;
  std::array<std::atomic<std::uint64_t>, kGpuMemoryKinds> bytes{};
  std::atomic<std::uint64_t> peak{0};
};

// Owners are never removed, so an index stays valid; a deque-like vector of pointers keeps the
// counters at stable addresses while the table grows.
struct OwnerTable {
  std::mutex mutex;
  std::vector<std::unique_ptr<OwnerCounters>> owners;
  std::atomic<std::uint64_t> total{0};
  std::atomic<std::uint64_t> peak_total{0};
};

OwnerTable& table() {
  static OwnerTable t;
  return t;
}

// The scene opens a scope per module and pass every frame: look the name up without allocating;
// only a new owner (once per name and process) copies it.
int owner_index(std::string_view name) {
  const std::string_view key = name.empty() ? std::string_view("other") : name;
  OwnerTable& t = table();
  std::lock_guard lock(t.mutex);
  for (std::size_t i = 0; i < t.owners.size(); ++i) {
    if (t.owners[i]->name == key) return static_cast<int>(i);
  }
  t.owners.push_back(std::make_unique<OwnerCounters>());
  t.owners.back()->name = std::string(key);
  return static_cast<int>(t.owners.size() - 1);
}

OwnerCounters& counters(int owner) {
  OwnerTable& t = table();
  std::lock_guard lock(t.mutex);
  return *t.owners[static_cast<std::size_t>(owner)];
}

thread_local int current_owner = -1;  // -1: "other"

void raise_peak(std::atomic<std::uint64_t>& peak, std::uint64_t value) {
  std::uint64_t seen = peak.load();
  while (value > seen && !peak.compare_exchange_weak(seen, value)) {
  }
}

void add(int owner, GpuMemoryKind kind, std::uint64_t bytes) {
  OwnerCounters& c = counters(owner);
  c.bytes[static_cast<int>(kind)] += bytes;
  raise_peak(c.peak, c.bytes[0] + c.bytes[1] + c.bytes[2]);
  OwnerTable& t = table();
  raise_peak(t.peak_total, t.total += bytes);
}

void subtract(int owner, GpuMemoryKind kind, std::uint64_t bytes) {
  counters(owner).bytes[static_cast<int>(kind)] -= bytes;
  table().total -= bytes;
}

}  // namespace

const char* gpu_memory_kind_name(GpuMemoryKind kind) {
  switch (kind) {
    case GpuMemoryKind::kBuffer: return "buffers";
    case GpuMemoryKind::kTexture: return "textures";
    case GpuMemoryKind::kRenderTarget: return "render_targets";
  }
  return "?";
}

std::uint64_t texel_bytes(GLenum format) {
  switch (format) {
    case GL_R8: case GL_R8UI: case GL_R8I: return 1;
    case GL_RG8: case GL_R16: case GL_R16F: case GL_R16UI: case GL_DEPTH_COMPONENT16: return 2;
    case GL_RGB8: case GL_SRGB8: case GL_RGBA8: case GL_SRGB8_ALPHA8: case GL_R32F: case GL_R32UI: case GL_R32I:
    case GL_RG16: case GL_RG16F: case GL_R11F_G11F_B10F: case GL_RGB10_A2: case GL_DEPTH_COMPONENT32F:
    case GL_DEPTH_COMPONENT24: case GL_DEPTH24_STENCIL8: return 4;
    case GL_RGB16: case GL_RGBA16: case GL_RGB16F: case GL_RGBA16F: case GL_RG32F: case GL_RG32UI: return 8;
    default: return 16;
  }
}

GpuMemoryOwner::GpuMemoryOwner(std::string_view name) : previous_(current_owner) { current_owner = owner_index(name); }
GpuMemoryOwner::~GpuMemoryOwner() { current_owner = previous_; }

GpuMemoryRecord::GpuMemoryRecord(GpuMemoryKind kind, std::uint64_t bytes)
    : owner_(current_owner >= 0 ? current_owner : owner_index("")), kind_(kind), bytes_(bytes) {
  add(owner_, kind_, bytes_);
}

GpuMemoryRecord::GpuMemoryRecord(GpuMemoryRecord&& other) noexcept
    : owner_(other.owner_), kind_(other.kind_), bytes_(other.bytes_) {
  other.owner_ = -1;
  other.bytes_ = 0;
}

GpuMemoryRecord& GpuMemoryRecord::operator=(GpuMemoryRecord&& other) noexcept {
  if (this != &other) {
    release();
    owner_ = other.owner_;
    kind_ = other.kind_;
    bytes_ = other.bytes_;
    other.owner_ = -1;
    other.bytes_ = 0;
  }
  return *this;
}

GpuMemoryRecord::~GpuMemoryRecord() { release(); }

void GpuMemoryRecord::release() {
  if (owner_ >= 0) subtract(owner_, kind_, bytes_);
  owner_ = -1;
  bytes_ = 0;
}

void GpuMemoryRecord::set_bytes(std::uint64_t bytes) {
  if (owner_ < 0) return;
  subtract(owner_, kind_, bytes_);
  bytes_ = bytes;
  add(owner_, kind_, bytes_);
}

void GpuMemoryRecord::set_kind(GpuMemoryKind kind) {
  if (owner_ < 0) return;
  subtract(owner_, kind_, bytes_);
  kind_ = kind;
  add(owner_, kind_, bytes_);
}

std::map<std::string, GpuMemoryUsage> gpu_memory_usage() {
  std::map<std::string, GpuMemoryUsage> out;
  OwnerTable& t = table();
  std::lock_guard lock(t.mutex);
  for (const auto& c : t.owners) {
    GpuMemoryUsage& u = out[c->name];
    for (int k = 0; k < kGpuMemoryKinds; ++k) u.bytes[k] = c->bytes[static_cast<std::size_t>(k)].load();
    u.peak_total = c->peak.load();
  }
  return out;
}

std::uint64_t gpu_memory_total() { return table().total.load(); }
std::uint64_t gpu_memory_peak_total() { return table().peak_total.load(); }

}  // namespace sylva::render
