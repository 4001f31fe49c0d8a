// render/lib/noise.glsl: integer hash, gradient noise, fBm and ridged fBm.
//
// The GLSL twin of <sylva/core/rng.hpp> (hash) and <sylva/core/noise.hpp> (noise). Every
// operation mirrors modules/core/src/noise.cpp in the same order with the same constants, so a
// shader sees the CPU's field: the hash is bit-exact, noise values agree to float rounding
// (the driver may fuse multiply-adds). Change both files together.
//
// Coordinates are in lattice units; every function is periodic with 65536 cells per axis.
// Ranges: sylva_noise1/2/3 and sylva_fbm2/3 in [-1, 1], sylva_ridged2/3 in [0, 1].
// The split overloads (int cell + float offset) take far positions or long-running time offsets
// computed in double on the CPU (sylva::split_noise_coord) without losing float precision.

#ifndef SYLVA_RENDER_NOISE_GLSL
#define SYLVA_RENDER_NOISE_GLSL

// PCG hash (Jarzynski & Olano 2020): uint wrap-around arithmetic, bit-exact with the CPU.
uint sylva_pcg_hash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// sylva::hash_u32 chains: hash(a, b) = pcg(a + pcg(b)).
uint sylva_hash(uint a) { return sylva_pcg_hash(a); }
uint sylva_hash(uint a, uint b) { return sylva_pcg_hash(a + sylva_pcg_hash(b)); }
uint sylva_hash(uint a, uint b, uint c) { return sylva_pcg_hash(a + sylva_pcg_hash(b + sylva_pcg_hash(c))); }
uint sylva_hash(uint a, uint b, uint c, uint d) {
  return sylva_pcg_hash(a + sylva_pcg_hash(b + sylva_pcg_hash(c + sylva_pcg_hash(d))));
}
uint sylva_hash(ivec2 p, uint seed) { return sylva_hash(uint(p.x), uint(p.y), seed); }
uint sylva_hash(ivec3 p, uint seed) { return sylva_hash(uint(p.x), uint(p.y), uint(p.z), seed); }

// Top 24 bits times 2^-24: [0, 1), exact.
float sylva_hash_to_unit(uint h) { return float(h >> 8u) * (1.0 / 16777216.0); }

const float SYLVA_NOISE_PERIOD = 65536.0;
const float SYLVA_NOISE_INV_PERIOD = 1.0 / 65536.0;
const uint SYLVA_NOISE_MASK = 0xFFFFu;

// Lattice index modulo the period, for a whole-number float (exact).
float sylva_noise_wrap(float whole) { return whole - SYLVA_NOISE_PERIOD * floor(whole * SYLVA_NOISE_INV_PERIOD); }
float sylva_noise_fade(float t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
float sylva_noise_mix(float a, float b, float t) { return a + t * (b - a); }

float sylva_noise_grad1(uint h, float x) {
  float g = float(h >> 8u) * (2.0 / 16777216.0) - 1.0;
  return g * x;
}

float sylva_noise_grad2(uint h, float x, float y) {
  uint k = h & 7u;
  float u = (k & 4u) != 0u ? y : x;
  float v = (k & 4u) != 0u ? x : y;
  return ((k & 1u) != 0u ? -u : u) + ((k & 2u) != 0u ? -2.0 * v : 2.0 * v);
}

float sylva_noise_grad3(uint h, float x, float y, float z) {
  uint k = h & 15u;
  float u = k < 8u ? x : y;
  float v = k < 4u ? y : ((k == 12u || k == 14u) ? x : z);
  return ((k & 1u) == 0u ? u : -u) + ((k & 2u) == 0u ? v : -v);
}

// One axis: cell index (base_cell + floor(offset), wrapped) and the fraction inside the cell.
void sylva_noise_axis(uint base_cell, float offset, out uint cell, out float frac) {
  float fl = floor(offset);
  cell = (base_cell + uint(int(sylva_noise_wrap(fl)))) & SYLVA_NOISE_MASK;
  frac = offset - fl;
}

float sylva_noise1_impl(uint cx, float fx, uint seed) {
  uint s = sylva_pcg_hash(seed);
  uint c1 = (cx + 1u) & SYLVA_NOISE_MASK;
  float n0 = sylva_noise_grad1(sylva_pcg_hash(cx + s), fx);
  float n1 = sylva_noise_grad1(sylva_pcg_hash(c1 + s), fx - 1.0);
  return sylva_noise_mix(n0, n1, sylva_noise_fade(fx)) * 2.0;
}

float sylva_noise2_impl(uint cx, uint cy, float fx, float fy, uint seed) {
  uint s = sylva_pcg_hash(seed);
  uint x1 = (cx + 1u) & SYLVA_NOISE_MASK;
  uint y1 = (cy + 1u) & SYLVA_NOISE_MASK;
  uint hy0 = sylva_pcg_hash(cy + s);
  uint hy1 = sylva_pcg_hash(y1 + s);
  float n00 = sylva_noise_grad2(sylva_pcg_hash(cx + hy0), fx, fy);
  float n10 = sylva_noise_grad2(sylva_pcg_hash(x1 + hy0), fx - 1.0, fy);
  float n01 = sylva_noise_grad2(sylva_pcg_hash(cx + hy1), fx, fy - 1.0);
  float n11 = sylva_noise_grad2(sylva_pcg_hash(x1 + hy1), fx - 1.0, fy - 1.0);
  float u = sylva_noise_fade(fx);
  float v = sylva_noise_fade(fy);
  return sylva_noise_mix(sylva_noise_mix(n00, n10, u), sylva_noise_mix(n01, n11, u), v) * 0.632455532;
}

float sylva_noise3_impl(uvec3 c, vec3 f, uint seed) {
  uint s = sylva_pcg_hash(seed);
  uint x1 = (c.x + 1u) & SYLVA_NOISE_MASK;
  uint y1 = (c.y + 1u) & SYLVA_NOISE_MASK;
  uint z1 = (c.z + 1u) & SYLVA_NOISE_MASK;
  uint hz0 = sylva_pcg_hash(c.z + s);
  uint hz1 = sylva_pcg_hash(z1 + s);
  uint hy00 = sylva_pcg_hash(c.y + hz0);
  uint hy10 = sylva_pcg_hash(y1 + hz0);
  uint hy01 = sylva_pcg_hash(c.y + hz1);
  uint hy11 = sylva_pcg_hash(y1 + hz1);
  float n000 = sylva_noise_grad3(sylva_pcg_hash(c.x + hy00), f.x, f.y, f.z);
  float n100 = sylva_noise_grad3(sylva_pcg_hash(x1 + hy00), f.x - 1.0, f.y, f.z);
  float n010 = sylva_noise_grad3(sylva_pcg_hash(c.x + hy10), f.x, f.y - 1.0, f.z);
  float n110 = sylva_noise_grad3(sylva_pcg_hash(x1 + hy10), f.x - 1.0, f.y - 1.0, f.z);
  float n001 = sylva_noise_grad3(sylva_pcg_hash(c.x + hy01), f.x, f.y, f.z - 1.0);
  float n101 = sylva_noise_grad3(sylva_pcg_hash(x1 + hy01), f.x - 1.0, f.y, f.z - 1.0);
  float n011 = sylva_noise_grad3(sylva_pcg_hash(c.x + hy11), f.x, f.y - 1.0, f.z - 1.0);
  float n111 = sylva_noise_grad3(sylva_pcg_hash(x1 + hy11), f.x - 1.0, f.y - 1.0, f.z - 1.0);
  float u = sylva_noise_fade(f.x);
  float v = sylva_noise_fade(f.y);
  float w = sylva_noise_fade(f.z);
  float nx00 = sylva_noise_mix(n000, n100, u);
  float nx10 = sylva_noise_mix(n010, n110, u);
  float nx01 = sylva_noise_mix(n001, n101, u);
  float nx11 = sylva_noise_mix(n011, n111, u);
  return sylva_noise_mix(sylva_noise_mix(nx00, nx10, v), sylva_noise_mix(nx01, nx11, v), w) * 0.816496581;
}

// Gradient noise in [-1, 1].
float sylva_noise1(float x, uint seed) {
  uint c; float f;
  sylva_noise_axis(0u, x, c, f);
  return sylva_noise1_impl(c, f, seed);
}

float sylva_noise1(int cell, float offset, uint seed) {
  uint c; float f;
  sylva_noise_axis(uint(cell), offset, c, f);
  return sylva_noise1_impl(c, f, seed);
}

float sylva_noise2(vec2 p, uint seed) {
  uint cx; uint cy; float fx; float fy;
  sylva_noise_axis(0u, p.x, cx, fx);
  sylva_noise_axis(0u, p.y, cy, fy);
  return sylva_noise2_impl(cx, cy, fx, fy, seed);
}

float sylva_noise3(ivec3 cell, vec3 offset, uint seed) {
  uvec3 c; vec3 f;
  sylva_noise_axis(uint(cell.x), offset.x, c.x, f.x);
  sylva_noise_axis(uint(cell.y), offset.y, c.y, f.y);
  sylva_noise_axis(uint(cell.z), offset.z, c.z, f.z);
  return sylva_noise3_impl(c, f, seed);
}

float sylva_noise3(vec3 p, uint seed) { return sylva_noise3(ivec3(0), p, seed); }

uint sylva_octave_seed(uint seed, int octave) { return sylva_hash(uint(octave), seed); }

// The octave loops are written once for vec2 and vec3 (GLSL has no templates): VEC is the
// coordinate type, NOISE the gradient noise of that dimension.

// fBm in [-1, 1]; the same parameters as sylva::FbmSettings (octaves clamped to [1, 16]).
#define SYLVA_DEFINE_FBM(NAME, VEC, NOISE)                                                     \
  float NAME(VEC p, int octaves, float persistence, float lacunarity, float frequency, uint seed) { \
    VEC q = p * frequency;                                                                     \
    float sum = 0.0;                                                                           \
    float amp = 1.0;                                                                           \
    float norm = 0.0;                                                                          \
    int n = clamp(octaves, 1, 16);                                                             \
    for (int k = 0; k < n; ++k) {                                                              \
      sum += amp * NOISE(q, sylva_octave_seed(seed, k));                                       \
      norm += abs(amp);                                                                        \
      amp *= persistence;                                                                      \
      q *= lacunarity;                                                                         \
    }                                                                                          \
    return sum / norm;                                                                         \
  }

// Ridged fBm in [0, 1] (see sylva::ridged2 for the weighting).
#define SYLVA_DEFINE_RIDGED(NAME, VEC, NOISE)                                                  \
  float NAME(VEC p, int octaves, float persistence, float lacunarity, float frequency, uint seed, \
             float ridge_gain) {                                                               \
    VEC q = p * frequency;                                                                     \
    float sum = 0.0;                                                                           \
    float amp = 1.0;                                                                           \
    float norm = 0.0;                                                                          \
    float weight = 1.0;                                                                        \
    int n = clamp(octaves, 1, 16);                                                             \
    for (int k = 0; k < n; ++k) {                                                              \
      float r = 1.0 - abs(NOISE(q, sylva_octave_seed(seed, k)));                               \
      r = r * r * weight;                                                                      \
      sum += amp * r;                                                                          \
      norm += abs(amp);                                                                        \
      weight = clamp(r * ridge_gain, 0.0, 1.0);                                                \
      amp *= persistence;                                                                      \
      q *= lacunarity;                                                                         \
    }                                                                                          \
    return sum / norm;                                                                         \
  }

SYLVA_DEFINE_FBM(sylva_fbm2, vec2, sylva_noise2)
SYLVA_DEFINE_FBM(sylva_fbm3, vec3, sylva_noise3)
SYLVA_DEFINE_RIDGED(sylva_ridged2, vec2, sylva_noise2)
SYLVA_DEFINE_RIDGED(sylva_ridged3, vec3, sylva_noise3)

#endif  // SYLVA_RENDER_NOISE_GLSL
