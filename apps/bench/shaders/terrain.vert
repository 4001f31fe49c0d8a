#version 450 core
// sylva-bench built-in terrain: the triangles a terrain LOD selection draws this frame
// (terrain::assemble_frame: chunk bodies with morphing, seams or skirts), camera-relative.
layout(location = 0) in vec3 a_rel_position;  // metres, relative to the camera

uniform mat4 u_view_projection;  // projection * rotation-only view
uniform vec3 u_camera_field;     // camera position relative to the field's sample (0, 0) [m]

out vec3 v_rel_position;
out vec2 v_field_xz;             // metres from sample (0, 0)
out float v_height;              // world height [m]

void main() {
  v_rel_position = a_rel_position;
  v_field_xz = u_camera_field.xz + a_rel_position.xz;
  v_height = u_camera_field.y + a_rel_position.y;
  gl_Position = u_view_projection * vec4(a_rel_position, 1.0);
}
