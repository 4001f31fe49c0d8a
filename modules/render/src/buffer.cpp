// DSA buffers (buffer.hpp).
#include <sylva/render/buffer.hpp>

#include <sylva/core/assert.hpp>

#include <algorithm>

namespace sylva::render {

Buffer Buffer::immutable(std::size_t bytes, const void* data, bool updatable) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  Buffer b;
  b.handle_ = GlHandle<BufferDeleter>(id);
  b.size_ = bytes;
  b.immutable_ = true;
  b.updatable_ = updatable;
  b.memory_ = GpuMemoryRecord(GpuMemoryKind::kBuffer, bytes);
  // Zero-sized storage is invalid in GL; keep one byte so the name is still a valid buffer.
  glNamedBufferStorage(id, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 1)), bytes > 0 ? data : nullptr,
                       updatable ? GL_DYNAMIC_STORAGE_BIT : 0);
  return b;
}

Buffer Buffer::dynamic(std::size_t bytes, GLenum usage) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  Buffer b;
  b.handle_ = GlHandle<BufferDeleter>(id);
  b.size_ = bytes;
  b.usage_ = usage;
  b.memory_ = GpuMemoryRecord(GpuMemoryKind::kBuffer, bytes);
  glNamedBufferData(id, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 1)), nullptr, usage);
  return b;
}

void Buffer::update(std::size_t offset, std::size_t bytes, const void* data) {
  SYLVA_ASSERT(handle_, "update on an empty buffer");
  SYLVA_ASSERT(!immutable_ || updatable_, "buffer {} is immutable and not updatable", id());
  SYLVA_ASSERT(offset + bytes <= size_, "offset={} bytes={} size={}", offset, bytes, size_);
  if (bytes == 0) return;
  glNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}

void Buffer::upload(std::size_t bytes, const void* data) {
  SYLVA_ASSERT(handle_ && !immutable_, "upload needs a dynamic buffer (id={})", id());
  if (bytes > size_) {
    const std::size_t capacity = std::max(bytes, size_ + size_ / 2);
    glNamedBufferData(id(), static_cast<GLsizeiptr>(capacity), nullptr, usage_);
    size_ = capacity;
    memory_.set_bytes(capacity);
  }
  if (bytes > 0) glNamedBufferSubData(id(), 0, static_cast<GLsizeiptr>(bytes), data);
}

void Buffer::read(std::size_t offset, std::size_t bytes, void* out) const {
  SYLVA_ASSERT(offset + bytes <= size_, "offset={} bytes={} size={}", offset, bytes, size_);
  if (bytes == 0) return;
  glGetNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), out);
}

void Buffer::bind_base(GLenum target, GLuint index) const { glBindBufferBase(target, index, id()); }
void Buffer::bind(GLenum target) const { glBindBuffer(target, id()); }

}  // namespace sylva::render
