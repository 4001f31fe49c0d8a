#pragma once
// Move-only owner of one GL object name. Deleter is a plain function pointer-like functor so
// every RAII type in render (buffers, textures, ...) has the same move semantics: moved-from
// objects hold 0 and destroying 0 does nothing. GL objects must be destroyed with their
// context current; destroy GL objects before the GlContext.

#include <epoxy/gl.h>

#include <utility>

namespace sylva::render {

template <class Deleter>
class GlHandle {
 public:
  GlHandle() = default;
  explicit GlHandle(GLuint id) : id_(id) {}
  GlHandle(GlHandle&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  GlHandle& operator=(GlHandle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  GlHandle(const GlHandle&) = delete;
  GlHandle& operator=(const GlHandle&) = delete;
  ~GlHandle() { reset(); }

  GLuint get() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_ != 0) Deleter{}(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

}  // namespace sylva::render
