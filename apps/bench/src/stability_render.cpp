// Stability cases of render (camera maths, sky and fog at extremes) and of the bench's built-in
// ground, rendered into a float framebuffer so a NaN in any shader output is counted.
#include "ground_target.hpp"
#include "stability.hpp"

#include <sylva/render/camera.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/shadow_cascades.hpp>

#include <fmt/format.h>

#include <cmath>

namespace sylva::bench {
namespace {

std::uint64_t non_finite(const glm::mat4& m) {
  std::uint64_t n = 0;
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) n += !std::isfinite(m[c][r]);
  }
  return n;
}

StabilityOutcome camera_far_from_origin() {
  StabilityOutcome o;
  double worst = 0.0;
  for (double d : {0.0, 1e5, 1e7, 1e9}) {
    render::Camera cam;
    cam.set_position(glm::dvec3(d, 250.0, -d));
    cam.set_yaw_pitch(0.3f, -0.2f);
    const glm::dvec3 object = cam.position() + glm::dvec3(1.25, -0.5, 3.0);
    const glm::mat4 model = cam.relative_model(object);
    o.nan_count += non_finite(model) + non_finite(cam.view_projection());
    const glm::dvec3 t(model[3][0], model[3][1], model[3][2]);
    worst = std::max(worst, glm::length(t - glm::dvec3(1.25, -0.5, 3.0)));
  }
  o.passed = worst <= 1e-6;
  o.detail = fmt::format("relative offset error of an object 3.3 m away, camera up to 1e9 m out: {:.2e} m", worst);
  return o;
}

StabilityOutcome camera_extreme_fov() {
  StabilityOutcome o;
  for (float fov : {1e-4f, 0.01f, 1.0f, 3.0f, 3.14f}) {
    for (float pitch : {-1.5707f, 0.0f, 1.5707f}) {
      render::Camera cam;
      cam.set_yaw_pitch(0.0f, pitch);
      cam.perspective().fov_y = fov;
      cam.set_aspect(256, 144);
      o.nan_count += non_finite(cam.view_projection());
      const render::Frustum f = cam.frustum();
      (void)f;
    }
  }
  o.passed = true;
  o.detail = "fov 1e-4..3.14 rad, pitch +-90 deg: projection matrices finite";
  return o;
}

// Cascaded shadow maps (seed 004 §3): for suns straight up (the seed's lookAt failure), at and
// below the horizon, zero and NaN, with the camera 1e9 m out and 3 or 4 cascades, every matrix
// stays finite and every cascade has a positive texel size.
StabilityOutcome shadow_cascades_extreme_suns() {
  StabilityOutcome o;
  int cases = 0, bad_texel = 0;
  for (double d : {0.0, 1e6, 1e9}) {
    for (const glm::vec3 sun : {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(1, 0, 0), glm::vec3(0.3f, -0.2f, 0.9f),
                                glm::vec3(0, 0, 0), glm::vec3(NAN, 1, 0), glm::vec3(1e-30f, 1, 1e-30f)}) {
      for (int count : {1, 4}) {
        render::Camera cam;
        cam.set_position(glm::dvec3(d, 300.0, -d));
        cam.set_yaw_pitch(0.7f, -1.5707f);
        cam.set_aspect(256, 144);
        render::ShadowSettings settings;
        settings.cascade_count = count;
        const render::ShadowCascades c = render::compute_shadow_cascades(cam, sun, settings);
        for (int i = 0; i < c.count; ++i) {
          o.nan_count += non_finite(c.cascades[i].relative_view_projection) + non_finite(c.cascades[i].relative_texture);
          bad_texel += !(c.cascades[i].texel_size > 0.0f && std::isfinite(c.cascades[i].texel_size));
        }
        o.nan_count += !std::isfinite(c.light_direction.x) + !std::isfinite(c.light_direction.y) +
                       !std::isfinite(c.light_direction.z);
        ++cases;
      }
    }
  }
  o.passed = o.nan_count == 0 && bad_texel == 0;
  o.detail = fmt::format("{} camera/sun/count combinations: {} non-finite matrix entries, {} cascades without a positive "
                         "texel size",
                         cases, o.nan_count, bad_texel);
  return o;
}

// Renders the built-in ground once into an RGBA32F target and counts non-finite pixels.
StabilityOutcome render_ground(const std::vector<Assignment>& sets, const CameraPose& pose, double time, float dt) {
  StabilityOutcome o;
  auto target = make_ground_target();
  const std::vector<ParamDescriptor> params = target->params();
  for (const Assignment& a : sets) {
    Status s = set_param(params, a.path, a.value);
    if (!s.ok()) {
      o.detail = s.error().message;
      return o;
    }
  }
  const glm::ivec2 size(96, 54);
  Status prepared = target->prepare(size);
  if (!prepared.ok()) {
    o.detail = prepared.error().message;
    return o;
  }
  auto fb = render::Framebuffer::create({.width = size.x, .height = size.y, .color_formats = {GL_RGBA32F}});
  if (!fb.ok()) {
    o.detail = fb.error().message;
    return o;
  }
  FrameOutput out;
  Status rendered = target->render({0, time, dt, pose}, *fb, out);
  if (!rendered.ok()) {
    o.detail = rendered.error().message;
    return o;
  }
  auto color = render::read_color(*fb);
  if (!color.ok()) {
    o.detail = color.error().message;
    return o;
  }
  const NonFiniteReport nf = find_non_finite(*color);
  o.nan_count = nf.count;
  float lo = INFINITY, hi = -INFINITY;
  for (float v : color->data()) {
    if (std::isfinite(v)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  o.passed = nf.count == 0 && std::isfinite(out.gpu_ms) && lo >= 0.0f;
  o.detail = fmt::format("{} non-finite values; colour range [{:.3f}, {:.3f}]; {} fragments", nf.count, lo, hi,
                         out.counts.fragments);
  return o;
}

}  // namespace

void add_render_stability_cases(std::vector<StabilityCase>& cases) {
  cases.push_back({"render", "camera_far_from_origin", "camera-relative model matrices keep an object's offset exact "
                   "(< 1e-6 m) with the camera 1e9 m from the origin; no NaN", false, camera_far_from_origin});
  cases.push_back({"render", "camera_extreme_fov", "projection finite for fov 1e-4..3.14 rad and pitch at +-90 deg",
                   false, camera_extreme_fov});
  cases.push_back({"render", "shadow_cascades_extreme_suns",
                   "cascade matrices finite and texel sizes positive for a vertical, horizon, below-horizon, zero and "
                   "NaN sun with the camera up to 1e9 m out looking straight down",
                   false, shadow_cascades_extreme_suns});
  cases.push_back({"render", "sun_at_zenith", "sky, fog and lighting with the sun straight up: no NaN pixel, colours >= 0",
                   true, [] {
                     return render_ground({{"lighting.sun_direction", "0,1,0"}},
                                          {{-1500.0, 430.0, 1500.0}, -45.0f, -16.0f, 60.0f}, 0.0, 0.0f);
                   }});
  cases.push_back({"render", "sun_below_horizon_dense_fog", "sun under the horizon and fog density 1/m: no NaN pixel",
                   true, [] {
                     return render_ground({{"lighting.sun_direction", "0.3,-0.9,0.1"}, {"lighting.fog_density", "1"}},
                                          {{-1500.0, 430.0, 1500.0}, -45.0f, -16.0f, 60.0f}, 1e7, 1.0f);
                   }});
  cases.push_back({"bench", "ground_camera_below_surface", "camera under the ground looking straight up: no NaN pixel",
                   true, [] {
                     return render_ground({}, {{0.0, -500.0, 0.0}, 0.0f, 89.9f, 60.0f}, 0.0, 0.0f);
                   }});
  cases.push_back({"bench", "ground_minimal_grid_narrow_fov", "2x2-vertex grid seen through a 0.01 deg lens: no NaN pixel",
                   true, [] {
                     return render_ground({{"ground.resolution", "2"}}, {{-1500.0, 430.0, 1500.0}, -45.0f, -16.0f, 0.01f},
                                          0.0, 0.0f);
                   }});
  cases.push_back({"bench", "ground_flat_and_huge", "height 0 and a 1e6 m ground with the camera 1e5 m out: no NaN pixel",
                   true, [] {
                     return render_ground({{"ground.height", "0"}, {"ground.size", "1e6"}},
                                          {{1e5, 100.0, -1e5}, 30.0f, -10.0f, 60.0f}, 0.0, 0.0f);
                   }});
}

}  // namespace sylva::bench
