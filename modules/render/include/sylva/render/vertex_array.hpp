#pragma once
// Vertex array objects, DSA style: attribute formats are declared once, buffers are attached
// to binding slots. Example (interleaved position + normal):
//   VertexArray vao;
//   vao.attribute(0, 0, 3, GL_FLOAT, offsetof(V, pos));
//   vao.attribute(1, 0, 3, GL_FLOAT, offsetof(V, normal));
//   vao.vertex_buffer(0, vbo, sizeof(V));
//   vao.index_buffer(ibo);

#include <sylva/render/buffer.hpp>
#include <sylva/render/gl_handle.hpp>

#include <epoxy/gl.h>

#include <cstddef>

namespace sylva::render {

struct VertexArrayDeleter {
  void operator()(GLuint id) const { glDeleteVertexArrays(1, &id); }
};

class VertexArray {
 public:
  // Creates the VAO (needs a current context).
  static VertexArray create();
  VertexArray() = default;

  GLuint id() const { return handle_.get(); }
  explicit operator bool() const { return static_cast<bool>(handle_); }

  // Float attribute `location` reading `components` values of `type` at `relative_offset`
  // bytes into each vertex of binding `binding`. normalized applies to integer types.
  void attribute(GLuint location, GLuint binding, GLint components, GLenum type,
                 std::size_t relative_offset, bool normalized = false);
  // Integer attribute (ivec/uvec in GLSL), glVertexArrayAttribIFormat.
  void attribute_int(GLuint location, GLuint binding, GLint components, GLenum type,
                     std::size_t relative_offset);
  // Per-instance stepping for a binding (divisor 0 = per vertex).
  void binding_divisor(GLuint binding, GLuint divisor);

  void vertex_buffer(GLuint binding, const Buffer& buffer, std::size_t stride, std::size_t offset = 0);
  void index_buffer(const Buffer& buffer);

  void bind() const;

 private:
  GlHandle<VertexArrayDeleter> handle_;
};

}  // namespace sylva::render
