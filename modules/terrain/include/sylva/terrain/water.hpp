#pragma once
// A water plane at a fixed level (seed 002 §3.3: "a horizontal square intersecting the terrain
// creates the impression of a water level"; issue 15: Fresnel-blended sky reflection,
// depth-tinted, fogged; off by default). A render::Drawable that draws in Pass::kTransparent,
// after the opaque ground and the sky, into whatever framebuffer the host has bound.
//
// The plane is infinite: one full-screen triangle whose fragments intersect their view ray with
// y = level (camera-relative, so it reaches the horizon at any distance from the origin without
// precision loss) and write that depth, so the host's depth test hides the water behind nearer
// ground per sample (MSAA edges stay smooth). Per pixel (shaders/water.frag):
//  * Depth tint: the scene's depth is copied (blit, resolving MSAA) into a texture before the
//    draw; the point behind the water gives the vertical water depth, the refracted path
//    (Snell, n = 1.33) through it the Beer-Lambert transmittance exp(-absorption x path) per
//    channel, and the light scattered by the water body fills in (1 - T) x color x light. So
//    shallow water shows its bed, deep water turns to `color`. The colour behind is blended by
//    the fixed-function blend (dual-source: out = src0 + dst x src1), no colour copy.
//  * Reflection: Schlick's Fresnel (F0 = 0.02 for n = 1.33) between the water seen through and
//    the sky in the reflected direction, from render/lib/sky.glsl (the sky pass's own function,
//    so the horizon matches), plus an optional sun glint (normalised Blinn-Phong).
//  * Shore: the water fades in over the first `shore_fade_m` of vertical depth: no seam line.
//  * Ripples: eight procedural travelling waves (deep-water dispersion) perturb the normal; each
//    fades out once it is smaller than about two pixels, so far water does not shimmer.
//  * Fog: the render core's aerial perspective (render/lib/fog.glsl) to the water point.
// Limits: no reflection of the terrain itself (the sky only), no underwater view (a camera
// below the level draws no water), no refraction offset of the bed. When the bound framebuffer
// has no 32-bit float depth (every render::Framebuffer has one), the water is drawn as deep.
//
// Threading: the GL thread. Failure: create() returns kInvalidArgument for settings outside
// their ranges (naming "<prefix>.<key>") and kGl when the shader does not build.

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/render/drawable.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/vertex_array.hpp>

#include <glm/glm.hpp>

#include <array>
#include <memory>
#include <string>

namespace sylva::terrain {

struct WaterSettings {
  bool enabled = false;
  double level = 0.0;                           // world y of the surface [m]
  glm::vec3 color{0.010f, 0.040f, 0.045f};      // scattering albedo of deep water (linear RGB)
  glm::vec3 absorption{0.45f, 0.11f, 0.08f};    // Beer-Lambert extinction [1/m] per channel
  float shore_fade_m = 0.4f;                    // vertical depth over which the water fades in [m]
  float ripple_strength = 0.06f;                // slope of the ripples (0 = a mirror)
  float ripple_scale_m = 4.0f;                  // wavelength of the longest ripple [m]
  float ripple_speed = 1.0f;                    // x the deep-water phase speed (0 = frozen)
  float sun_glint = 1.0f;                       // strength of the sun's specular highlight (0 = off)

  template <class V>
  void visit(V& v) {
    v(enabled, "enabled", {.help = "Draw a water plane at `level` (off by default)"});
    v(level, "level", {.min = -1.0e6, .max = 1.0e6, .step = 0.5, .unit = "m",
      .help = "World height of the water surface"});
    v(color, "color", {.min = 0.0, .max = 1.0,
      .help = "Colour of deep water: the water body's scattering albedo (linear RGB)"});
    v(absorption, "absorption", {.min = 0.0, .max = 100.0, .unit = "1/m",
      .help = "Extinction per metre of water path per channel (Beer-Lambert); red is absorbed first"});
    v(shore_fade_m, "shore_fade_m", {.min = 0.0, .max = 100.0, .step = 0.05, .unit = "m",
      .help = "Water depth over which the surface fades in at the shore (0 = a hard edge)"});
    v(ripple_strength, "ripple_strength", {.min = 0.0, .max = 1.0, .step = 0.005,
      .help = "Slope of the animated ripples (0 = a flat mirror)"});
    v(ripple_scale_m, "ripple_scale_m", {.min = 0.05, .max = 1000.0, .unit = "m",
      .help = "Wavelength of the longest ripple; seven shorter ones follow", .log_scale = true});
    v(ripple_speed, "ripple_speed", {.min = 0.0, .max = 10.0, .step = 0.05,
      .help = "Ripple speed as a multiple of the deep-water phase speed (0 = frozen)"});
    v(sun_glint, "sun_glint", {.min = 0.0, .max = 10.0, .step = 0.05,
      .help = "Strength of the sun's specular glint on the water (0 = off)"});
  }
};

// One ripple: world wave vector k [rad/m] (direction x 2 pi / wavelength), angular frequency
// omega [rad/s] (deep water: sqrt(g |k|) x speed) and slope amplitude (a |k|).
struct RippleWave {
  glm::dvec2 k{0.0};
  double omega = 0.0;
  float slope = 0.0f;
};
constexpr int kRippleWaves = 8;
std::array<RippleWave, kRippleWaves> ripple_waves(const WaterSettings& s);

struct WaterFrameStats {
  bool drawn = false;          // the last draw() put the plane on screen (camera above it)
  bool scene_depth = false;    // the bound target's depth was copied for the depth tint
  std::size_t gpu_bytes = 0;   // the depth copy
};

class WaterRenderer final : public render::Drawable {
 public:
  // Needs a current GL 4.5 context. `prefix` names the settings in errors ("terrain.water").
  static Result<std::unique_ptr<WaterRenderer>> create(const WaterSettings& settings,
                                                       const std::string& prefix = "water");
  ~WaterRenderer() override;

  void update(const render::FrameContext& frame) override { (void)frame; }
  // Draws in Pass::kTransparent only (nothing when !enabled or the camera is below the level).
  void draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) override;

  WaterSettings& settings() { return settings_; }
  const WaterSettings& settings() const { return settings_; }
  const WaterFrameStats& frame_stats() const { return stats_; }

 private:
  WaterRenderer() = default;
  bool copy_scene_depth(glm::ivec2 size);

  WaterSettings settings_;
  WaterFrameStats stats_;
  render::Program program_;
  render::VertexArray vao_;         // empty: the full-screen triangle comes from gl_VertexID
  render::Framebuffer depth_copy_;  // single-sample depth of the host's target
  bool depth_warned_ = false;
};

// For hosts that read WaterSettings from a scene every frame: creates `water` the first time
// `wanted.enabled` is set (a scene without water compiles no water shader), then copies
// `wanted` into it. A failed creation is logged once per reason and leaves `water` null.
void sync_water(std::unique_ptr<WaterRenderer>& water, const WaterSettings& wanted, const std::string& prefix);

}  // namespace sylva::terrain
