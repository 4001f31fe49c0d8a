#version 450 core
// terrain/model.vert: a vertex of the general-model tree (seed 002 §4). Every segment indexes the
// one vertex buffer, so a locked border vertex shared by segments of different levels goes
// through the same operations with the same inputs: bit-identical positions, no cracks (§4.2).

layout(location = 0) in vec3 a_position;  // relative to the model's origin [m]
layout(location = 1) in vec3 a_normal;    // of the original mesh at this vertex

uniform mat4 u_view_projection;  // camera-relative position -> clip
uniform mat4 u_model;            // model origin -> camera-relative (Camera::relative_model)
uniform vec3 u_origin;           // the model's origin in world metres (material placement)

out vec3 v_rel;     // camera-relative position [m]
out vec3 v_world;   // world position [m]
out vec3 v_normal;

invariant gl_Position;

void main() {
  vec4 rel = u_model * vec4(a_position, 1.0);
  v_rel = rel.xyz;
  v_world = a_position + u_origin;
  v_normal = a_normal;
  gl_Position = u_view_projection * rel;
}
