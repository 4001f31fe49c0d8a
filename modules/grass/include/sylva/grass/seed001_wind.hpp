#pragma once
// Seed 001's own wind function (eq. 2.7 / 4.2), an option beside the shared wind field
// (grass.render.physics.seed001_wind.enabled, off by default). The thesis displaces blade tips
// kinematically; Sylva feeds the same function to its stable physics as the wind velocity at
// the blade root, so trampling, gravity and the length constraint still hold:
//
//   a      = pi p_x + t + K / (|cos(k2 pi p_z)| + eps),   K = pi / 4 (the thesis's code)
//   short  = sin(k1 a) cos(k3 a)                           (eq. 2.7)
//   long_x = 2 sin(p_x + p_y + p_z + t) + 1,  long_z = sin(2 (p_x + p_y + p_z + t)) + 0.5   (eq. 4.2)
//   wind   = strength (short + long_x, 0, short + long_z)  [m/s]
//
// As in the thesis the direction is fixed (the short term moves x and z together, the long terms
// lean towards +x/+z): the scene's wind direction, strength and gusts are ignored. eps = 0.05,
// not the thesis's 1e-5: near cos(k2 pi p_z) = 0 the thesis's term reaches 7.9e4 rad and float
// sin/cos turn into noisy stripes (seed 001 errata §8). p is the blade root in the field's
// frame [m]; t is simulation time wrapped by seed001_wind_time() so float phases stay exact.
// shaders/seed001_wind.glsl is the GPU twin.

#include <glm/glm.hpp>

namespace sylva::grass {

struct Seed001WindSettings {
  bool enabled = false;
  float k1 = 1.0f;        // frequency of the short wave's sine (thesis k1, user-set)
  float k2 = 2.0f;        // spacing of the z singular lines (thesis k2; its code: 2)
  float k3 = 1.0f;        // frequency of the short wave's cosine (thesis k3, user-set)
  float strength = 2.0f;  // m/s per unit of the thesis's displacement

  template <class V>
  void visit(V& v) {
    v(enabled, "enabled", {.help = "Seed 001 eq. 2.7/4.2 wind function instead of the scene's wind field"});
    v(k1, "k1", {.min = 0.0f, .max = 50.0f, .help = "Seed 001 wind k1 (short-wave sine frequency)"});
    v(k2, "k2", {.min = 0.0f, .max = 50.0f, .help = "Seed 001 wind k2 (z pattern frequency)"});
    v(k3, "k3", {.min = 0.0f, .max = 50.0f, .help = "Seed 001 wind k3 (short-wave cosine frequency)"});
    v(strength, "strength", {.min = 0.0f, .max = 50.0f, .unit = "m/s", .help = "Wind speed per unit of the seed's displacement"});
  }
};

// Simulation time wrapped to [0, 2 pi 1000) s in double precision (the long waves have period
// 2 pi and pi; the short wave jumps once every 6283 s unless k1 and k3 are multiples of 0.001).
float seed001_wind_time(double t);

// The wind velocity of the header comment at p [m], wrapped time t [s] [m/s]; finite for finite input.
glm::vec3 seed001_wind(const glm::vec3& p, float t, const Seed001WindSettings& s);

}  // namespace sylva::grass
