#pragma once
// GPU buffers, DSA style (GL 4.5). Two kinds, because they are used differently:
//  - immutable: glNamedBufferStorage once, contents fixed or updated only through
//    GL_DYNAMIC_STORAGE_BIT (flag `updatable`); the driver can place it optimally.
//  - dynamic: re-specified with glNamedBufferData when it must grow (streamed per-frame data,
//    instance lists). Capacity grows geometrically, never shrinks.
// Sizes are in bytes. Bind points are the caller's business (bind_base helpers below).

#include <sylva/render/gl_handle.hpp>
#include <sylva/render/gpu_memory.hpp>

#include <epoxy/gl.h>

#include <cstddef>
#include <span>

namespace sylva::render {

struct BufferDeleter {
  void operator()(GLuint id) const { glDeleteBuffers(1, &id); }
};

class Buffer {
 public:
  Buffer() = default;

  // Immutable storage of `bytes` bytes initialised from `data` (may be null for uninitialised).
  // updatable = GL_DYNAMIC_STORAGE_BIT so update() works; otherwise the content is fixed.
  static Buffer immutable(std::size_t bytes, const void* data, bool updatable = false);
  template <class T>
  static Buffer immutable(std::span<const T> data, bool updatable = false) {
    return immutable(data.size_bytes(), data.data(), updatable);
  }

  // Mutable storage (glNamedBufferData with `usage`, e.g. GL_DYNAMIC_DRAW / GL_STREAM_DRAW).
  static Buffer dynamic(std::size_t bytes, GLenum usage = GL_DYNAMIC_DRAW);

  GLuint id() const { return handle_.get(); }
  std::size_t size() const { return size_; }
  bool is_immutable() const { return immutable_; }
  explicit operator bool() const { return static_cast<bool>(handle_); }

  // Writes bytes at offset; offset + bytes <= size() (asserted). Immutable buffers need
  // updatable = true.
  void update(std::size_t offset, std::size_t bytes, const void* data);
  template <class T>
  void update(std::span<const T> data, std::size_t offset = 0) {
    update(offset, data.size_bytes(), data.data());
  }

  // Dynamic buffers only: makes room for `bytes` (orphaning the old store, content is lost
  // when it grows) and writes data at offset 0. Grows capacity by at least 1.5x.
  void upload(std::size_t bytes, const void* data);
  template <class T>
  void upload(std::span<const T> data) { upload(data.size_bytes(), data.data()); }

  // Reads bytes back (stalls; for tests and tools).
  void read(std::size_t offset, std::size_t bytes, void* out) const;

  void bind_base(GLenum target, GLuint index) const;  // GL_UNIFORM_BUFFER, GL_SHADER_STORAGE_BUFFER
  void bind(GLenum target) const;                     // e.g. GL_DRAW_INDIRECT_BUFFER

 private:
  GlHandle<BufferDeleter> handle_;
  GpuMemoryRecord memory_;  // its bytes in the tracked GPU memory (gpu_memory.hpp)
  std::size_t size_ = 0;
  bool immutable_ = false;
  bool updatable_ = false;
  GLenum usage_ = GL_DYNAMIC_DRAW;
};

}  // namespace sylva::render
