#version 450 core
// grass/ground.vert: the ground layer, a lifted copy of the height field's surface. The lift
// grows with distance (u_lift_per_m) so the layer stays above a ground drawn with a coarser or
// differently split mesh: its mismatch in height is seen over ever fewer pixels far away, and a
// metre of lift at 2 km is a fraction of a pixel.
layout(location = 0) in vec3 a_position;  // blade-set local
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_color;     // field_color() at the vertex

uniform mat4 u_view_proj;
uniform vec3 u_origin_rel;
uniform float u_lift_per_m;

out vec3 g_local;
out vec3 g_rel_pos;
out vec3 g_normal;
out vec3 g_color;

void main() {
  vec3 rel = a_position + u_origin_rel;
  vec3 lifted = a_position + a_normal * (u_lift_per_m * length(rel));
  g_local = lifted;
  g_rel_pos = lifted + u_origin_rel;
  g_normal = a_normal;
  g_color = a_color;
  gl_Position = u_view_proj * vec4(g_rel_pos, 1.0);
}
