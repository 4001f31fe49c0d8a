#include "support/terrain_test_support.hpp"

#include <sylva/core/noise.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <unordered_map>
#include <unistd.h>

namespace sylva::terrain::testing {

std::filesystem::path unique_temp(const std::string& name) {
  return std::filesystem::temp_directory_path() / fmt::format("sylva_terrain_{}_{}", ::getpid(), name);
}

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
  // Each directed edge a->b becomes (smaller end, larger end, +1 or -1); sorting brings the uses
  // of one undirected edge together and their signs must cancel.
  struct Use {
    Key key;
    int sign;
  };
  auto less = [](const glm::vec3& a, const glm::vec3& b) {
    if (bits(a.x) != bits(b.x)) return bits(a.x) < bits(b.x);
    if (bits(a.y) != bits(b.y)) return bits(a.y) < bits(b.y);
    return bits(a.z) < bits(b.z);
  };
  std::vector<Use> uses;
  uses.reserve(mesh.positions.size());
  for (std::size_t t = 0; t < mesh.triangles(); ++t) {
    if (mesh.kind[t] == PieceKind::kSkirt) continue;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 a = mesh.positions[3 * t + static_cast<std::size_t>(k)];
      const glm::vec3 b = mesh.positions[3 * t + static_cast<std::size_t>((k + 1) % 3)];
      uses.push_back(less(a, b) ? Use{make_key(a, b), 1} : Use{make_key(b, a), -1});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const Use& a, const Use& b) {
    return std::memcmp(a.key.v, b.key.v, sizeof(a.key.v)) < 0;
  });
  WatertightResult r;
  const double sp = frame.spacing;
  auto grid = [&](float x, float z) {
    return glm::dvec2((static_cast<double>(x) + frame.camera.x) / sp + frame.origin.x,
                      (static_cast<double>(z) + frame.camera.z) / sp + frame.origin.y);
  };
  auto as_float = [](std::uint32_t b) {
    float f;
    std::memcpy(&f, &b, 4);
    return f;
  };
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    int net = 0;
    while (j < uses.size() && uses[j].key == uses[i].key) net += uses[j++].sign;
    ++r.edges;
    if (net != 0) {
      const Key& key = uses[i].key;
      const glm::dvec2 ga = grid(as_float(key.v[0]), as_float(key.v[2]));
      const glm::dvec2 gb = grid(as_float(key.v[3]), as_float(key.v[5]));
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
                                  ga.y, gb.x, gb.y, as_float(key.v[1]), as_float(key.v[4]), net);
        }
      } else {
        ++r.boundary_edges;
      }
    }
    i = j;
  }
  (void)tree;
  return r;
}

}  // namespace sylva::terrain::testing



namespace sylva::terrain::testing {
PolygonMesh grid_cage(int n, double size, const std::function<float(double, double)>& h) {
  PolygonMesh m;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = size * i / n, z = size * j / n;
      m.positions.emplace_back(static_cast<float>(x), h(x, z), static_cast<float>(z));
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = static_cast<std::uint32_t>(j * (n + 1) + i);
      // Counter-clockwise seen from above (normal +y).
      m.face_sizes.push_back(4);
      m.face_indices.insert(m.face_indices.end(), {a, a + static_cast<std::uint32_t>(n + 1) , a + static_cast<std::uint32_t>(n + 2), a + 1});
    }
  }
  return m;
}

PolygonMesh overhang_cage(int n, double size, float lean) {
  PolygonMesh m = grid_cage(n, size, [&](double x, double z) {
    const double r = std::hypot(x - 0.5 * size, z - 0.5 * size) / size;
    return static_cast<float>(0.6 * size * std::exp(-12.0 * r * r) + 0.03 * size * std::sin(x * 0.3) * std::cos(z * 0.2));
  });
  for (glm::vec3& p : m.positions) p.x += lean * p.y * p.y / static_cast<float>(size);
  return m;
}
}  // namespace sylva::terrain::testing
