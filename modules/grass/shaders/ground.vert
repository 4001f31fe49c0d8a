#version 450 core
// grass/ground.vert: the far ground layer, a lifted copy of the height field's surface.
layout(location = 0) in vec3 a_position;  // blade-set local
layout(location = 1) in vec3 a_normal;

uniform mat4 u_view_proj;
uniform vec3 u_origin_rel;

out vec3 g_local;
out vec3 g_rel_pos;
out vec3 g_normal;

void main() {
  g_local = a_position;
  g_rel_pos = a_position + u_origin_rel;
  g_normal = a_normal;
  gl_Position = u_view_proj * vec4(g_rel_pos, 1.0);
}
