// Cascade fitting for the sun's shadow maps; see shadow_cascades.hpp for the conventions.
#include <sylva/core/assert.hpp>
#include <sylva/render/shadow_cascades.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::render {
namespace {

float finite_or(float v, float fallback) { return std::isfinite(v) ? v : fallback; }

}  // namespace

std::array<float, kMaxShadowCascades> practical_splits(float near_plane, float far_plane, int count, float lambda) {
  SYLVA_ASSERT(near_plane > 0.0f && far_plane > near_plane, "practical_splits: near {} far {}", near_plane, far_plane);
  SYLVA_ASSERT(count >= 1 && count <= kMaxShadowCascades, "practical_splits: count {}", count);
  std::array<float, kMaxShadowCascades> out{};
  const double n = near_plane;
  const double f = far_plane;
  for (int i = 1; i <= count; ++i) {
    const double t = static_cast<double>(i) / count;
    const double log_split = n * std::pow(f / n, t);
    const double uniform_split = n + (f - n) * t;
    out[static_cast<std::size_t>(i - 1)] = static_cast<float>(lambda * log_split + (1.0 - lambda) * uniform_split);
  }
  out[static_cast<std::size_t>(count - 1)] = far_plane;  // exact, whatever the rounding
  for (int i = count; i < kMaxShadowCascades; ++i) out[static_cast<std::size_t>(i)] = far_plane;
  return out;
}

void light_basis(const glm::vec3& toward_light, glm::dvec3& right, glm::dvec3& up, glm::dvec3& back) {
  glm::dvec3 l(toward_light);
  const double len = glm::length(l);
  l = (std::isfinite(len) && len > 1e-12) ? l / len : glm::dvec3(0.0, 1.0, 0.0);
  // World +y is a fine "up" unless the light is (nearly) vertical: then lookAt's cross product
  // vanishes (seed §3.5.2 failure), so use world -z, which is perpendicular to a vertical light.
  const glm::dvec3 hint = std::abs(l.y) < 0.999 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(0.0, 0.0, -1.0);
  right = glm::normalize(glm::cross(hint, l));
  up = glm::cross(l, right);
  back = l;
}

float shadow_depth_bias(const ShadowSettings& settings, float n_dot_l, float cascade_scale) {
  const float nl = std::clamp(n_dot_l, 0.0f, 1.0f);
  return std::max(settings.slope_bias * (1.0f - nl), settings.min_bias) * cascade_scale;
}

float shadow_normal_offset(const ShadowSettings& settings, float n_dot_l, float texel) {
  const float nl = std::clamp(n_dot_l, -1.0f, 1.0f);
  const float sin_angle = std::sqrt(std::max(1.0f - nl * nl, 0.0f));
  return settings.normal_offset * static_cast<float>(std::clamp(settings.pcf_radius, 0, 3) + 1) * texel * sin_angle;
}

ShadowCascades compute_shadow_cascades(const Camera& camera, const glm::vec3& toward_sun, const ShadowSettings& in) {
  ShadowCascades out;
  const int count = std::clamp(in.cascade_count, 1, kMaxShadowCascades);
  const int resolution = std::clamp(in.resolution, 64, 8192);
  const PerspectiveParams& p = camera.perspective();
  const float near_plane = std::max(finite_or(p.near_plane, 0.1f), 1e-4f);
  float far_plane = std::clamp(finite_or(in.max_distance, 150.0f), near_plane * 1.01f, 1.0e7f);
  if (p.far_plane > 0.0f && std::isfinite(p.far_plane)) far_plane = std::clamp(p.far_plane, near_plane * 1.01f, far_plane);
  const float lambda = std::clamp(finite_or(in.split_lambda, 0.75f), 0.0f, 1.0f);
  const std::array<float, kMaxShadowCascades> splits = practical_splits(near_plane, far_plane, count, lambda);

  glm::dvec3 right, up, back;
  light_basis(toward_sun, right, up, back);
  out.count = count;
  out.light_direction = glm::vec3(back);
  out.light_right = glm::vec3(right);
  out.light_up = glm::vec3(up);
  out.view_forward = camera.forward();

  // Corner offset per metre of view depth: a slice corner at depth d lies d*k from the axis.
  const double tan_y = std::tan(std::clamp(static_cast<double>(finite_or(p.fov_y, 1.0f)), 1e-4, 3.1) * 0.5);
  const double tan_x = tan_y * std::clamp(static_cast<double>(finite_or(p.aspect, 1.0f)), 1e-3, 1e3);
  const double k2 = tan_x * tan_x + tan_y * tan_y;
  const glm::dvec3 cam = camera.position();
  const glm::dvec3 fwd(out.view_forward);
  const std::array<glm::vec4, 2> bias_scale{in.cascade_bias_scale, in.cascade_bias_scale_far};

  float slice_near = near_plane;
  for (int i = 0; i < count; ++i) {
    const double n = slice_near;
    const double f = splits[static_cast<std::size_t>(i)];
    // Smallest sphere through the slice's eight corners: its centre is on the view axis, at
    // equal distance from near and far corners; clamped to the far plane for wide slices.
    double c = 0.5 * (f + n) * (1.0 + k2);
    double r = 0.0;
    if (c >= f) {
      c = f;
      r = f * std::sqrt(k2);
    } else {
      r = std::sqrt((c - n) * (c - n) + n * n * k2);
    }
    // Round the radius up to 1/64 of itself in a power-of-two grid so float noise in fov or
    // aspect cannot change the texel size from frame to frame.
    const double quantum = std::exp2(std::ceil(std::log2(r)) - 6.0);
    r = std::ceil(r / quantum) * quantum;
    const double diameter = 2.0 * r;
    const double texel = diameter / resolution;

    // Sphere centre in world space, then in light coordinates (double), snapped to texels.
    const glm::dvec3 centre_world = cam + fwd * c;
    double lx = glm::dot(centre_world, right);
    double ly = glm::dot(centre_world, up);
    double lz = glm::dot(centre_world, back);
    if (in.snap_to_texels) {
      lx = std::floor(lx / texel) * texel;
      ly = std::floor(ly / texel) * texel;
      lz = std::floor(lz / texel) * texel;
    }
    // u = (dot(world, right) - lx + r) / d, with world = cam + rel:
    //   u = dot(rel, right)/d + (dot(cam, right) - lx + r)/d     (offset in double)
    const double ou = (glm::dot(cam, right) - lx + r) / diameter;
    const double ov = (glm::dot(cam, up) - ly + r) / diameter;
    // Reversed depth: 1 at the sun side of the sphere (lz + r), 0 at the far side (lz - r).
    const double oz = (glm::dot(cam, back) - (lz - r)) / diameter;
    glm::mat4 tex(0.0f);  // column-major: tex[col][row]
    for (int a = 0; a < 3; ++a) {
      tex[a][0] = static_cast<float>(right[a] / diameter);
      tex[a][1] = static_cast<float>(up[a] / diameter);
      tex[a][2] = static_cast<float>(back[a] / diameter);
    }
    tex[3] = glm::vec4(static_cast<float>(ou), static_cast<float>(ov), static_cast<float>(oz), 1.0f);
    // Clip space: x, y = 2u - 1, 2v - 1; z = depth (glClipControl zero-to-one).
    glm::mat4 to_clip(1.0f);
    to_clip[0][0] = 2.0f;
    to_clip[1][1] = 2.0f;
    to_clip[3][0] = -1.0f;
    to_clip[3][1] = -1.0f;

    ShadowCascade& sc = out.cascades[static_cast<std::size_t>(i)];
    sc.relative_texture = tex;
    sc.relative_view_projection = to_clip * tex;
    {
      // z' = z / (1 + E): the frustum's 0 <= z' <= 1 then spans E depth units more on the sun side.
      const double e = std::clamp(static_cast<double>(finite_or(in.caster_reach, 500.0f)), 0.0, 1.0e5) / diameter;
      glm::mat4 squeeze(1.0f);
      squeeze[2][2] = static_cast<float>(1.0 / (1.0 + e));
      sc.relative_cull = squeeze * sc.relative_view_projection;
    }
    sc.near_depth = static_cast<float>(n);
    sc.far_depth = static_cast<float>(f);
    sc.radius = static_cast<float>(r);
    sc.texel_size = static_cast<float>(texel);
    sc.bias_scale = std::max(finite_or(bias_scale[static_cast<std::size_t>(i / 4)][i % 4], 1.0f), 0.0f);
    sc.center = right * (lx) + up * (ly) + back * (lz);
    slice_near = static_cast<float>(f);
  }
  return out;
}

}  // namespace sylva::render
