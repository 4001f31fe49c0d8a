#include "brush.hpp"

#include <sylva/core/noise.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::editor {

float falloff_weight(Falloff falloff, double t) {
  if (!(t < 1.0)) return 0.0f;  // also NaN
  t = std::max(t, 0.0);
  switch (falloff) {
    case Falloff::kConstant:
      return 1.0f;
    case Falloff::kLinear:
      return static_cast<float>(1.0 - t);
    case Falloff::kSmooth: {
      const double s = 1.0 - t;
      return static_cast<float>(s * s * (3.0 - 2.0 * s));
    }
    case Falloff::kGaussian: {
      // exp(-4.5 t^2) shifted and scaled so it reaches exactly 0 at the rim.
      const double e = std::exp(-4.5 * t * t), rim = std::exp(-4.5);
      return static_cast<float>((e - rim) / (1.0 - rim));
    }
  }
  return 0.0f;
}

scene::TexelRect dab_rect(const scene::MapGrid& grid, glm::dvec2 center, double radius) {
  if (grid.empty() || !(radius > 0.0)) return {};
  const glm::dvec2 lo = grid.texel(center - radius), hi = grid.texel(center + radius);
  scene::TexelRect r{static_cast<int>(std::floor(lo.x)), static_cast<int>(std::floor(lo.y)),
                     static_cast<int>(std::ceil(hi.x)) + 1, static_cast<int>(std::ceil(hi.y)) + 1};
  r = r.intersect(grid.bounds());
  // Shrink to the texels strictly inside the circle.
  scene::TexelRect tight{r.x1, r.y1, r.x0, r.y0};
  for (int j = r.y0; j < r.y1; ++j) {
    for (int i = r.x0; i < r.x1; ++i) {
      if (glm::distance(grid.world(i, j), center) < radius) {
        tight.x0 = std::min(tight.x0, i);
        tight.y0 = std::min(tight.y0, j);
        tight.x1 = std::max(tight.x1, i + 1);
        tight.y1 = std::max(tight.y1, j + 1);
      }
    }
  }
  return tight.empty() ? scene::TexelRect{} : tight;
}

std::vector<glm::dvec2> stroke_dabs(std::span<const glm::dvec2> points, double spacing) {
  std::vector<glm::dvec2> dabs;
  if (points.empty()) return dabs;
  dabs.push_back(points[0]);
  double carry = 0.0;  // distance travelled since the last dab
  for (std::size_t k = 1; k < points.size(); ++k) {
    const glm::dvec2 a = points[k - 1], b = points[k];
    const double len = glm::distance(a, b);
    if (!(len > 0.0)) continue;
    double s = spacing - carry;
    while (s <= len) {
      dabs.push_back(a + (b - a) * (s / len));
      s += spacing;
    }
    carry = len - (s - spacing);
  }
  return dabs;
}

float sample_grid(const scene::MapGrid& grid, glm::dvec2 world) {
  const glm::dvec2 t = glm::clamp(grid.texel(world), glm::dvec2(0.0), glm::dvec2(grid.width - 1, grid.height - 1));
  const int i0 = static_cast<int>(std::floor(t.x)), j0 = static_cast<int>(std::floor(t.y));
  const int i1 = std::min(i0 + 1, grid.width - 1), j1 = std::min(j0 + 1, grid.height - 1);
  const double fx = t.x - i0, fy = t.y - j0;
  const double top = grid.at(i0, j0) * (1.0 - fx) + grid.at(i1, j0) * fx;
  const double bottom = grid.at(i0, j1) * (1.0 - fx) + grid.at(i1, j1) * fx;
  return static_cast<float>(top * (1.0 - fy) + bottom * fy);
}

float resolve_target(const scene::MapGrid& grid, const BrushSettings& brush, glm::dvec2 first_dab) {
  if (brush.use_target) return brush.target;
  if (brush.op == BrushOp::kFlatten) return sample_grid(grid, first_dab);
  if (brush.op == BrushOp::kErase) return 0.0f;
  return 1.0f;  // paint
}

std::array<std::string, 3> color_channel_ids(const std::string& color_map_id) {
  return {color_map_id + "_r", color_map_id + "_g", color_map_id + "_b"};
}

BrushSettings color_channel_brush(const BrushSettings& brush, int channel) {
  BrushSettings b = brush;
  if (brush.op == BrushOp::kPaint || brush.op == BrushOp::kErase) {
    b.target = brush.op == BrushOp::kPaint ? brush.color[channel] : 1.0f;
    b.op = BrushOp::kPaint;
    b.use_target = true;
  }
  return b;
}

scene::TexelRect apply_dab(scene::MapGrid& grid, scene::MapKind kind, const BrushSettings& brush, glm::dvec2 center,
                           float target) {
  const scene::TexelRect r = dab_rect(grid, center, brush.radius);
  if (r.empty()) return {};
  // Smooth reads the 3x3 neighbourhoods from the values before this dab.
  std::vector<float> before;
  scene::TexelRect ring;
  if (brush.op == BrushOp::kSmooth) {
    ring = scene::TexelRect{r.x0 - 1, r.y0 - 1, r.x1 + 1, r.y1 + 1}.intersect(grid.bounds());
    before = grid.copy_rect(ring);
  }
  auto old_value = [&](int i, int j) {
    i = std::clamp(i, ring.x0, ring.x1 - 1);
    j = std::clamp(j, ring.y0, ring.y1 - 1);
    return before[static_cast<std::size_t>(j - ring.y0) * static_cast<std::size_t>(ring.width()) +
                  static_cast<std::size_t>(i - ring.x0)];
  };
  FbmSettings noise;
  noise.octaves = 3;
  noise.frequency = 1.0f / std::max(brush.noise_scale, 1e-3f);
  noise.seed = brush.seed;
  if (brush.op == BrushOp::kErase && !brush.use_target) target = 0.0f;

  scene::TexelRect changed{r.x1, r.y1, r.x0, r.y0};
  for (int j = r.y0; j < r.y1; ++j) {
    for (int i = r.x0; i < r.x1; ++i) {
      const glm::dvec2 p = grid.world(i, j);
      const float w = falloff_weight(brush.falloff, glm::distance(p, center) / brush.radius);
      if (!(w > 0.0f)) continue;
      float& v = grid.at(i, j);
      const float a = std::clamp(brush.strength * w, 0.0f, 1.0f);
      float nv = v;
      switch (brush.op) {
        case BrushOp::kRaise:
          nv = v + brush.strength * w;
          break;
        case BrushOp::kLower:
          nv = v - brush.strength * w;
          break;
        case BrushOp::kPaint:
        case BrushOp::kErase:
        case BrushOp::kFlatten:
          nv = v + (target - v) * a;
          break;
        case BrushOp::kSmooth: {
          float sum = 0.0f;
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) sum += old_value(i + di, j + dj);
          nv = v + (sum / 9.0f - v) * a;
          break;
        }
        case BrushOp::kNoise:
          nv = v + brush.strength * w * fbm2(p, noise);
          break;
      }
      if (kind == scene::MapKind::kUnit) nv = std::clamp(nv, 0.0f, 1.0f);
      if (!std::isfinite(nv)) continue;
      if (nv == v) continue;
      v = nv;
      changed.x0 = std::min(changed.x0, i);
      changed.y0 = std::min(changed.y0, j);
      changed.x1 = std::max(changed.x1, i + 1);
      changed.y1 = std::max(changed.y1, j + 1);
    }
  }
  return changed.empty() ? scene::TexelRect{} : changed;
}

}  // namespace sylva::editor
