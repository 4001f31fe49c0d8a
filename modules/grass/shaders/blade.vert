#version 450 core
// grass/blade.vert: one patch vertex per visible blade; the blade index comes from the list
// written by cull.comp (the draw is glDrawArraysIndirect with the count it produced).
#include "grass/blade.glsl"

layout(std430, binding = GRASS_VISIBLE_BINDING) readonly buffer Visible { uint visible[]; };

flat out uint v_blade;

void main() {
  v_blade = visible[gl_VertexID];
}
