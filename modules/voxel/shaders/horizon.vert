#version 450 core
// The horizon skirt: a flat ring around the camera from u_skirt.x out to u_skirt.y blocks at
// height u_skirt.z below the camera (the lowest loaded block), drawn in the
// colour the world fades into (distance_fade.glsl). Seen from above it fills every direction
// below the horizon that would otherwise look past the world's edge into the void. 64 segments
// of two triangles each, generated from gl_VertexID.
uniform mat4 u_view_projection;  // camera-relative
uniform vec3 u_skirt;
out vec3 v_rel_pos;

const int kSegments = 64;
const ivec2 kCorners[6] = ivec2[](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));

void main() {
  int segment = gl_VertexID / 6;
  ivec2 c = kCorners[gl_VertexID % 6];
  float a = 6.28318531 * float(segment + c.x) / float(kSegments);
  float r = c.y == 0 ? u_skirt.x : u_skirt.y;
  v_rel_pos = vec3(cos(a) * r, u_skirt.z, sin(a) * r);
  gl_Position = u_view_projection * vec4(v_rel_pos, 1.0);
}
