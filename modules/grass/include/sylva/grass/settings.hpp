#pragma once
// Settings of a grass field, each struct listing its fields once through visit() (DESIGN.md §2).
// Units are SI (metres, seconds, radians unless a field says degrees). The ranges in visit()
// are the ranges the module is tested over; values outside them are rejected by the parameter
// system with a message naming the path (e.g. "grass.blade.height_max").
//
// What a change needs (DESIGN.md §2b): GrassFieldSettings and BladeSettings -> regenerate the
// blades (CPU + GPU buffers); PhysicsSettings, CullSettings, ShadingSettings, FarFieldSettings
// -> nothing, they are read every frame.

#include <sylva/core/params.hpp>
#include <sylva/grass/seed001_wind.hpp>

#include <glm/glm.hpp>

#include <array>
#include <cstdint>

namespace sylva::grass {

// Placement: how many blades, where (seed 001 §2.6 "Density": blades per unit area times the
// density map; §3.4 tiles). Tiles are anchored to the world grid, so a blade's identity depends
// only on (seed, tile, index), never on the camera or the field's extent.
struct GrassFieldSettings {
  float density = 300.0f;     // blades per square metre where the density map is 1 [1/m^2]
  float tile_size = 4.0f;     // side of a placement / culling tile [m]
  std::uint32_t seed = 1;     // changes every blade of the field
  float up_normal_blend = 0.0f;  // 0: blades grow along world up on height fields; 1: along the ground normal
  // Seed 001 Algorithm 2: no blade where the height map is at or below this [0, 1] (the thesis's
  // code: 0.1); 0 = off (then min_height keeps painted-short blades visible instead).
  float height_threshold = 0.0f;

  template <class V>
  void visit(V& v) {
    v(density, "density", {.min = 0.0f, .max = 5000.0f, .unit = "1/m^2",
                           .help = "Blades per square metre where the density map is white", .rebuild = Rebuild::kOffline});
    v(tile_size, "tile_size", {.min = 0.25f, .max = 64.0f, .unit = "m",
                               .help = "Side of a placement and culling tile", .rebuild = Rebuild::kOffline});
    v(seed, "seed", {.min = 0.0f, .max = 4294967295.0, .help = "Random seed of the field", .rebuild = Rebuild::kOffline});
    v(up_normal_blend, "up_normal_blend", {.min = 0.0f, .max = 1.0f,
                                           .help = "On height fields: 0 = blades grow vertically, 1 = along the ground normal", .rebuild = Rebuild::kOffline});
    v(height_threshold, "height_threshold", {.min = 0.0f, .max = 1.0f,
                                             .help = "Seed 001 Algorithm 2: no blades where the height map is at or below this (0 = off)",
                                             .rebuild = Rebuild::kOffline});
  }
};

// Per-blade random ranges (seed 001 §3.5 table of r0..r7, eq. 2.1 and 2.2; Jahrmann & Wimmer
// 2017 §3 blade model: height, width, bend, stiffness).
struct BladeSettings {
  float height_min = 0.25f;   // [m] before the height map scales it
  float height_max = 0.55f;   // [m]
  float width_min = 0.008f;   // [m] at the root
  float width_max = 0.016f;   // [m]
  float min_height = 0.02f;   // a painted height map never makes a blade shorter than this [m]
  float bend = 0.3f;          // rest bend: the tip's sideways offset as a share of the height (seed's b)
  float stiffness_min = 40.0f;   // recovery rate towards the rest pose [1/s]
  float stiffness_max = 80.0f;   // [1/s]
  float height_width_correlation = 0.5f;  // 0: independent randoms; 1: seed 001's single random for both
  float color_variation = 0.15f;  // per-blade multiplicative jitter of each channel (seed's r5..r7)
  // Field colour (field_color.hpp): lush/dry patches and per-clump hue, shared by all three LODs.
  float patch_variation = 0.5f;   // strength of the low-frequency lush/dry patches [0..1]
  float patch_size = 14.0f;       // feature size of the patches [m]
  float clump_variation = 0.12f;  // strength of the per-clump hue and brightness offset [0..1]
  float clump_size = 0.7f;        // side of a clump cell [m]
  // Seed 001 eq. 2.4 (§3.5 randoms r3, r4): each blade's drawn Bezier control point is jittered
  // per blade, r3 in [-0.25, 0.25) of the tip's sideways offset on x/z and r4 in [0.75, 1.25) of
  // its height on y (blade.hpp drawn_control). Off: the control point is the physics' one.
  bool control_jitter = false;

  template <class V>
  void visit(V& v) {
    v(height_min, "height_min", {.min = 0.01f, .max = 10.0f, .unit = "m", .help = "Shortest blade", .rebuild = Rebuild::kOffline});
    v(height_max, "height_max", {.min = 0.01f, .max = 10.0f, .unit = "m", .help = "Tallest blade", .rebuild = Rebuild::kOffline});
    v(width_min, "width_min", {.min = 0.0005f, .max = 1.0f, .unit = "m", .help = "Narrowest blade at the root", .rebuild = Rebuild::kOffline});
    v(width_max, "width_max", {.min = 0.0005f, .max = 1.0f, .unit = "m", .help = "Widest blade at the root", .rebuild = Rebuild::kOffline});
    v(min_height, "min_height", {.min = 0.001f, .max = 1.0f, .unit = "m",
                                 .help = "Lower bound on height after the height map scales it", .rebuild = Rebuild::kOffline});
    v(bend, "bend", {.min = 0.0f, .max = 0.95f, .help = "Rest bend: tip offset as a share of the height", .rebuild = Rebuild::kOffline});
    v(stiffness_min, "stiffness_min", {.min = 0.0f, .max = 1.0e6f, .unit = "1/s", .help = "Softest blade", .rebuild = Rebuild::kOffline});
    v(stiffness_max, "stiffness_max", {.min = 0.0f, .max = 1.0e6f, .unit = "1/s", .help = "Stiffest blade", .rebuild = Rebuild::kOffline});
    v(height_width_correlation, "height_width_correlation",
      {.min = 0.0f, .max = 1.0f, .help = "1 = tall blades are wide (seed 001), 0 = independent", .rebuild = Rebuild::kOffline});
    v(color_variation, "color_variation", {.min = 0.0f, .max = 1.0f, .help = "Per-blade colour jitter", .rebuild = Rebuild::kOffline});
    v(patch_variation, "patch_variation", {.min = 0.0f, .max = 1.0f, .help = "Lush/dry colour patches across the field",
                                           .rebuild = Rebuild::kOffline});
    v(patch_size, "patch_size", {.min = 0.5f, .max = 1000.0f, .unit = "m", .help = "Size of the colour patches",
                                 .rebuild = Rebuild::kOffline});
    v(clump_variation, "clump_variation", {.min = 0.0f, .max = 1.0f, .help = "Hue and brightness offset per clump of blades",
                                           .rebuild = Rebuild::kOffline});
    v(clump_size, "clump_size", {.min = 0.05f, .max = 20.0f, .unit = "m", .help = "Side of a clump cell",
                                 .rebuild = Rebuild::kOffline});
    v(control_jitter, "control_jitter",
      {.help = "Seed 001 eq. 2.4: jitter each blade's Bezier control point (r3 on x/z, r4 on y)", .rebuild = Rebuild::kOffline});
  }
};

// Blade physics after Jahrmann & Wimmer 2017 §4, integrated unconditionally stably (see
// physics.hpp for the scheme).
struct PhysicsSettings {
  float gravity = 9.81f;         // environmental gravity [m/s^2]
  float front_gravity = 0.25f;   // share of |g| pulling along the blade's front (paper: 1/4)
  float wind_response = 6.0f;    // tip speed per wind speed in the overdamped model [dimensionless]
  float collision_recovery = 1.5f;  // time constant of the decay of a blade's collision strength [s]
  float max_substep = 1.0f / 60.0f; // longest sub-step [s]; accuracy only, stability never depends on it
  int max_substeps = 4;          // upper bound on sub-steps per frame (cost bound)
  // A collision sphere that follows the camera (the walker's body), added to the field's own
  // colliders every frame; radius 0 turns it off. Centre = camera position + offset [m].
  float camera_collider_radius = 0.0f;
  glm::vec3 camera_collider_offset{0.0f, -1.2f, 0.0f};
  Seed001WindSettings seed001_wind;  // seed 001's own wind function instead of the scene's (off)

  template <class V>
  void visit(V& v) {
    v(gravity, "gravity", {.min = 0.0f, .max = 100.0f, .unit = "m/s^2", .help = "Gravity pulling blade tips down"});
    v(front_gravity, "front_gravity", {.min = 0.0f, .max = 4.0f, .help = "Share of gravity along the blade front"});
    v(wind_response, "wind_response", {.min = 0.0f, .max = 100.0f, .help = "How strongly wind pushes the tips"});
    v(collision_recovery, "collision_recovery", {.min = 0.01f, .max = 60.0f, .unit = "s",
                                                 .help = "How long a trampled blade stays weakened"});
    v(max_substep, "max_substep", {.min = 0.001f, .max = 1.0f, .unit = "s", .help = "Longest physics sub-step"});
    v(max_substeps, "max_substeps", {.min = 1.0f, .max = 64.0f, .help = "Most sub-steps per frame"});
    v(camera_collider_radius, "camera_collider_radius", {.min = 0.0f, .max = 100.0f, .unit = "m",
                                                         .help = "Sphere around the camera pushing blades aside (0 = off)"});
    v(camera_collider_offset, "camera_collider_offset", {.min = -100.0f, .max = 100.0f, .unit = "m",
                                                         .help = "Centre of the camera sphere relative to the camera"});
    v(seed001_wind, "seed001_wind");
  }
};

// Spacing of the blade tessellation along the blade (GLSL layout of grass/blade.tese). kEqual:
// integer levels (ceil), a blade's segment count jumps with distance (seed 001's code; its
// "LOD popping" pitfall); the fractional modes pass the level unrounded and the tessellator
// morphs the new segments in (GL 4.5 §11.2.2): even counts >= 2 / odd counts >= 1.
enum class TessSpacing { kEqual, kFractionalEven, kFractionalOdd };
constexpr std::array<EnumName<TessSpacing>, 3> enum_names(TessSpacing) {
  return {{{TessSpacing::kEqual, "equal"},
           {TessSpacing::kFractionalEven, "fractional_even"},
           {TessSpacing::kFractionalOdd, "fractional_odd"}}};
}

// Culling and blade LOD (seed 001 §3.7 eq. 2.3 and 4.3, §3.12; Jahrmann & Wimmer 2017 §5).
struct CullSettings {
  bool frustum = true;
  bool orientation = true;
  float orientation_threshold = 0.97f; // |dot(view, width dir)| above this is "edge-on" (paper: 0.9, see culling.hpp)
  float orientation_max_px = 0.75f;    // ... and only culled when its edge-on width is below this [px]
  bool distance_thinning = true;
  float near_distance = 50.0f;         // blades end here (d_max of seed 001) [m]
  float thinning_start = 12.0f;        // thinning starts here; 0 gives seed 001's 1 - d/d_max [m]
  float thinning_min_keep = 0.08f;     // share of blades still kept just before near_distance
  float width_compensation = 1.0f;     // 0..1: widen survivors by 1/keep so coverage stays
  float density_scale = 1.0f;          // global quality knob: share of each tile's blades used
  float max_tess_level = 8.0f;         // most segments along a blade (seed's smoothness factor s)
  float pixels_per_segment = 6.0f;     // one segment per this many projected pixels of blade height
  bool distance_tess_law = false;      // seed 001 eq. 2.3: segments from distance alone (culling.hpp)
  TessSpacing tess_spacing = TessSpacing::kEqual;  // fractional: no popping (seed 001 pitfall "LOD popping")

  template <class V>
  void visit(V& v) {
    v(frustum, "frustum", {.help = "Cull blades outside the view frustum"});
    v(orientation, "orientation", {.help = "Cull thin edge-on blades"});
    v(orientation_threshold, "orientation_threshold", {.min = 0.0f, .max = 1.0f,
                                                       .help = "|cos| between view and blade width above which a blade is edge-on"});
    v(orientation_max_px, "orientation_max_px", {.min = 0.0f, .max = 100.0f, .unit = "px",
                                                 .help = "Edge-on blades wider than this on screen are kept"});
    v(distance_thinning, "distance_thinning", {.help = "Thin blades out with distance"});
    v(near_distance, "near_distance", {.min = 0.5f, .max = 5000.0f, .unit = "m", .help = "Where blades end"});
    v(thinning_start, "thinning_start", {.min = 0.0f, .max = 5000.0f, .unit = "m", .help = "Where thinning starts"});
    v(thinning_min_keep, "thinning_min_keep", {.min = 0.0f, .max = 1.0f, .help = "Share kept just before the end"});
    v(width_compensation, "width_compensation", {.min = 0.0f, .max = 1.0f,
                                                 .help = "Widen surviving blades so thinning keeps coverage"});
    v(density_scale, "density_scale", {.min = 0.0f, .max = 1.0f, .help = "Share of blades used (quality)"});
    v(max_tess_level, "max_tess_level", {.min = 1.0f, .max = 64.0f, .help = "Most segments per blade"});
    v(pixels_per_segment, "pixels_per_segment", {.min = 0.5f, .max = 200.0f, .unit = "px",
                                                 .help = "Projected blade height per segment"});
    v(distance_tess_law, "distance_tess_law",
      {.help = "Seed 001 eq. 2.3: segments = ceil(max_tess_level (1 - d / near_distance)) instead of the projected size"});
    v(tess_spacing, "tess_spacing",
      {.help = "Tessellation spacing: equal (integer levels, segments pop), fractional_even or fractional_odd (segments morph)"});
  }
};

// Blade shading: two-sided diffuse with translucency, root darkening, per-blade colour.
struct ShadingSettings {
  float translucency = 0.5f;   // share of back light passing through a blade
  float ambient = 0.35f;       // ambient light level
  float root_occlusion = 0.7f; // how much darker the root is than the tip (0 = none)
  float specular = 0.15f;      // strength of a soft sheen
  bool receive_shadows = true; // sun light is multiplied by the render core's cascaded shadows
  // Seed 003 §3.4 motion by colour (off by default): every blade, clump and ground-layer texel
  // takes albedo x (1 + color_motion sin(2 pi color_motion_hz t + 2 pi phase)), phase random per
  // blade and per clump, 0 for the whole ground layer (the thesis's far pulse, in sync so that
  // tiles show no seams). field_color.hpp color_motion_uniform(), color.glsl grass_color_pulse().
  float color_motion = 0.0f;   // k1 of c = tex (1 + k1 s) [0, 1); 0 = off
  float color_motion_hz = 0.5f; // [Hz]

  template <class V>
  void visit(V& v) {
    v(translucency, "translucency", {.min = 0.0f, .max = 1.0f, .help = "Light passing through blades"});
    v(ambient, "ambient", {.min = 0.0f, .max = 2.0f, .help = "Ambient light"});
    v(root_occlusion, "root_occlusion", {.min = 0.0f, .max = 1.0f, .help = "Darkening towards the root"});
    v(specular, "specular", {.min = 0.0f, .max = 1.0f, .help = "Sheen strength"});
    v(receive_shadows, "receive_shadows", {.help = "Blades receive the sun's cascaded shadows"});
    v(color_motion, "color_motion", {.min = 0.0f, .max = 0.9f,
                                     .help = "Seed 003 motion by colour: amplitude of the sine-modulated brightness (0 = off)"});
    v(color_motion_hz, "color_motion_hz", {.min = 0.0f, .max = 10.0f, .unit = "Hz", .help = "Frequency of the colour motion"});
  }
};

}  // namespace sylva::grass
