#version 450 core
// terrain/bounds.vert: chunk bounding-box lines (debug view), camera-relative positions.
layout(location = 0) in vec3 a_rel;
uniform mat4 u_view_projection;
void main() { gl_Position = u_view_projection * vec4(a_rel, 1.0); }
