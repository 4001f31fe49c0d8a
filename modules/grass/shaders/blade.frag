#version 450 core
// grass/blade.frag: two-sided blade shading: diffuse on the lit face, translucency (light
// through the blade) on the other, hemisphere ambient, root darkening, per-blade colour and a
// soft sheen; distance fog; the sun (diffuse, translucency, sheen) is multiplied by the render
// core's cascaded shadows, looked up with the normal of the face towards the eye (render README
// "How each module casts and receives"). Linear RGB out, like the rest of the render core.
#include "grass/color.glsl"
#include "render/lib/fog.glsl"
#include "render/lib/shadows.glsl"

in vec3 te_rel_pos;
in vec3 te_normal;
in vec2 te_uv;
flat in vec3 te_color_mult;
flat in float te_shade;

uniform vec3 u_base_color;
uniform vec3 u_tip_color;
uniform vec4 u_shading;   // x translucency, y ambient, z root_occlusion, w specular
uniform int u_receive_shadows;
uniform vec2 u_color_motion;  // seed 003 motion by colour (color.glsl grass_color_pulse)

out vec4 o_color;

void main() {
  vec3 view = normalize(-te_rel_pos);
  vec3 n = normalize(te_normal);
  if (dot(n, view) < 0.0) n = -n;  // two-sided: the face towards the eye
  vec3 l = sun_direction();
  // Multisampled targets shade a partly covered pixel at its centre, which can lie off the blade:
  // the interpolants are then extrapolated (v < 0 below the root), and pow(v, 0.8) is NaN there.
  float v = clamp(te_uv.y, 0.0, 1.0);
  // Dry tips: a per-blade random decorrelated from the ambient shade random (both from te_shade).
  float dryness = grass_blade_dryness(fract(te_shade * 7.31));
  vec3 albedo = grass_albedo(u_base_color, u_tip_color, v, dryness) * te_color_mult;
  albedo *= grass_color_pulse(u_color_motion, fract(te_shade * 3.17));  // per-blade phase
  float ao = mix(1.0 - u_shading.z, 1.0, smoothstep(0.0, 1.0, v));
  // A blade is not a flat card: its cross-section is curved and it sits in a canopy lit from
  // above, so the sun and the sky are gathered with the normal leaned towards up. With the bare
  // card normal, blades seen edge-on to the sun or facing down went black (dark strokes in the
  // meadow). The sum is at least 0.6 - 0.4 = 0.2 long (|n| = 1), so it never vanishes.
  vec3 n_lit = normalize(n * 0.6 + vec3(0.0, 0.4, 0.0));
  float ndl = dot(n, l);
  float diffuse = max(dot(n_lit, l), 0.0);
  // Light through the blade: the unlit face glows, strongest when looking towards the sun.
  float through = max(-ndl, 0.0) * (0.5 + 0.5 * max(dot(-view, l), 0.0));
  vec3 transmitted = u_shading.x * through * vec3(1.0, 1.05, 0.55);
  float lit = u_receive_shadows != 0 ? sylva_shadow(te_rel_pos, n) : 1.0;
  vec3 direct = sun_radiance() * (diffuse + transmitted) * lit;
  vec3 ambient = hemisphere_ambient(n_lit) * u_shading.y * (0.8 + 0.4 * te_shade);
  float sheen = u_shading.w * blinn_phong(n, view, l, 24.0) * v;
  vec3 color = (albedo * (direct + ambient) + sheen * lit * sun_radiance() * 0.04) * ao;
  o_color = vec4(apply_fog(color, te_rel_pos), 1.0);
}
