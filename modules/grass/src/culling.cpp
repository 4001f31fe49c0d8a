#include <sylva/grass/culling.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::grass {

namespace {

glm::vec4 normalize_plane(const glm::vec4& p) {
  const float len = glm::length(glm::vec3(p));
  return len > 0.0f ? p / len : p;
}

bool sphere_outside(const CullView& view, const glm::vec3& c, float r) {
  for (const glm::vec4& p : view.planes) {
    if (glm::dot(glm::vec3(p), c) + p.w < -r) return true;
  }
  // Behind the camera (the side planes meet at the eye, so this only trims the mirror cone).
  return glm::dot(view.forward, c - view.camera) < -r;
}

}  // namespace

CullView make_cull_view(const glm::mat4& vp, const glm::vec3& camera, const glm::vec3& forward,
                        float viewport_height_px, float fov_y_radians) {
  CullView v;
  const glm::vec4 row0(vp[0][0], vp[1][0], vp[2][0], vp[3][0]);
  const glm::vec4 row1(vp[0][1], vp[1][1], vp[2][1], vp[3][1]);
  const glm::vec4 row3(vp[0][3], vp[1][3], vp[2][3], vp[3][3]);
  v.planes[0] = normalize_plane(row3 + row0);
  v.planes[1] = normalize_plane(row3 - row0);
  v.planes[2] = normalize_plane(row3 + row1);
  v.planes[3] = normalize_plane(row3 - row1);
  v.camera = camera;
  v.forward = glm::normalize(forward);
  v.pixels_per_radian = viewport_height_px / (2.0f * std::tan(0.5f * fov_y_radians));
  return v;
}

const char* to_string(CullResult result) {
  switch (result) {
    case CullResult::kVisible: return "visible";
    case CullResult::kDensity: return "density";
    case CullResult::kDistance: return "distance";
    case CullResult::kFrustum: return "frustum";
    case CullResult::kOrientation: return "orientation";
  }
  return "?";
}

float distance_keep(float distance, const CullSettings& s) {
  if (!s.distance_thinning) return distance < s.near_distance ? 1.0f : 0.0f;
  if (!(distance < s.near_distance)) return 0.0f;
  const float start = std::min(s.thinning_start, s.near_distance);
  if (distance <= start) return 1.0f;
  const float t = (distance - start) / std::max(s.near_distance - start, 1e-6f);
  return glm::mix(1.0f, s.thinning_min_keep, std::clamp(t, 0.0f, 1.0f));
}

float width_scale(float keep, const CullSettings& s) {
  const float compensated = 1.0f / std::max(keep, 0.25f);
  return glm::mix(1.0f, compensated, std::clamp(s.width_compensation, 0.0f, 1.0f));
}

CullResult cull_blade(const Blade& blade, const CullView& view, const CullSettings& s) {
  const float rank = blade.rank();
  if (!(rank < s.density_scale)) return CullResult::kDensity;
  const glm::vec3 v0 = blade.root();
  const float distance = glm::length(v0 - view.camera);
  const float keep = distance_keep(distance, s) * s.density_scale;
  if (!(rank < keep)) return CullResult::kDistance;
  const float half_width = 0.5f * blade.width() * width_scale(keep, s);
  if (s.frustum) {
    const glm::vec3 v1 = drawn_control(blade);  // the drawn curve's hull (seed 001 eq. 2.4 jitter)
    const glm::vec3 lo = glm::min(glm::min(v0, v1), blade.tip());
    const glm::vec3 hi = glm::max(glm::max(v0, v1), blade.tip());
    const glm::vec3 c = 0.5f * (lo + hi);
    const float r = 0.5f * glm::length(hi - lo) + half_width;
    if (sphere_outside(view, c, r)) return CullResult::kFrustum;
  }
  if (s.orientation && distance > 0.0f) {
    const glm::vec3 view_dir = (v0 - view.camera) / distance;
    const float c = std::abs(glm::dot(view_dir, blade_width_dir(blade.up_dir(), blade.orientation())));
    if (c > s.orientation_threshold) {
      const float edge_px = 2.0f * half_width * std::sqrt(std::max(1.0f - c * c, 0.0f)) * view.pixels_per_radian / distance;
      if (edge_px < s.orientation_max_px) return CullResult::kOrientation;
    }
  }
  return CullResult::kVisible;
}

float tessellation_level(const Blade& blade, const CullView& view, const CullSettings& s) {
  // Seed 001 pitfall "LOD popping": equal spacing needs the ceil, fractional spacing morphs.
  const bool ceiled = s.tess_spacing == TessSpacing::kEqual;
  const float max_level = std::max(s.max_tess_level, 1.0f);
  if (s.distance_tess_law) {  // seed 001 eq. 2.3 (culling.hpp)
    const float d = glm::length(blade.root() - view.camera);
    const float raw = s.max_tess_level * (1.0f - d / std::max(s.near_distance, 1e-3f));
    const float n = ceiled ? std::ceil(raw) : raw;
    return std::clamp(std::isfinite(n) ? n : 1.0f, 1.0f, max_level);
  }
  const glm::vec3 mid = bezier_point(blade.root(), drawn_control(blade), blade.tip(), 0.5f);
  const float distance = std::max(glm::length(mid - view.camera), 1e-3f);
  const float px = blade.height() * view.pixels_per_radian / distance;
  const float raw = px / std::max(s.pixels_per_segment, 1e-3f);
  return std::clamp(ceiled ? std::ceil(raw) : raw, 1.0f, max_level);
}

int spacing_segments(float level, TessSpacing spacing) {
  const float l = std::isfinite(level) ? level : 64.0f;
  switch (spacing) {
    case TessSpacing::kFractionalEven: return 2 * static_cast<int>(std::ceil(0.5f * std::clamp(l, 2.0f, 64.0f)));
    case TessSpacing::kFractionalOdd: return 2 * static_cast<int>(std::ceil(0.5f * (std::clamp(l, 1.0f, 63.0f) + 1.0f))) - 1;
    case TessSpacing::kEqual: break;
  }
  return static_cast<int>(std::ceil(std::clamp(l, 1.0f, 64.0f)));
}

int tessellation_segments(const Blade& blade, const CullView& view, const CullSettings& s) {
  const float level = tessellation_level(blade, view, s);
  if (s.tess_spacing == TessSpacing::kEqual) return static_cast<int>(level);
  return spacing_segments(level, s.tess_spacing);
}

std::uint32_t blades_per_draw(float max_tess_level, TessSpacing spacing) {
  // The shaders clamp segments to max_tess_level and the tessellator rounds a fractional level
  // up (equal_spacing; to the next even or odd integer for the fractional modes) and caps it at
  // GL_MAX_TESS_GEN_LEVEL (64 everywhere we run).
  const float level = std::isfinite(max_tess_level) ? std::clamp(std::ceil(max_tess_level), 1.0f, 64.0f) : 64.0f;
  const std::uint32_t segments = spacing == TessSpacing::kEqual
                                     ? static_cast<std::uint32_t>(level)
                                     : static_cast<std::uint32_t>(spacing_segments(level, spacing));
  const std::uint32_t vertices = 2u * (segments + 1u);
  return std::max<std::uint32_t>(kTessVerticesPerDraw / vertices, 1u);
}

bool tile_visible(const GrassTile& tile, const CullView& view, const CullSettings& s) {
  const glm::vec3 nearest = glm::clamp(view.camera, tile.bounds_min, tile.bounds_max);
  if (!(glm::length(nearest - view.camera) < s.near_distance)) return false;
  if (!s.frustum) return true;
  for (const glm::vec4& p : view.planes) {
    // The box corner farthest along the plane normal.
    const glm::vec3 n(p);
    const glm::vec3 far_corner(n.x >= 0 ? tile.bounds_max.x : tile.bounds_min.x,
                               n.y >= 0 ? tile.bounds_max.y : tile.bounds_min.y,
                               n.z >= 0 ? tile.bounds_max.z : tile.bounds_min.z);
    if (glm::dot(n, far_corner) + p.w < 0.0f) return false;
  }
  return true;
}

void CullCounts::add(CullResult r) {
  ++considered;
  switch (r) {
    case CullResult::kVisible: ++visible; break;
    case CullResult::kDensity: ++density; break;
    case CullResult::kDistance: ++distance; break;
    case CullResult::kFrustum: ++frustum; break;
    case CullResult::kOrientation: ++orientation; break;
  }
}

CullCounts cull_blade_set(const BladeSet& set, const CullView& view, const CullSettings& s) {
  CullCounts counts;
  for (const GrassTile& tile : set.tiles) {
    if (!tile_visible(tile, view, s)) {
      const glm::vec3 nearest = glm::clamp(view.camera, tile.bounds_min, tile.bounds_max);
      const bool too_far = !(glm::length(nearest - view.camera) < s.near_distance);
      counts.considered += tile.count;
      (too_far ? counts.distance : counts.frustum) += tile.count;
      continue;
    }
    for (std::uint32_t i = tile.first; i < tile.first + tile.count; ++i) {
      const CullResult r = cull_blade(set.blades[i], view, s);
      counts.add(r);
      if (r == CullResult::kVisible) counts.segments += static_cast<std::uint64_t>(tessellation_segments(set.blades[i], view, s));
    }
  }
  return counts;
}

}  // namespace sylva::grass
