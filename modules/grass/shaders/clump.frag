#version 450 core
// grass/clump.frag: strand-by-strand density and fade (a strand is drawn when its graded
// threshold is below the fade), coloured and lit like the blades (grass/color.glsl): the strand's
// luminance ramp stands for the height along a blade, the clump's colour carries the field's
// patches and clump hue, `u_brightness` calibrates the mean to the blades' (far_field.hpp).
#include "grass/color.glsl"
#include "render/lib/fog.glsl"
#include "render/lib/shadows.glsl"

layout(binding = 0) uniform sampler2D u_atlas;

uniform vec3 u_base_color;
uniform vec3 u_tip_color;
uniform int u_receive_shadows;  // sun term times the render core's cascaded shadows
uniform vec3 u_shading;         // x brightness (calibration), y ambient, z translucency (the blades' shading)
uniform vec2 u_color_motion;    // seed 003 motion by colour (color.glsl grass_color_pulse)

in vec3 c_rel_pos;
in vec2 c_uv;
in float c_v;
flat in vec3 c_color;
flat in float c_fade;
flat in vec3 c_normal;
flat in float c_repeat;
flat in vec2 c_cell;
flat in float c_phase;

out vec4 o_color;

void main() {
  vec4 t;
  vec2 du = dFdx(c_uv) * 0.5, dv = dFdy(c_uv) * 0.5;
  if (c_repeat > 0.0) {
    // Wide billboard: the cell repeats along the width; gradients of the unwrapped uv (no seam).
    t = textureGrad(u_atlas, (c_cell + vec2(fract(c_uv.x), c_uv.y)) * 0.5, du, dv);
  } else {
    t = texture(u_atlas, c_uv);
  }
  if (!(t.a < c_fade)) discard;
  float along = clamp(t.r * 1.2 - 0.1, 0.0, 1.0);
  vec3 albedo = grass_albedo(u_base_color, u_tip_color, along, GRASS_MEAN_DRYNESS) * c_color;
  albedo *= grass_color_pulse(u_color_motion, c_phase);
  float ao = mix(0.35, 1.0, smoothstep(0.0, 1.0, c_v));
  float lit = u_receive_shadows != 0 ? sylva_shadow(c_rel_pos, c_normal) : 1.0;
  vec3 color = albedo * grass_canopy_light(normalize(c_rel_pos), u_shading.z, lit, u_shading.y) * ao * u_shading.x;
  o_color = vec4(apply_fog(color, c_rel_pos), 1.0);
}
