// grass/seed001_wind.glsl: seed 001's wind function (eq. 2.7 / 4.2), the GPU twin of
// <sylva/grass/seed001_wind.hpp> (see there for the formula, eps and the time wrap).
#ifndef SYLVA_GRASS_SEED001_WIND_GLSL
#define SYLVA_GRASS_SEED001_WIND_GLSL

// k: x k1, y k2, z k3, w strength [m/s]; p [m]; t wrapped time [s].
vec3 grass_seed001_wind(vec3 p, float t, vec4 k) {
  const float kPi = 3.14159265;
  float a = kPi * p.x + t + (kPi / 4.0) / (abs(cos(k.y * kPi * p.z)) + 0.05);
  float short_wave = sin(k.x * a) * cos(k.z * a);
  float c = p.x + p.y + p.z + t;
  return k.w * vec3(short_wave + 2.0 * sin(c) + 1.0, 0.0, short_wave + sin(2.0 * c) + 0.5);
}

#endif
