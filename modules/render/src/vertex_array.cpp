// DSA vertex arrays (vertex_array.hpp).
#include <sylva/render/vertex_array.hpp>

namespace sylva::render {

VertexArray VertexArray::create() {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  VertexArray v;
  v.handle_ = GlHandle<VertexArrayDeleter>(id);
  return v;
}

void VertexArray::attribute(GLuint location, GLuint binding, GLint components, GLenum type,
                            std::size_t relative_offset, bool normalized) {
  glEnableVertexArrayAttrib(id(), location);
  glVertexArrayAttribFormat(id(), location, components, type, normalized ? GL_TRUE : GL_FALSE,
                            static_cast<GLuint>(relative_offset));
  glVertexArrayAttribBinding(id(), location, binding);
}

void VertexArray::attribute_int(GLuint location, GLuint binding, GLint components, GLenum type,
                                std::size_t relative_offset) {
  glEnableVertexArrayAttrib(id(), location);
  glVertexArrayAttribIFormat(id(), location, components, type, static_cast<GLuint>(relative_offset));
  glVertexArrayAttribBinding(id(), location, binding);
}

void VertexArray::binding_divisor(GLuint binding, GLuint divisor) {
  glVertexArrayBindingDivisor(id(), binding, divisor);
}

void VertexArray::vertex_buffer(GLuint binding, const Buffer& buffer, std::size_t stride, std::size_t offset) {
  glVertexArrayVertexBuffer(id(), binding, buffer.id(), static_cast<GLintptr>(offset), static_cast<GLsizei>(stride));
}

void VertexArray::index_buffer(const Buffer& buffer) { glVertexArrayElementBuffer(id(), buffer.id()); }

void VertexArray::bind() const { glBindVertexArray(id()); }

}  // namespace sylva::render
