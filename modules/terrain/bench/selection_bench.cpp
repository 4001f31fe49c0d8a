// Triangles per frame and selection CPU time against tau along a fixed flight path over a
// generated 4k^2 (and 16k^2) fBm field, against brute force at full resolution and against the
// seed's distance criterion tuned to the same measured max pixel error (README, "Results").
//
//   bench_terrain_selection [--benchmark_filter=...]      (SYLVA_BENCH_16K=0 skips the 16k field)
#include <sylva/core/log.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/error_measure.hpp>
#include <sylva/terrain/frame_mesh.hpp>
#include <sylva/terrain/height_source.hpp>
#include <sylva/terrain/selection.hpp>

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>

namespace sylva::terrain {
namespace {

constexpr int kViewW = 1920, kViewH = 1080;
constexpr double kFovY = 1.0471975511965976;  // 60 degrees

struct BenchField {
  HeightField field;
  std::unique_ptr<ChunkTree> tree;
  std::vector<LodView> path;
  std::uint64_t brute_total = 0;  // every full-resolution triangle of the field
  double build_ms = 0.0;
};

// A straight flight across the field 120 m above the ground, looking ahead and slightly down,
// with a slow yaw swing: 64 frames.
std::vector<LodView> flight(const HeightField& f) {
  std::vector<LodView> out;
  const glm::dvec2 ext = f.extent();
  for (int i = 0; i < 64; ++i) {
    const double t = i / 63.0;
    const double x = f.origin().x + ext.x * (0.15 + 0.7 * t), z = f.origin().y + ext.y * (0.2 + 0.6 * t);
    const double y = f.height(x, z) + 120.0;
    const double yaw = 0.785 + 0.5 * std::sin(6.283 * t);
    const glm::dvec3 fwd(std::cos(yaw), -0.2, std::sin(yaw));
    out.push_back(LodView::perspective({x, y, z}, fwd, {0, 1, 0}, kFovY, kViewW, kViewH, 0.1, 1e7));
  }
  return out;
}

BenchField make_field(int size, bool keep_meshes) {
  BenchField b;
  GeneratedFieldSettings g;
  g.size = size;
  g.spacing = 2.0;
  g.height_scale = 1200.0f;
  g.feature_size = 3000.0f;
  g.fbm.octaves = 10;
  g.fbm.seed = 2024;
  b.field = generate_height_field(g).value();
  ChunkTreeSettings s;
  s.leaf_dimension = 65;
  s.keep_meshes = keep_meshes;
  Stopwatch w;
  b.tree = std::make_unique<ChunkTree>(std::move(ChunkTree::build(b.field, s)).value());
  b.build_ms = w.elapsed_ms();
  b.brute_total = 2ull * static_cast<std::uint64_t>(size - 1) * static_cast<std::uint64_t>(size - 1);
  b.path = flight(b.field);
  const BuildReport& r = b.tree->report();
  log_info("terrain bench: {}^2 field built in {:.0f} ms ({} threads), {} triangles over {} levels", size,
           r.total_ms, r.threads, r.triangles(), r.levels.size());
  for (const LevelReport& l : r.levels) {
    log_info("  level {}: {} chunks, {} triangles ({:.1f} % of its grid), max error {:.3f} m", l.level, l.chunks,
             l.triangles, 100.0 * l.triangles / std::max<double>(1.0, l.grid_triangles), l.max_error);
  }
  return b;
}

BenchField& field_4k() {
  static BenchField f = make_field(4097, true);
  return f;
}
BenchField& field_16k() {
  static BenchField f = make_field(16385, false);
  return f;
}
bool want_16k() {
  const char* e = std::getenv("SYLVA_BENCH_16K");
  return e == nullptr || std::string(e) != "0";
}

// Full-resolution triangles inside the frustum (the leaves' full grids of every visible leaf).
double brute_visible(const BenchField& b, const LodView& v) {
  const ChunkTree& t = *b.tree;
  const int leaf = t.levels() - 1;
  double tris = 0.0;
  const double grid = 2.0 * t.leaf_intervals() * t.leaf_intervals();
  for (std::uint32_t z = 0; z < t.chunks_per_side(leaf); ++z)
    for (std::uint32_t x = 0; x < t.chunks_per_side(leaf); ++x) {
      const std::uint32_t i = t.index(leaf, x, z);
      if (!t.chunk(i).present) continue;
      glm::dvec3 lo, hi;
      t.chunk_bounds(i, lo, hi);
      if (v.box_visible(lo, hi)) tris += grid;
    }
  return tris;
}

// Measured max projected error over every 8th frame of the flight (CPU rasterisation).
double measured_error(BenchField& b, const LodSettings& ls) {
  LodSelector sel(*b.tree);
  SeamCache seams;
  double worst = 0.0;
  for (std::size_t i = 0; i < b.path.size(); i += 8) {
    const Selection& s = sel.select(b.path[i], ls);
    const VertexFrame vf = make_vertex_frame(*b.tree, b.path[i], ls);
    const FrameMesh mesh = assemble_frame(*b.tree, s, vf, CrackFix::kSeams, seams);
    worst = std::max(worst, measure_projected_error(b.field, vf, mesh, b.path[i].k).max_px);
  }
  return worst;
}

// The seed's lod_distance whose measured max error matches `target_px` (bisection in log space).
double matching_lod_distance(BenchField& b, double target_px) {
  static std::map<double, double> cache;
  if (auto it = cache.find(target_px); it != cache.end()) return it->second;
  double lo = std::log(0.5), hi = std::log(5000.0);
  LodSettings ls;
  ls.criterion = LodCriterion::kSeedDistance;
  for (int it = 0; it < 14; ++it) {
    const double mid = 0.5 * (lo + hi);
    ls.lod_distance = static_cast<float>(std::exp(mid));
    // Larger lod_distance keeps detail longer: smaller error.
    if (measured_error(b, ls) > target_px) lo = mid; else hi = mid;
  }
  const double d = std::exp(hi);
  cache[target_px] = d;
  return d;
}

void run(benchmark::State& state, BenchField& b, LodSettings ls, bool report_error) {
  LodSelector sel(*b.tree);
  double tris = 0.0, chunks = 0.0, brute_vis = 0.0;
  for (const LodView& v : b.path) {
    const Selection& s = sel.select(v, ls);
    tris += static_cast<double>(s.stats.triangles);
    chunks += s.stats.chunks;
    brute_vis += brute_visible(b, v);
  }
  const double n = static_cast<double>(b.path.size());
  std::size_t i = 0;
  for (auto _ : state) {
    const Selection& s = sel.select(b.path[i], ls);
    benchmark::DoNotOptimize(s.chunks.data());
    i = (i + 1) % b.path.size();
  }
  state.counters["tri_per_frame"] = tris / n;
  state.counters["chunks"] = chunks / n;
  state.counters["pct_of_brute_visible"] = 100.0 * tris / brute_vis;
  state.counters["pct_of_brute_total"] = 100.0 * (tris / n) / static_cast<double>(b.brute_total);
  state.counters["lod_distance"] = ls.lod_distance;
  if (report_error && b.tree->has_meshes()) state.counters["max_err_px"] = measured_error(b, ls);
}

void BM_Select4k_ScreenSpace(benchmark::State& state) {
  LodSettings ls;
  ls.max_pixel_error = static_cast<float>(state.range(0)) / 10.0f;
  run(state, field_4k(), ls, true);
}
BENCHMARK(BM_Select4k_ScreenSpace)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);

// The seed's criterion with lod_distance tuned to the measured max error of tau = arg / 10.
void BM_Select4k_SeedDistanceAtSameError(benchmark::State& state) {
  BenchField& b = field_4k();
  LodSettings tau;
  tau.max_pixel_error = static_cast<float>(state.range(0)) / 10.0f;
  const double target = measured_error(b, tau);
  LodSettings ls;
  ls.criterion = LodCriterion::kSeedDistance;
  ls.lod_distance = static_cast<float>(matching_lod_distance(b, target));
  run(state, b, ls, true);
  state.counters["target_err_px"] = target;
}
BENCHMARK(BM_Select4k_SeedDistanceAtSameError)->Arg(10)->Unit(benchmark::kMillisecond);

void BM_BruteForce4k(benchmark::State& state) {
  BenchField& b = field_4k();
  double vis = 0.0;
  for (const LodView& v : b.path) vis += brute_visible(b, v);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(brute_visible(b, b.path[i]));
    i = (i + 1) % b.path.size();
  }
  state.counters["tri_per_frame_visible"] = vis / static_cast<double>(b.path.size());
  state.counters["tri_total"] = static_cast<double>(b.brute_total);
  state.counters["build_ms"] = b.build_ms;
}
BENCHMARK(BM_BruteForce4k)->Unit(benchmark::kMillisecond);

void BM_Select16k_ScreenSpace(benchmark::State& state) {
  if (!want_16k()) {
    state.SkipWithError("SYLVA_BENCH_16K=0");
    return;
  }
  LodSettings ls;
  ls.max_pixel_error = static_cast<float>(state.range(0)) / 10.0f;
  BenchField& b = field_16k();
  run(state, b, ls, false);
  state.counters["build_ms"] = b.build_ms;
}
BENCHMARK(BM_Select16k_ScreenSpace)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sylva::terrain
