#version 450 core
// sylva-bench built-in ground: a regular grid of the fBm height field, drawn camera-relative.
layout(location = 0) in vec3 a_position;  // metres, relative to the mesh origin (world 0,0,0)
layout(location = 1) in vec3 a_normal;    // from the full-detail noise, independent of the grid

uniform mat4 u_view_projection;  // projection * rotation-only view
uniform mat4 u_model;            // translate(origin - camera), subtracted in double on the CPU

out vec3 v_rel_position;
out vec3 v_normal;
out float v_height;

void main() {
  vec4 rel = u_model * vec4(a_position, 1.0);
  v_rel_position = rel.xyz;
  v_normal = a_normal;
  v_height = a_position.y;
  gl_Position = u_view_projection * rel;
}
