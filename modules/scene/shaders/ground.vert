#version 450 core
// Scene "ground" module: one chunk of the height-field mesh, positions relative to the field
// origin, drawn camera-relative (u_model holds origin - camera, subtracted in double on the CPU).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_view_projection;  // projection * rotation-only view
uniform mat4 u_model;            // translate(field origin - camera)
uniform float u_origin_height;   // world y of the field origin [m] (0 for height fields)

out vec3 v_rel_position;  // camera-relative position [m], for fog
out vec3 v_normal;
out float v_height;       // world height [m], for the material
out vec2 v_field_xz;      // position in the field's own frame [m]: anchors the detail noise

void main() {
  vec4 rel = u_model * vec4(a_position, 1.0);
  v_rel_position = rel.xyz;
  v_normal = a_normal;
  v_height = a_position.y + u_origin_height;
  v_field_xz = a_position.xz;
  gl_Position = u_view_projection * rel;
}
