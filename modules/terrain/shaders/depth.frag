#version 450 core
// terrain/depth.frag: shadow-map and depth-only passes (depth comes from chunk.vert).
in vec3 v_rel;
in vec2 v_grid;
in float v_morph;
uniform ivec2 u_field_size;
void main() {
  if (v_grid.x > float(u_field_size.x - 1) + 1e-3 || v_grid.y > float(u_field_size.y - 1) + 1e-3) discard;
}
