#version 450 core
// grass/draw_batches.comp: turns one chunk's cull count into indirect sub-draws of at most
// u_batch blades each, for glMultiDrawArraysIndirect (why: blades_per_draw() in
// <sylva/grass/culling.hpp>, llvmpipe breaks past 65,536 tessellated vertices per draw).
// Command k draws visible[k * u_batch, ...); commands past the count draw nothing. The count
// is clamped to the visible list's capacity, so the blade shaders never read past its end.
#include "grass/blade.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = GRASS_COMMAND_BINDING) readonly buffer Command { GRASS_COMMAND_MEMBERS };
layout(std430, binding = GRASS_BATCHES_BINDING) writeonly buffer Batches {
  uvec4 batches[];  // DrawArraysIndirectCommand: count, instance count, first, base instance
};

uniform uint u_batch;        // blades per sub-draw, >= 1
uniform uint u_batch_count;  // commands to write (the multi-draw's drawcount)

void main() {
  uint visible = min(draw_count, capacity);
  for (uint k = gl_LocalInvocationID.x; k < u_batch_count; k += gl_WorkGroupSize.x) {
    uint first = k * u_batch;
    uint count = first < visible ? min(u_batch, visible - first) : 0u;
    batches[k] = uvec4(count, 1u, first, 0u);
  }
}
