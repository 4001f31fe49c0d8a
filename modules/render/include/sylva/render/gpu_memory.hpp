#pragma once
// Tracked GPU memory (issue #20, the memory metric of seed 002 Tab 3.5/3.7/4.10/4.11): every
// render::Buffer and render::Texture records the bytes of its storage under an owner and a kind,
// so a frame report can say how much GPU memory each module holds, split into buffers, textures
// and render targets, without asking the driver (GL has no portable query for it).
//
// Owner: the innermost GpuMemoryOwner scope alive on the allocating thread when the storage is
// created ("grass", "terrain", ...; the scene opens one around each module's build, update and
// draw), else "other". Bytes are what the storage needs by its size and internal format
// (texel_bytes below; mip chains counted level by level, multisample textures times their
// samples), not the driver's padding or alignment: a lower bound, exact for buffers.
//
// Thread-safety: counters are atomic; scopes are per thread. GL objects are created on the GL
// thread, so in practice everything runs there.

#include <epoxy/gl.h>

#include <cstdint>
#include <map>
#include <string>
#include <string_view>

namespace sylva::render {

enum class GpuMemoryKind : std::uint8_t { kBuffer = 0, kTexture = 1, kRenderTarget = 2 };
inline constexpr int kGpuMemoryKinds = 3;
const char* gpu_memory_kind_name(GpuMemoryKind kind);  // "buffers", "textures", "render_targets"

// Bytes one texel of `internal_format` takes (GL_RGB8 and other 3-channel formats count as 4,
// as drivers store them; unknown formats count 16, the widest).
std::uint64_t texel_bytes(GLenum internal_format);

// Sets the owner of GPU storage created on this thread while it lives; nests (the innermost
// wins). `name` is copied; an empty name means "other".
class GpuMemoryOwner {
 public:
  explicit GpuMemoryOwner(std::string_view name);
  ~GpuMemoryOwner();
  GpuMemoryOwner(const GpuMemoryOwner&) = delete;
  GpuMemoryOwner& operator=(const GpuMemoryOwner&) = delete;

 private:
  int previous_ = 0;
};

// One allocation's entry: counted from construction (or set_bytes) until destruction. Move-only;
// a moved-from record counts nothing. Buffer and Texture hold one each.
class GpuMemoryRecord {
 public:
  GpuMemoryRecord() = default;
  GpuMemoryRecord(GpuMemoryKind kind, std::uint64_t bytes);  // owner: the current scope
  GpuMemoryRecord(GpuMemoryRecord&& other) noexcept;
  GpuMemoryRecord& operator=(GpuMemoryRecord&& other) noexcept;
  ~GpuMemoryRecord();

  void set_bytes(std::uint64_t bytes);  // storage re-specified (a dynamic buffer that grew)
  void set_kind(GpuMemoryKind kind);    // a texture turned into a render target attachment
  std::uint64_t bytes() const { return bytes_; }

 private:
  void release();
  int owner_ = -1;  // index into the owner table; -1 = nothing counted
  GpuMemoryKind kind_ = GpuMemoryKind::kBuffer;
  std::uint64_t bytes_ = 0;
};

struct GpuMemoryUsage {
  std::uint64_t bytes[kGpuMemoryKinds] = {0, 0, 0};  // now, by GpuMemoryKind
  std::uint64_t peak_total = 0;                       // largest total this owner ever held
  std::uint64_t total() const { return bytes[0] + bytes[1] + bytes[2]; }
};

// Every owner that ever allocated, with its current bytes by kind and its peak.
std::map<std::string, GpuMemoryUsage> gpu_memory_usage();
// Current bytes of all owners together, and the largest that total has been.
std::uint64_t gpu_memory_total();
std::uint64_t gpu_memory_peak_total();

}  // namespace sylva::render
