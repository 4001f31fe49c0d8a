#include "support/terrain_test_support.hpp"

#include <sylva/core/noise.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <unordered_map>

namespace sylva::terrain::testing {

HeightField make_field(int columns, int rows, double spacing, const std::function<float(int, int)>& height,
                       glm::dvec2 origin) {
  HeightField f(columns, rows, spacing, origin);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) f.sample(i, j) = height(i, j);
  f.update_range();
  return f;
}

HeightField fbm_field(int columns, int rows, double spacing, float amplitude, std::uint32_t seed, glm::dvec2 origin) {
  FbmSettings s;
  s.octaves = 7;
  s.seed = seed;
  s.frequency = 1.0f / 64.0f;
  return make_field(columns, rows, spacing, [&](int i, int j) {
    return amplitude * 0.5f * (1.0f + fbm2(glm::vec2(static_cast<float>(i), static_cast<float>(j)), s));
  }, origin);
}

HeightField cliff_field(int columns, int rows, double spacing, float cliff_height, std::uint32_t seed) {
  FbmSettings s;
  s.octaves = 5;
  s.seed = seed;
  s.frequency = 1.0f / 48.0f;
  return make_field(columns, rows, spacing, [&](int i, int j) {
    const float base = 0.5f * (1.0f + fbm2(glm::vec2(static_cast<float>(i), static_cast<float>(j)), s));
    const float terrace = std::floor(base * 4.0f) / 4.0f;  // steps: vertical cliffs between samples
    return cliff_height * terrace + 0.1f * cliff_height * base;
  });
}

LodView look_at_view(const glm::dvec3& eye, const glm::dvec3& target, double fov_deg, int width, int height) {
  return LodView::perspective(eye, target - eye, glm::dvec3(0, 1, 0), glm::radians(fov_deg), width, height, 0.05, 1e7);
}

LodView random_view(std::mt19937& rng, const ChunkTree& tree, const HeightField& field, const PoseOptions& o) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const glm::dvec2 ext = field.extent();
  const double x = field.origin().x + (-0.2 + 1.4 * u01(rng)) * ext.x;
  const double z = field.origin().y + (-0.2 + 1.4 * u01(rng)) * ext.y;
  const double ground = field.height(x, z);
  const double alt = o.min_altitude * std::pow(o.max_altitude / o.min_altitude, u01(rng));
  const double y = o.below_ground ? ground - alt : ground + alt;
  const double yaw = u01(rng) * 2.0 * 3.14159265358979;
  const double pitch = glm::radians(o.min_pitch_deg + (o.max_pitch_deg - o.min_pitch_deg) * u01(rng));
  const glm::dvec3 fwd(std::cos(pitch) * std::cos(yaw), std::sin(pitch), std::cos(pitch) * std::sin(yaw));
  const double fov = o.min_fov_deg + (o.max_fov_deg - o.min_fov_deg) * u01(rng);
  (void)tree;
  return LodView::perspective({x, y, z}, fwd, {0, 1, 0}, glm::radians(fov), o.width, o.height, 0.05, 1e7);
}

namespace {
struct Key {
  std::uint32_t v[6];
  bool operator==(const Key& o) const { return std::memcmp(v, o.v, sizeof(v)) == 0; }
};
struct KeyHash {
  std::size_t operator()(const Key& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint32_t x : k.v) h = (h ^ x) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};
std::uint32_t bits(float f) {
  std::uint32_t b;
  std::memcpy(&b, &f, 4);
  return b;
}
Key make_key(const glm::vec3& a, const glm::vec3& b) {
  return Key{{bits(a.x), bits(a.y), bits(a.z), bits(b.x), bits(b.y), bits(b.z)}};
}
}  // namespace

WatertightResult check_watertight(const ChunkTree& tree, const LodSelector& selector, const VertexFrame& frame,
                                  const FrameMesh& mesh) {
  // Net use of each directed edge: +1 for a->b, -1 for b->a, keyed by the lexicographically
  // smaller end first.
  std::unordered_map<Key, int, KeyHash> net;
  std::unordered_map<Key, std::pair<glm::vec3, glm::vec3>, KeyHash> ends;
  auto less = [](const glm::vec3& a, const glm::vec3& b) {
    if (bits(a.x) != bits(b.x)) return bits(a.x) < bits(b.x);
    if (bits(a.y) != bits(b.y)) return bits(a.y) < bits(b.y);
    return bits(a.z) < bits(b.z);
  };
  for (std::size_t t = 0; t < mesh.triangles(); ++t) {
    if (mesh.kind[t] == PieceKind::kSkirt) continue;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 a = mesh.positions[3 * t + static_cast<std::size_t>(k)];
      const glm::vec3 b = mesh.positions[3 * t + static_cast<std::size_t>((k + 1) % 3)];
      if (less(a, b)) {
        const Key key = make_key(a, b);
        net[key] += 1;
        ends.emplace(key, std::make_pair(a, b));
      } else {
        const Key key = make_key(b, a);
        net[key] -= 1;
        ends.emplace(key, std::make_pair(b, a));
      }
    }
  }
  WatertightResult r;
  r.edges = net.size();
  const double sp = frame.spacing;
  auto grid = [&](const glm::vec3& p) {
    return glm::dvec2((static_cast<double>(p.x) + frame.camera.x) / sp + frame.origin.x,
                      (static_cast<double>(p.z) + frame.camera.z) / sp + frame.origin.y);
  };
  for (const auto& [key, count] : net) {
    if (count == 0) continue;
    const auto& [a, b] = ends.at(key);
    const glm::dvec2 ga = grid(a), gb = grid(b);
    const glm::dvec2 mid = 0.5 * (ga + gb);
    bool crack = true;
    const double eps = 1e-3;
    if (std::fabs(ga.x - gb.x) < eps) {  // along z on the line x = ga.x
      const std::int64_t lx = std::llround(ga.x), cz = static_cast<std::int64_t>(std::floor(mid.y));
      crack = selector.drawn_chunk_at_cell(lx - 1, cz) != kNoChunk && selector.drawn_chunk_at_cell(lx, cz) != kNoChunk;
    } else if (std::fabs(ga.y - gb.y) < eps) {  // along x on the line z = ga.y
      const std::int64_t lz = std::llround(ga.y), cx = static_cast<std::int64_t>(std::floor(mid.x));
      crack = selector.drawn_chunk_at_cell(cx, lz - 1) != kNoChunk && selector.drawn_chunk_at_cell(cx, lz) != kNoChunk;
    }
    if (crack) {
      ++r.crack_edges;
      if (r.crack_edges <= 5) {
        r.report += fmt::format("unbalanced edge ({:.3f},{:.3f})-({:.3f},{:.3f}) grid, y {} / {}, net {}\n", ga.x,
                                ga.y, gb.x, gb.y, a.y, b.y, count);
      }
    } else {
      ++r.boundary_edges;
    }
  }
  (void)tree;
  return r;
}

}  // namespace sylva::terrain::testing
