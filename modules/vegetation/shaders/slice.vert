#version 450 core
// LOD1/LOD2 slice clusters (seed 000 §2.6): quads generated from gl_VertexID (6 vertices per
// slice), fixed in object space so the cluster turns with the instance. Slices nearly parallel to
// the view fade out (§2.10); fully faded slices are collapsed so they cost no fragments. The depth
// pass (shadow maps) fades by the light direction instead.
#include "vegetation/lib/slices.glsl"

uniform mat4 u_view_proj;        // camera-relative
uniform int u_instance_base;
uniform vec4 u_view_direction;   // w = 1: fixed world view direction xyz (a directional light)

out vec2 v_q;                    // slice coordinates [m] (x along a_j from the centre, y object y)
out vec3 v_rel;                  // camera-relative world position on the quad
flat out int v_slice;
flat out int v_direction;
flat out int v_instance;
flat out float v_fade;           // instance transition fade
flat out vec2 v_pick;            // [lo, hi) of the direction-selection hash this slice draws
flat out vec2 v_origin;          // clip-space xy / w of the instance centre (dither key origin)

void main() {
  const ivec2 corners[6] = ivec2[](ivec2(0, 0), ivec2(1, 0), ivec2(0, 1), ivec2(0, 1), ivec2(1, 0), ivec2(1, 1));
  int layers = int(sylva_slices.extent.w);
  int quad = gl_VertexID / 6;
  int j = quad / layers;
  int i = quad - j * layers;
  ivec2 c = corners[gl_VertexID - quad * 6];
  float R = sylva_slices.center_radius.w;
  float m = sylva_slices.extent.y;
  float T = 2.0 * R / float(layers);
  vec3 a = sylva_slice_axis(j);
  vec3 n = sylva_slice_normal(j);
  vec2 lo = sylva_slice_rect_min() - vec2(m);
  vec2 hi = sylva_slice_rect_min() + sylva_slice_rect_size() + vec2(m);
  vec2 q = mix(lo, hi, vec2(c));
  vec3 centre = sylva_slices.center_radius.xyz;
  vec3 p = vec3(centre.x, 0.0, centre.z) + a * q.x + vec3(0.0, q.y, 0.0) + n * (-R + (float(i) + 0.5) * T);

  int index = u_instance_base + gl_InstanceID;
  SylvaTreeInstance inst = sylva_instances[index];
  vec3 rel = sylva_instance_point(inst, p);
  // View direction in object space (inverse yaw), horizontal part only: slices are vertical.
  vec3 view = u_view_direction.w != 0.0 ? u_view_direction.xyz : sylva_instance_point(inst, centre);
  float cy = inst.rotation.x;
  float sy = inst.rotation.y;
  vec2 h = vec2(cy * view.x - sy * view.z, sy * view.x + cy * view.z);
  float hl = length(h);
  h = hl > 1.0e-6 ? h / hl : vec2(0.0, 1.0);
  // Direction weights (seed §2.10 hides view-parallel slices): w_k rises with |cos| between the
  // view and direction k's normal and the weights are normalised, so every pixel of the cluster
  // shows exactly one direction, picked by a hash against the cumulative weights. Directions are
  // blended, never stacked: the cluster never covers more than one projection of the tree would.
  v_pick = sylva_slice_pick_range(j, vec3(h.x, 0.0, h.y));
  v_fade = inst.lod.x;
  vec4 oc = u_view_proj * vec4(sylva_instance_point(inst, centre), 1.0);
  v_origin = oc.xy / max(abs(oc.w), 1.0e-6);
  v_q = q;
  v_rel = rel;
  v_slice = quad;
  v_direction = j;
  v_instance = index;
  // A slice hidden by the centre's weights is collapsed (no fragments) unless the camera is within
  // four cluster radii, where the fragment shaders pick per fragment (sylva_slice_pick_range).
  bool near = length(view) < 4.0 * R * inst.translation_scale.w && u_view_direction.w == 0.0;
  gl_Position = ((v_pick.y > v_pick.x || near) && v_fade > 0.0) ? u_view_proj * vec4(rel, 1.0) : vec4(2.0, 2.0, 2.0, 1.0);
}
