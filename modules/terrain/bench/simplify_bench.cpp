// Simplification throughput and error on the same general-model segments: the QEM reducer with
// locked borders (default), the seed's shortest-edge collapse, and meshoptimizer 0.18
// meshopt_simplify with meshopt_SimplifyLockBorder. Input: a Catmull-Clark refined terrain cage
// with overhangs (about 1 M triangles) split into 16 segments by centroid (seed §4.1); each
// segment is reduced to 25 % of its triangles. Counters: input M triangles per second, the
// measured Hausdorff error (max over segments) and the triangles reached. meshopt_lock_border
// includes the compaction of each segment (as the QEM reducers do inside their call);
// meshopt_lock_border_precompacted times meshopt_simplify alone on copies made beforehand.
#include <sylva/terrain/mesh.hpp>
#include <sylva/terrain/simplify.hpp>
#include <sylva/terrain/subdivision.hpp>

#include <benchmark/benchmark.h>
#include <meshoptimizer.h>

#include <cmath>
#include <map>
#include <unordered_map>

namespace sylva::terrain {
namespace {

struct Segments {
  std::vector<glm::vec3> positions;
  std::vector<std::vector<std::uint32_t>> segments;  // triangle lists
  std::vector<std::uint8_t> locked;                   // border vertices of any segment
  std::size_t triangles = 0;
};

PolygonMesh cage(int n, double size) {
  PolygonMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = size * i / n, z = size * j / n;
      const double r = std::hypot(x - 0.5 * size, z - 0.5 * size) / size;
      const double y = 0.5 * size * std::exp(-10.0 * r * r) + 0.05 * size * std::sin(x * 0.05) * std::cos(z * 0.07);
      m.positions.emplace_back(static_cast<float>(x + 0.6 * y * y / size), static_cast<float>(y), static_cast<float>(z));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = static_cast<std::uint32_t>(j * (n + 1) + i);
      m.face_sizes.push_back(4);
      m.face_indices.insert(m.face_indices.end(), {a, a + static_cast<std::uint32_t>(n + 1), a + static_cast<std::uint32_t>(n + 2), a + 1});
    }
  return m;
}

Segments& segments() {
  static Segments s = [] {
    SubdivisionSettings sd;
    sd.level = 4;
    const TriangleMesh m = triangulate(subdivide(cage(44, 1000.0), sd).value());  // 44^2 * 256 * 2 ~ 1 M
    Segments out;
    out.positions = m.positions;
    out.triangles = m.triangle_count();
    const int side = 4;
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : m.positions) {
      lo = glm::min(lo, glm::vec2(p.x, p.z));
      hi = glm::max(hi, glm::vec2(p.x, p.z));
    }
    const float cell = std::max(hi.x - lo.x, hi.y - lo.y) / side;
    out.segments.resize(side * side);
    std::vector<int> owner(m.triangle_count());
    std::vector<int> vcell(m.positions.size());
    auto cell_of = [&](float x, float z) {
      const int cx = std::clamp(static_cast<int>((x - lo.x) / cell), 0, side - 1);
      const int cz = std::clamp(static_cast<int>((z - lo.y) / cell), 0, side - 1);
      return cz * side + cx;
    };
    for (std::size_t v = 0; v < m.positions.size(); ++v) vcell[v] = cell_of(m.positions[v].x, m.positions[v].z);
    out.locked.assign(m.positions.size(), 0);
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      glm::vec3 c(0.0f);
      for (int k = 0; k < 3; ++k) c += m.positions[m.indices[3 * t + k]];
      const int s = cell_of(c.x / 3.0f, c.z / 3.0f);
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = m.indices[3 * t + k];
        out.segments[static_cast<std::size_t>(s)].push_back(v);
        if (vcell[v] != s) out.locked[v] = 1;  // seed §4.2 border rule (both cases)
      }
    }
    for (const auto& [a, b] : boundary_edges(m.indices)) out.locked[a] = out.locked[b] = 1;
    return out;
  }();
  return s;
}

enum class Method { kQem, kQemPasses, kSeed, kMeshopt, kMeshoptOnly };

std::vector<std::uint32_t> reduce(Method method, const Segments& s, const std::vector<std::uint32_t>& seg,
                                  SimplifyStats* st) {
  const std::size_t target = seg.size() / 3 / 4;
  if (method == Method::kQem) return simplify_qem(s.positions, seg, s.locked, target, st);
  if (method == Method::kQemPasses) return simplify_qem_passes(s.positions, seg, s.locked, target, st);
  if (method == Method::kSeed) return simplify_shortest_edge(s.positions, seg, s.locked, target, st);
  if (method == Method::kMeshoptOnly) {
    // meshopt_simplify alone: the compact copy of every segment is made once, outside the timing
    // (the fairest comparison; the QEM reducers compact inside their call).
    struct Compact {
      std::vector<std::uint32_t> global, li;
      std::vector<glm::vec3> pos;
    };
    static std::map<const std::vector<std::uint32_t>*, Compact> cache;
    auto [it, inserted] = cache.try_emplace(&seg);
    Compact& c = it->second;
    if (inserted) {
      std::unordered_map<std::uint32_t, std::uint32_t> local;
      c.li.resize(seg.size());
      for (std::size_t i = 0; i < seg.size(); ++i) {
        auto [l, fresh] = local.try_emplace(seg[i], static_cast<std::uint32_t>(c.global.size()));
        if (fresh) c.global.push_back(seg[i]);
        c.li[i] = l->second;
      }
      for (std::uint32_t g : c.global) c.pos.push_back(s.positions[g]);
    }
    std::vector<std::uint32_t> out(c.li.size());
    const std::size_t n = meshopt_simplify(out.data(), c.li.data(), c.li.size(), &c.pos[0].x, c.pos.size(),
                                           sizeof(glm::vec3), target * 3, 1.0f, meshopt_SimplifyLockBorder, nullptr);
    out.resize(n);
    for (std::uint32_t& v : out) v = c.global[v];
    return out;
  }
  // meshoptimizer on a compact copy of the segment (it sizes its work arrays by vertex count).
  std::unordered_map<std::uint32_t, std::uint32_t> local;
  std::vector<std::uint32_t> global, li(seg.size());
  for (std::size_t i = 0; i < seg.size(); ++i) {
    auto [it, inserted] = local.try_emplace(seg[i], static_cast<std::uint32_t>(global.size()));
    if (inserted) global.push_back(seg[i]);
    li[i] = it->second;
  }
  std::vector<glm::vec3> pos(global.size());
  for (std::size_t i = 0; i < global.size(); ++i) pos[i] = s.positions[global[i]];
  std::vector<std::uint32_t> out(li.size());
  const std::size_t n = meshopt_simplify(out.data(), li.data(), li.size(), &pos[0].x, pos.size(), sizeof(glm::vec3),
                                         target * 3, 1.0f, meshopt_SimplifyLockBorder, nullptr);
  out.resize(n);
  for (std::uint32_t& v : out) v = global[v];
  return out;
}

void BM_Simplify(benchmark::State& state, Method method) {
  const Segments& s = segments();
  std::vector<std::vector<std::uint32_t>> results(s.segments.size());
  std::size_t passes = 0;
  for (auto _ : state) {
    passes = 0;
    for (std::size_t i = 0; i < s.segments.size(); ++i) {
      SimplifyStats st;
      results[i] = reduce(method, s, s.segments[i], &st);
      passes = std::max(passes, st.passes);
    }
    benchmark::DoNotOptimize(results.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(s.triangles));
  double err = 0.0, out_tris = 0.0;
  std::size_t borders_kept = 0, flipped = 0, bad = 0;
  for (std::size_t i = 0; i < s.segments.size(); ++i) {
    err = std::max(err, hausdorff_distance(s.positions, s.segments[i], results[i]).max());
    out_tris += static_cast<double>(results[i].size() / 3);
    borders_kept += boundary_edges(results[i]) == boundary_edges(s.segments[i]);
    flipped += count_flipped(s.positions, s.segments[i], results[i]);
    const MeshCheck c = check_mesh(s.positions, results[i]);
    bad += c.degenerate + c.non_manifold + c.duplicate;
  }
  state.counters["input_tris"] = static_cast<double>(s.triangles);
  state.counters["max_passes"] = static_cast<double>(passes);
  state.counters["output_tris"] = out_tris;
  state.counters["hausdorff_m"] = err;
  state.counters["segments_outline_kept"] = static_cast<double>(borders_kept);
  state.counters["flipped"] = static_cast<double>(flipped);
  state.counters["degenerate_or_nonmanifold"] = static_cast<double>(bad);
}
BENCHMARK_CAPTURE(BM_Simplify, qem, Method::kQem)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_CAPTURE(BM_Simplify, qem_passes, Method::kQemPasses)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_CAPTURE(BM_Simplify, seed_shortest_edge, Method::kSeed)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_CAPTURE(BM_Simplify, meshopt_lock_border, Method::kMeshopt)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_CAPTURE(BM_Simplify, meshopt_lock_border_precompacted, Method::kMeshoptOnly)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

}  // namespace
}  // namespace sylva::terrain
