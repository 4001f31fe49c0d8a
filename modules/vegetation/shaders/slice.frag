#version 450 core
// LOD1/LOD2 colour pass: backward transform (lib/slices.glsl), coverage by alpha-to-coverage on
// multisampled targets or a hashed alpha test (view and transition fades dither the coverage, so
// no back-to-front sorting is needed), then the leaf shading of LOD0 in reduced form (season colour
// per leafSpecificNumber with budding and leaf fall, diffuse + Cook-Torrance + a translucency term
// + ambient) or bark diffuse, with the render core's shadows at the depth-offset position.
#include "render/lib/fog.glsl"
#include "render/lib/shadows.glsl"
#include "vegetation/lib/slices.glsl"
#include "vegetation/lib/leaf_alpha.glsl"
#include "vegetation/lib/leaf_shading.glsl"

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
uniform int u_alpha_mode;  // 0 alpha test, 1 hashed, 2 alpha-to-coverage
uniform int u_samples;
uniform float u_roughness;
uniform float u_ior;
uniform vec3 u_specular_color;
uniform vec3 u_translucent_color;
uniform float u_leaf_transmittance;  // [0, 1], SliceAsset::create
uniform float u_diffuse;
uniform float u_ambient;
uniform vec4 u_view_direction;  // w = 1: a fixed (orthographic) view direction, slice.vert

out vec4 o_color;

void main() {
  SylvaTreeInstance inst = sylva_instances[v_instance];
  vec2 size = sylva_slice_rect_size();
  // Derivatives of the untransformed coordinate: the transformed one jumps at Voronoi borders.
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
  vec4 col = textureGrad(u_slice_color, vec3(uv, float(v_slice)), dx, dy);
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
  float a = (inside && picked) ? col.a : 0.0;
  bool leaf = nrm.a > 0.125;
  float number = clamp((nrm.a - 0.25) / 0.75, 0.0, 1.0);
  vec4 season = texture(u_season, vec2(0.5, u_season_time + u_leaf_spread * number + inst.rotation.w));
  if (leaf && season.a < 0.5) a = 0.0;  // budding and leaf fall (seed §4.6)
  int mask = 1;
  if (u_alpha_mode == 2) {
    float cov = mix(step(0.5, a), a, minified) * v_fade;
    mask = sylva_coverage_mask(cov, u_samples, vec3(q0, float(v_slice) + salt));
  } else {
    float threshold = u_alpha_mode == 0 ? 0.5 : mix(0.5, h1, minified);
    mask = (a < threshold || v_fade < h2) ? 0 : 1;
  }
  if (mask == 0) discard;
  if (u_alpha_mode == 2) gl_SampleMask[0] = mask;

  vec3 an = sylva_slice_axis(v_direction);
  vec3 nn = sylva_slice_normal(v_direction);
  vec3 ns = nrm.xyz * 2.0 - 1.0;
  if (!gl_FrontFacing) ns.z = -ns.z;  // seen from behind: the mirrored side
  vec3 N = normalize(sylva_instance_vector(inst, ns.x * an + vec3(0.0, ns.y, 0.0) + ns.z * nn));
  // The surface point on the viewing ray (parallax above): shading, fog and shadow lookups there.
  vec3 rel = v_rel + sylva_instance_vector(inst, normalize(view_obj)) * (sylva_slice_ray_distance(depth, v_direction, view_obj) * inst.translation_scale.w);
  vec3 V = normalize(-rel);
  vec3 L = sun_direction();
  vec3 color;
  if (leaf) {
    if (dot(N, V) < 0.0) N = -N;  // two-sided
#if SYLVA_TREE_ANIMATION >= 3
    // Colour noise (seed §3.3.1): the leaf turns its normal by a small angle that changes with
    // time, the same for every fragment of the leaf (its number from the normal map, plus the
    // instance), then is shaded as before. Integer multiples of the wrapped scroll offsets keep
    // the motion continuous.
    float tilt = min(sylva_slices.misc.y * inst.wind.w, 0.5);
    if (tilt > 0.0) {
      float phase = number * 61.0 + inst.variation.w * 13.0;
      vec2 w = vec2(sin(6.2831853 * (3.0 * sylva_slices.leaf_scroll.x + phase)),
                    sin(6.2831853 * (4.0 * sylva_slices.leaf_scroll.w + 1.618 * phase)));
      vec3 t1 = normalize(cross(N, abs(N.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
      N = normalize(N + tilt * (w.x * t1 + w.y * cross(N, t1)));
    }
#endif
    vec3 base = max(col.rgb - 0.5 + season.rgb + inst.variation.rgb, vec3(0.0));
    float nl = dot(N, L);
    float shadow = sylva_shadow(rel, nl >= 0.0 ? N : -N);
    float specular = nl > 0.0 ? sylva_cook_torrance(N, L, V, u_roughness, u_ior) : 0.0;
    // The species' mean transmittance (textures.hpp mean_leaf_transmittance): a fixed 0.35 made
    // back-lit needle and shrub slices 1.7-1.9 times brighter than their LOD0 (crown_gl_test).
    float translucency = nl < 0.0 ? u_leaf_transmittance * (-nl) : 0.0;
    color = shadow * sun_radiance() * (max(nl, 0.0) * u_diffuse * base + specular * u_specular_color +
                                       translucency * base * u_translucent_color) +
            hemisphere_ambient(N) * u_ambient * base;
  } else {
    if (dot(N, V) < 0.0) N = -N;
    float shadow = sylva_shadow(rel, N);
    color = shade_diffuse(col.rgb, N, shadow);
  }
  o_color = vec4(apply_fog(color, rel), 1.0);
}
