#version 450 core
// grass/physics.comp: one step of the blade physics for the blades of the visible tiles. The
// GPU twin of simulate_blade() in src/physics.cpp (see <sylva/grass/physics.hpp> for the
// scheme): same operations in the same order, float throughout. One work group per tile job.
#include "grass/blade.glsl"
#include "render/lib/wind.glsl"
#include "grass/seed001_wind.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = GRASS_BLADES_BINDING) buffer Blades { Blade blades[]; };
layout(std430, binding = GRASS_JOBS_BINDING) readonly buffer Jobs { TileJob jobs[]; };
layout(std430, binding = GRASS_SPHERES_BINDING) readonly buffer Spheres { vec4 spheres[]; };  // xyz centre, w radius
layout(std140, binding = GRASS_WIND_UBO_BINDING) uniform GrassWind { SylvaWind u_wind; };

uniform vec4 u_physics;      // x gravity, y front_gravity, z wind_response, w collision_recovery
uniform vec2 u_substep;      // x max_substep, y max_substeps
uniform int u_sphere_count;
uniform vec3 u_wind_offset;  // blade-set origin minus the wind frame origin [m]
uniform int u_seed001_on;    // 1: seed 001's wind function (grass/seed001_wind.glsl) instead of u_wind
uniform vec4 u_seed001_wind; // k1, k2, k3, strength
uniform float u_seed001_time; // wrapped simulation time [s]

const float kMaxWind = 1000.0;
const float kMaxStiffness = 1.0e9;
const float kMinRecovery = 0.1;

bool finite3(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

float expm1_portable(float x) {
  if (abs(x) < 1.0e-3) return x + 0.5 * x * x + (1.0 / 6.0) * x * x * x;
  return exp(x) - 1.0;
}

void recovery_coefficients(float s, float dt, out float a, out float phi) {
  float x = s * dt;
  a = -expm1_portable(-x);
  phi = x > 1.0e-4 ? a / s : dt * (1.0 - 0.5 * x);
  a = clamp(a, 0.0, 1.0);
  phi = clamp(phi, 0.0, dt);
}

// Stable closed-form arc length; see bezier_length() in src/blade.cpp.
float bezier_length(vec3 p0, vec3 p1, vec3 p2) {
  vec3 A = p1 - p0;
  vec3 B = p2 - 2.0 * p1 + p0;
  float a = dot(B, B);
  float c = dot(A, A);
  float chord = length(p2 - p0);
  if (!(a > 1.0e-6 * c) || a <= 0.0) return chord;
  float b = dot(A, B);
  vec3 cr = cross(A, B);
  float k = dot(cr, cr) / (a * a);
  float u0 = b / a;
  float u1 = 1.0 + b / a;
  float integral;
  if (k <= 1.0e-7 * max(1.0, max(u0 * u0, u1 * u1))) {
    integral = 0.5 * (u1 * abs(u1) - u0 * abs(u0));
  } else {
    float s0 = sqrt(u0 * u0 + k), s1 = sqrt(u1 * u1 + k);
    float l1 = u1 >= 0.0 ? log(u1 + s1) : log(k) - log(s1 - u1);
    float l0 = u0 >= 0.0 ? log(u0 + s0) : log(k) - log(s0 - u0);
    integral = 0.5 * ((u1 * s1 - u0 * s0) + k * (l1 - l0));
  }
  float len = 2.0 * sqrt(a) * integral;
  return (isnan(len) || isinf(len)) ? chord : max(len, chord);
}

void validate(inout Blade b) {
  vec3 v0 = b.v0.xyz;
  vec3 up = b.up.xyz;
  float h = b.v1.w;
  vec3 v2 = b.v2.xyz;
  if (!finite3(v2) || !(h > 0.0)) v2 = v0 + b.rest.xyz;
  v2 -= up * min(dot(up, v2 - v0), 0.0);
  vec3 offset = v2 - v0;
  float chord = length(offset);
  if (!(chord > 1.0e-6 * h)) {
    v2 = v0 + b.rest.xyz;
    offset = v2 - v0;
    chord = length(offset);
  }
  float l_proj = length(offset - up * dot(offset, up));
  float lean = chord > 0.0 ? min(l_proj / chord, 1.0) : 0.0;
  vec3 v1 = v0 + chord * up * max(1.0 - lean, 0.05);
  float len = bezier_length(v0, v1, v2);
  if (len > 1.0e-12 && !isinf(len) && !isnan(len)) {
    float r = h / len;
    v1 = v0 + r * (v1 - v0);
    v2 = v0 + r * (v2 - v0);
  }
  b.v1.xyz = v1;
  b.v2.xyz = v2;
}

float sphere_push(vec4 sphere, vec3 p, vec3 up, out vec3 push) {
  vec3 d = p - sphere.xyz;
  float dist = length(d);
  float depth = sphere.w - dist;
  push = vec3(0.0);
  if (!(depth > 0.0)) return 0.0;
  vec3 dir = dist > 1.0e-6 * max(sphere.w, 1.0e-6) ? d / dist : up;
  push = dir * depth;
  return depth;
}

void substep(inout Blade b, vec3 wind, float h) {
  vec3 v0 = b.v0.xyz;
  vec3 up = b.up.xyz;
  float height = b.v1.w;
  vec3 v2 = b.v2.xyz;

  vec3 front = grass_front_dir(up, b.v0.w);
  vec3 gravity = vec3(0.0, -u_physics.x, 0.0) + u_physics.y * u_physics.x * front;
  vec3 wind_force = vec3(0.0);
  float wind_speed = length(wind);
  if (wind_speed > 0.0) {
    vec3 blade_dir = v2 - v0;
    float blade_len = length(blade_dir);
    float f_d = blade_len > 0.0 ? 1.0 - abs(dot(wind / wind_speed, blade_dir / blade_len)) : 1.0;
    float f_r = clamp(dot(blade_dir, up) / height, 0.0, 1.0);
    wind_force = u_physics.z * wind * (f_d * f_r);
  }
  vec3 force = gravity + wind_force;

  float eta = clamp(b.rest.w, 0.0, 1.0);
  float s_eff = clamp(b.up.w, 0.0, kMaxStiffness) * max(1.0 - eta, kMinRecovery);
  float a, phi;
  recovery_coefficients(s_eff, h, a, phi);
  vec3 rest_tip = v0 + b.rest.xyz;
  v2 += (rest_tip - v2) * a + force * phi;

  float new_eta = eta * exp(-h / max(u_physics.w, 1.0e-3));
  for (int i = 0; i < u_sphere_count; ++i) {
    vec4 sphere = spheres[i];
    if (!(sphere.w > 0.0) || !finite3(sphere.xyz) || isinf(sphere.w)) continue;
    vec3 push;
    float depth = sphere_push(sphere, v2, up, push);
    if (depth > 0.0) {
      v2 += push;
      new_eta += depth / height;
    }
    vec3 mid = 0.25 * v0 + 0.5 * b.v1.xyz + 0.25 * v2;
    depth = sphere_push(sphere, mid, up, push);
    if (depth > 0.0) {
      v2 += 2.0 * push;
      new_eta += depth / height;
    }
  }
  b.rest.w = clamp(new_eta, 0.0, 1.0);
  b.v2.xyz = v2;
  validate(b);
}

void reset_blade(inout Blade b) {
  b.v2.xyz = b.v0.xyz + b.rest.xyz;
  b.rest.w = 0.0;
  validate(b);
}

void simulate(inout Blade b, vec3 wind, float dt) {
  dt = (!isnan(dt) && !isinf(dt) && dt > 0.0) ? dt : 0.0;
  if (!finite3(wind)) wind = vec3(0.0);
  float speed = length(wind);
  if (speed > kMaxWind) wind *= kMaxWind / speed;
  if (!finite3(b.v2.xyz) || !finite3(b.v1.xyz) || isnan(b.rest.w) || isinf(b.rest.w)) reset_blade(b);
  if (dt == 0.0) {
    validate(b);
    return;
  }
  float max_sub = max(u_substep.x, 1.0e-4);
  int n = int(clamp(ceil(dt / max_sub), 1.0, max(u_substep.y, 1.0)));
  float h = dt / float(n);
  for (int i = 0; i < n; ++i) substep(b, wind, h);
}

void main() {
  TileJob job = jobs[gl_WorkGroupID.x];
  if ((job.flags & 1u) == 0u) return;
  for (uint i = gl_LocalInvocationID.x; i < job.count; i += gl_WorkGroupSize.x) {
    uint index = job.first + i;
    Blade b = blades[index];
    vec3 wind = u_seed001_on != 0 ? grass_seed001_wind(b.v0.xyz, u_seed001_time, u_seed001_wind)
                                  : sylva_wind(u_wind, b.v0.xyz + u_wind_offset);
    simulate(b, wind, job.dt);
    blades[index].v1 = b.v1;
    blades[index].v2 = b.v2;
    blades[index].rest.w = b.rest.w;
  }
}
