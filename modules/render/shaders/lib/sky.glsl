// The physically based sky and the sun disk from the SylvaLighting block. Include as
// "render/lib/sky.glsl". CPU twin of atmosphere_radiance: sylva::render::sky_table_radiance
// (atmosphere.hpp; sky_radiance in sky.hpp); keep them identical.
#ifndef SYLVA_RENDER_SKY_GLSL
#define SYLVA_RENDER_SKY_GLSL

#include "render/lib/lighting.glsl"

const int SYLVA_SKY_ROWS = 16;
const int SYLVA_SKY_COLS = 5;

float rayleigh_phase(float mu) { return 3.0 / (16.0 * PI) * (1.0 + mu * mu); }

// Cornette-Shanks: Henyey-Greenstein with a Rayleigh-like factor, normalised over the sphere.
float mie_phase(float mu, float g) {
  float g2 = g * g;
  float denom = max(1.0 + g2 - 2.0 * g * mu, 1.0e-6);
  return 3.0 / (8.0 * PI) * ((1.0 - g2) * (1.0 + mu * mu)) / ((2.0 + g2) * denom * sqrt(denom));
}

// Horizontal length of a downward direction below which its azimuth fades out (30 degrees
// from the nadir; see atmosphere_radiance). SkyTable::kNadirFade on the CPU.
const float SYLVA_SKY_NADIR_FADE = 0.5;

// Sky radiance without the sun disk for a unit world direction: the table cell by view
// elevation (row = sqrt(sin elevation), denser near the horizon) and azimuth from the sun
// (column = (1 - cos azimuth) / 2: no inverse trigonometry per pixel), bilinear, times the
// phase functions. Below the horizon: the horizon in the same azimuth, the haze. That azimuth
// is undefined straight down (a wedge of the sun-side horizon's glow pointed at the nadir of a
// lake seen from above), so within 30 degrees of the nadir (horizontal length h of dir below
// 0.5) the azimuth fades out: the column goes to the 90-degree one and the phase direction from
// the horizon's to dir itself, by smoothstep(0, 0.5, h). Straight up needs nothing: the top row
// is one direction, the same value in every column.
vec3 atmosphere_radiance(vec3 dir) {
  vec3 sun = sun_direction();
  float azimuth_weight = 1.0;
  if (dir.y < 0.0) {
    float h = length(dir.xz);
    vec3 horizon = h > 1.0e-6 ? vec3(dir.x / h, 0.0, dir.z / h) : vec3(0.0, 0.0, -1.0);
    azimuth_weight = smoothstep(0.0, SYLVA_SKY_NADIR_FADE, h);
    dir = azimuth_weight < 1.0 ? normalize(mix(dir, horizon, azimuth_weight)) : horizon;
  }
  float row = dir.y > 0.0 ? sqrt(min(dir.y, 1.0)) * float(SYLVA_SKY_ROWS - 1) : 0.0;
  float lens = length(dir.xz) * length(sun.xz);
  float cos_phi = (lens > 1.0e-6 ? clamp(dot(dir.xz, sun.xz) / lens, -1.0, 1.0) : 1.0) * azimuth_weight;
  float col = (1.0 - cos_phi) * 0.5 * float(SYLVA_SKY_COLS - 1);
  int r0 = min(int(row), SYLVA_SKY_ROWS - 2);
  int c0 = min(int(col), SYLVA_SKY_COLS - 2);
  float fr = clamp(row - float(r0), 0.0, 1.0);
  float fc = clamp(col - float(c0), 0.0, 1.0);
  int i00 = (r0 * SYLVA_SKY_COLS + c0) * 2;
  int i10 = i00 + SYLVA_SKY_COLS * 2;
  vec3 ray = mix(mix(sylva_sky_table[i00].rgb, sylva_sky_table[i00 + 2].rgb, fc),
                 mix(sylva_sky_table[i10].rgb, sylva_sky_table[i10 + 2].rgb, fc), fr);
  vec3 mie = mix(mix(sylva_sky_table[i00 + 1].rgb, sylva_sky_table[i00 + 3].rgb, fc),
                 mix(sylva_sky_table[i10 + 1].rgb, sylva_sky_table[i10 + 3].rgb, fc), fr);
  float mu = dot(dir, sun);
  return ray * rayleigh_phase(mu) + mie * mie_phase(mu, sylva_mie.z);
}

// Kept for callers of the old gradient: now the atmosphere's radiance.
vec3 sky_gradient(vec3 dir) { return atmosphere_radiance(dir); }

// The sun disk (0.53 deg across) with limb darkening I(mu) = 1 - 0.6 (1 - mu) (mu: cosine
// at the disk's surface point), only above the horizon. Its radiance is the sun's light times
// 50, not the physical ~46000: enough to saturate any sane exposure without overflowing the
// half-float target (the Mie phase already paints the glow around it).
vec3 sun_disk(vec3 dir) {
  float c = dot(dir, sun_direction());
  float cos_r = sylva_mie.w;
  if (c < cos_r || dir.y < 0.0) return vec3(0.0);
  float s2 = clamp((1.0 - c * c) / max(1.0 - cos_r * cos_r, 1.0e-9), 0.0, 1.0);
  float limb = 1.0 - 0.6 * (1.0 - sqrt(1.0 - s2));
  return sun_radiance() * (50.0 * limb);
}

vec3 sky_color(vec3 dir) { return atmosphere_radiance(dir) + sun_disk(dir); }

#endif
