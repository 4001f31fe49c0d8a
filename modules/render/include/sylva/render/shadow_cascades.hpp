#pragma once
// Cascaded shadow maps, the GL-free part: split distances, per-cascade light frusta fitted to
// slices of the camera frustum, texel snapping and bias constants (seed 004 §3.5–3.6,
// extraction §4.6–4.8; DESIGN.md §2 "shadow cascades"). The GL part is shadow_maps.hpp.
//
// Conventions (all documented again in shaders/lib/shadows.glsl):
//  - Matrices take CAMERA-RELATIVE positions (world - camera.position(), as everything else in
//    Sylva), so casters and receivers 1e6 m from the origin stay exact. The snapping itself is
//    done in double on world coordinates, so the texel grid is fixed in the world.
//  - Shadow depth is REVERSED like the main camera (camera.hpp): 1 = nearest to the sun, 0 =
//    farthest, cleared to 0, drawn with GL_GREATER, compared with GL_GEQUAL. Each cascade's depth
//    range is the diameter of its bounding sphere; casters between the sun and the sphere are
//    kept by GL_DEPTH_CLAMP (they clamp to depth 1 and still occlude), which replaces the seed's
//    scene-tuned `zMult` range extension (extraction §4.6).
//  - Split scheme: the "practical" split of Zhang et al. 2006, d_i = lambda * n (f/n)^(i/N) +
//    (1 - lambda) * (n + (f - n) i / N) (the seed gives no split scheme, extraction §4.7).
//  - Each cascade is fitted with the bounding SPHERE of its frustum slice (radius depends only on
//    near, far, fov and aspect, so rotating the camera never changes the texel size) and its
//    centre is snapped to whole shadow-map texels in the light's plane, so moving the camera
//    never shimmers the shadow edges (the seed's AABB fit shimmers, extraction §10).
//  - Light basis: up = world +y unless the sun is within ~2.6 deg of vertical, then world -z, so
//    a sun straight overhead never degenerates lookAt (the seed's failure, extraction §4.6).
//  - Bias: the seed's slope-scaled formula b = max(slope_bias * (1 - N.L), min_bias) (§3.3)
//    times a per-cascade factor `cascade_bias_scale` (the seed's `cascadeBiases`, §3.6.1). The
//    seed's constants are in normalised depth of a light frustum whose extent (zMult) it never
//    states, so here one unit of b is 100 shadow-map texels of depth: the default range
//    [0.00085, 0.0085] becomes 0.085 - 0.85 texels, and since texels grow with the cascade the
//    world bias grows with it as the seed's per-cascade table intends. Most of the acne margin
//    at grazing light comes from a normal offset instead: the receiver moves along its normal by
//    normal_offset * (pcf_radius + 1) texels * sin(angle between N and L), which gives exactly
//    the depth margin a (2 pcf_radius + 2)-texel wide filter footprint needs on a plane at any
//    sun elevation (margin = offset / sin(elevation) in light depth) while shifting shadow
//    edges by at most (pcf_radius + 1) * cos^2(elevation) texels.

#include <sylva/core/params.hpp>
#include <sylva/render/camera.hpp>

#include <glm/glm.hpp>

#include <array>

namespace sylva::render {

// Cascade arrays in the shader are sized for this many; the count changes at run time below it.
// Eight: seed 004 compared 3 against 5 cascades (R3, §3.8), and large views want more.
inline constexpr int kMaxShadowCascades = 8;

struct ShadowSettings {
  bool enabled = true;
  int cascade_count = 3;         // seed default 3 (§3.6.2)
  int resolution = 1024;         // texels per side of every cascade (seed: 1024², §3.8)
  float max_distance = 150.0f;   // view depth covered by the last cascade [m]
  float split_lambda = 0.75f;    // 0 = uniform splits, 1 = logarithmic
  float blend_fraction = 0.1f;   // share of each cascade's depth range cross-faded into the next
  int pcf_radius = 1;            // (2r+1)^2 bilinear comparison taps; 1 = the seed's 3x3 PCF
  float slope_bias = 0.0085f;    // seed §3.3
  float min_bias = 0.00085f;     // seed §3.3
  float normal_offset = 1.0f;    // receiver offset along the normal [(pcf_radius + 1) texels]
  glm::vec4 cascade_bias_scale{1.0f, 1.0f, 1.0f, 1.0f};  // the seed's cascadeBiases, cascades 1-4
  glm::vec4 cascade_bias_scale_far{1.0f, 1.0f, 1.0f, 1.0f};  // the same for cascades 5-8
  bool snap_to_texels = true;    // off only to demonstrate shimmer
  float caster_reach = 500.0f;   // casters this far toward the sun beyond a cascade survive culling [m]

  template <class V>
  void visit(V& v) {
    v(enabled, "enabled", {.help = "Render and sample the sun's cascaded shadow maps"});
    v(cascade_count, "cascade_count", {.min = 1, .max = kMaxShadowCascades, .help = "Number of cascades (run time, no recompile)"});
    v(resolution, "resolution", {.min = 64, .max = 8192, .unit = "texels", .help = "Shadow-map side per cascade"});
    v(max_distance, "max_distance", {.min = 1.0, .max = 1.0e5, .unit = "m", .help = "View depth covered by shadows", .log_scale = true});
    v(split_lambda, "split_lambda", {.min = 0.0, .max = 1.0, .help = "Split blend: 0 uniform, 1 logarithmic"});
    v(blend_fraction, "blend_fraction", {.min = 0.0, .max = 0.5, .help = "Cross-fade band at the end of each cascade"});
    v(pcf_radius, "pcf_radius", {.min = 0, .max = 3, .unit = "texels", .help = "PCF kernel radius"});
    v(slope_bias, "slope_bias", {.min = 0.0, .max = 0.1, .help = "Seed bias: max(slope_bias*(1-N.L), min_bias)"});
    v(min_bias, "min_bias", {.min = 0.0, .max = 0.1, .help = "Seed bias floor"});
    v(normal_offset, "normal_offset", {.min = 0.0, .max = 8.0, .help = "Receiver offset along the normal, in filter half-widths"});
    v(cascade_bias_scale, "cascade_bias_scale", {.min = 0.0, .max = 100.0, .help = "Per-cascade bias factor (cascades 1-4)"});
    v(cascade_bias_scale_far, "cascade_bias_scale_far", {.min = 0.0, .max = 100.0, .help = "Per-cascade bias factor (cascades 5-8)"});
    v(snap_to_texels, "snap_to_texels", {.help = "Snap cascades to whole texels (no shimmer)"});
    v(caster_reach, "caster_reach", {.min = 0.0, .max = 1.0e5, .unit = "m", .help = "Caster culling reach toward the sun"});
  }
};

struct ShadowCascade {
  // Camera-relative position -> clip space of the shadow map (x, y in [-1, 1], reversed depth
  // z in [0, 1]) for drawing casters.
  glm::mat4 relative_view_projection{1.0f};
  // Camera-relative position -> (u, v, depth) in [0, 1]^3 for receivers.
  glm::mat4 relative_texture{1.0f};
  // relative_view_projection with its depth range stretched by caster_reach toward the sun:
  // build culling frusta from this one (casters there are depth-clamped, not clipped).
  glm::mat4 relative_cull{1.0f};
  float near_depth = 0.0f;    // view depth where the slice starts [m]
  float far_depth = 0.0f;     // view depth where it ends [m]
  float radius = 0.0f;        // bounding-sphere radius = half the side of the light frustum [m]
  float texel_size = 0.0f;    // world size of one shadow texel [m]
  float bias_scale = 1.0f;    // cascade_bias_scale[i] (cascade_bias_scale_far[i - 4] from the fifth on)
  glm::dvec3 center{0.0};     // snapped sphere centre, world [m]
};

struct ShadowCascades {
  int count = 0;
  std::array<ShadowCascade, kMaxShadowCascades> cascades{};
  glm::vec3 light_direction{0.0f, 1.0f, 0.0f};  // unit, toward the sun
  glm::vec3 light_right{1.0f, 0.0f, 0.0f};      // light basis (unit, world)
  glm::vec3 light_up{0.0f, 0.0f, -1.0f};
  glm::vec3 view_forward{0.0f, 0.0f, -1.0f};    // camera forward (view depth = dot(rel, forward))
};

// Practical split: returns the far view depth of each of `count` slices between near and far
// (split[count - 1] == far). Needs 0 < near < far and 1 <= count <= kMaxShadowCascades (asserted).
std::array<float, kMaxShadowCascades> practical_splits(float near_plane, float far_plane, int count, float lambda);

// A stable light basis for a unit direction toward the light: right, up, toward-light (all unit,
// orthonormal). Never degenerate, including straight up/down and at the horizon.
void light_basis(const glm::vec3& toward_light, glm::dvec3& right, glm::dvec3& up, glm::dvec3& back);

// Fits every cascade to `camera` for a sun in direction `toward_sun` (need not be normalised;
// a zero or non-finite direction falls back to straight up). The settings are clamped to their
// visit() ranges, so out-of-range values never produce NaN matrices.
ShadowCascades compute_shadow_cascades(const Camera& camera, const glm::vec3& toward_sun, const ShadowSettings& settings);

// Seed bias (§3.3) for a cascade: max(slope*(1 - n_dot_l), min) * scale, in units of 100 texels
// of depth (see above); the shader adds bias * 100 / resolution to the normalised depth.
float shadow_depth_bias(const ShadowSettings& settings, float n_dot_l, float cascade_scale);

// Receiver offset along the normal [m] for a cascade with texel size `texel` (see above).
float shadow_normal_offset(const ShadowSettings& settings, float n_dot_l, float texel);

}  // namespace sylva::render
