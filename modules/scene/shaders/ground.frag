#version 450 core
// Height and slope material (grass low, rock on steep slopes, snow high), sun + ambient + aerial
// perspective. Linear albedos (the scene tone-maps; render/README "Lighting"): a sunlit grass
// albedo of 0.1 shows as a mid green. Procedural detail at three scales (lush and dry patches of
// ~35 m, tufts of ~5 m, grain of ~0.8 m) so the plain ground does not read as a flat plane
// (issue 19); each scale fades out once a pixel covers more than half its wavelength, so the
// far ground does not shimmer. u_tint is white normally; the LOD-colour debug view tints each
// chunk. Receives the sun's cascaded shadows (render/lib/shadows.glsl).
#include "render/lib/fog.glsl"
#include "render/lib/noise.glsl"
#include "render/lib/shadows.glsl"

in vec3 v_rel_position;
in vec3 v_normal;
in float v_height;
in vec2 v_field_xz;
out vec4 o_color;

uniform float u_snow_line;  // metres
uniform vec3 u_tint;

// Noise of wavelength `metres` in [-1, 1], faded to 0 where a pixel spans half a wavelength.
float detail(vec2 p, float metres, uint seed, float footprint) {
  float visible = 1.0 - smoothstep(0.25, 0.5, footprint / metres);
  return visible > 0.0 ? visible * sylva_noise2(p / metres, seed) : 0.0;
}

void main() {
  vec3 n = normalize(v_normal);
  float slope = 1.0 - n.y;  // 0 flat, 1 vertical
  float footprint = length(fwidth(v_field_xz));  // metres per pixel
  float patches = detail(v_field_xz, 35.0, 11u, footprint);
  float tufts = detail(v_field_xz, 5.0, 12u, footprint);
  float grain = detail(v_field_xz, 0.8, 13u, footprint);
  vec3 lush = vec3(0.055, 0.105, 0.030);
  vec3 dry = vec3(0.115, 0.120, 0.050);
  vec3 grass = mix(lush, dry, clamp(0.5 + 0.9 * patches + 0.3 * tufts, 0.0, 1.0));
  grass *= 1.0 + 0.25 * tufts + 0.2 * grain;
  vec3 rock = vec3(0.16, 0.145, 0.13) * (1.0 + 0.3 * tufts + 0.25 * grain);
  vec3 snow = vec3(0.80, 0.83, 0.88);
  vec3 albedo = mix(grass, rock, smoothstep(0.18, 0.35, slope + 0.05 * tufts));
  albedo = mix(albedo, snow, smoothstep(u_snow_line - 10.0, u_snow_line + 10.0, v_height) * (1.0 - smoothstep(0.35, 0.6, slope)));
  vec3 color = shade_diffuse(albedo * u_tint, n, sylva_shadow(v_rel_position, n));
  o_color = vec4(apply_fog(color, v_rel_position), 1.0);
}
