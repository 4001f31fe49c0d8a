#version 450 core
// LOD1/LOD2 depth pass (shadow maps): the colour pass's backward transform, coverage and season
// discard as a hashed test (shadow maps are single-sampled; transition fades dither, seed §4.7),
// and the slice's baked depth offset written to gl_FragDepth, so flat slices cast a crown-shaped
// shadow (§2.13; this disables early depth tests, as the seed notes).
#include "vegetation/lib/slices.glsl"

in vec2 v_q;
in vec3 v_rel;
flat in int v_slice;
flat in int v_direction;
flat in int v_instance;
flat in float v_fade;
flat in vec2 v_pick;
flat in vec2 v_origin;
uniform vec2 u_viewport;  // target size [px]

layout(binding = 3) uniform sampler2D u_season;
uniform float u_season_time;
uniform float u_leaf_spread;
uniform mat4 u_view_proj;
uniform vec4 u_view_direction;  // w = 1: the light's direction (slice.vert)

void main() {
  SylvaTreeInstance inst = sylva_instances[v_instance];
  vec2 size = sylva_slice_rect_size();
  vec2 dx = dFdx(v_q) / size;
  vec2 dy = dFdy(v_q) / size;
  float footprint = sylva_slice_footprint(dFdx(v_q), dFdy(v_q));
  float minified = clamp(footprint * sylva_slices.fade_range.z / size.x - 1.0, 0.0, 1.0);
  vec3 view_obj = sylva_instance_inverse_vector(inst, u_view_direction.w != 0.0 ? u_view_direction.xyz : -v_rel);
  vec2 qp = sylva_slice_parallax(v_q, v_slice, v_direction, view_obj);
  vec2 pick_range = u_view_direction.w != 0.0 ? v_pick : sylva_slice_pick_range(v_direction, view_obj);
  vec2 q0 = sylva_backward_transform(qp, v_slice, v_direction, inst);
  vec2 uv = (q0 - sylva_slice_rect_min()) / size;
  bool inside = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
  vec4 nrm = textureGrad(u_slice_normal, vec3(uv, float(v_slice)), dx, dy);
  float depth = textureLod(u_slice_depth, vec3(uv, float(v_slice)), 0.0).r;
  float salt = inst.variation.w * 977.0 + float(v_instance);
  float h1 = sylva_slice_threshold(q0, footprint, v_slice, salt);
  float h2 = sylva_slice_threshold(q0, footprint, v_slice, salt + 0.5);
  // Direction pick: a hash of the pixel relative to the projected instance centre (so the pattern
  // travels with the tree on screen), shared by all slices of the instance.
  ivec2 px = ivec2(floor(gl_FragCoord.xy - (v_origin * 0.5 + 0.5) * u_viewport));
  float pick = float(sylva_hash(ivec3(px, v_instance), 0x2545f491u) >> 8u) * (1.0 / 16777216.0);
  bool picked = pick >= pick_range.x && pick < pick_range.y;
  float a = (inside && picked) ? textureGrad(u_slice_color, vec3(uv, float(v_slice)), dx, dy).a : 0.0;
  float number = clamp((nrm.a - 0.25) / 0.75, 0.0, 1.0);
  if (nrm.a > 0.125 && texture(u_season, vec2(0.5, u_season_time + u_leaf_spread * number + inst.rotation.w)).a < 0.5) a = 0.0;
  if (a < mix(0.5, h1, minified) || v_fade < h2) discard;
  vec3 rel = v_rel;
  // The surface point on the light ray (parallax above): the slice writes the crown's depth (§2.13).
  vec3 ray = sylva_instance_vector(inst, normalize(view_obj));
  if (sylva_slices.misc.z != 0.0) rel += ray * (sylva_slice_ray_distance(depth, v_direction, view_obj) * inst.translation_scale.w);
  vec4 clip = u_view_proj * vec4(rel, 1.0);
  gl_FragDepth = clamp(clip.z / clip.w, 0.0, 1.0);
}
