#pragma once
// Whether the host bound the render core's shadow block (render::ShadowMaps::bind()). Receivers
// read the SylvaShadows block only then: a shader reading an unbound uniform block gets
// undefined data (llvmpipe returns garbage after the block's buffer was deleted), which would
// shadow grass at random in hosts without shadow maps (tools, benchmarks).

#include <sylva/render/shadow_maps.hpp>

#include <epoxy/gl.h>

namespace sylva::grass::detail {

inline bool shadow_block_bound() {
  GLint buffer = 0;
  glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, render::kShadowUniformBinding, &buffer);
  return buffer != 0;
}

}  // namespace sylva::grass::detail
