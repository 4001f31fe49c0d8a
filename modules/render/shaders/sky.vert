#version 450 core
// Full-screen triangle at the far plane (reversed-Z depth 0) with the world view direction.
#include "render/lib/common.glsl"

uniform mat4 u_inv_view_projection;  // inverse(projection * view_rotation)

out vec3 v_direction;

void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
  gl_Position = vec4(p, 0.0, 1.0);
  // A point on the near plane (clip z = w); the camera sits at the origin of this space.
  vec4 near_point = u_inv_view_projection * vec4(p, 1.0, 1.0);
  v_direction = near_point.xyz / near_point.w;
}
