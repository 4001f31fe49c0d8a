// Chunk-tree build time and triangles per level on both cores (ChunkTreeSettings::threads = 0)
// against one thread, for a generated 2k^2 fBm field.
#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/height_source.hpp>

#include <benchmark/benchmark.h>

namespace sylva::terrain {
namespace {

const HeightField& field() {
  static HeightField f = [] {
    GeneratedFieldSettings g;
    g.size = 2049;
    g.spacing = 2.0;
    g.height_scale = 900.0f;
    g.feature_size = 2000.0f;
    g.fbm.octaves = 9;
    return generate_height_field(g).value();
  }();
  return f;
}

void BM_BuildChunkTree(benchmark::State& state) {
  ChunkTreeSettings s;
  s.leaf_dimension = 65;
  s.threads = static_cast<int>(state.range(0));
  BuildReport report;
  for (auto _ : state) {
    auto t = ChunkTree::build(field(), s);
    report = t->report();
    benchmark::DoNotOptimize(report);
  }
  state.counters["threads"] = report.threads;
  state.counters["triangles"] = static_cast<double>(report.triangles());
  state.counters["error_grid_ms"] = report.error_grid_ms;
  state.counters["meshes_ms"] = report.meshes_ms;
  for (const LevelReport& l : report.levels) {
    state.counters["tris_L" + std::to_string(l.level)] = static_cast<double>(l.triangles);
  }
}
BENCHMARK(BM_BuildChunkTree)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace
}  // namespace sylva::terrain
