// World generation throughput: chunks per second for the generator alone (one thread) and for
// populate() + parallel meshing on the worker pool.

#include <benchmark/benchmark.h>

#include <sylva/voxel/world_builder.hpp>

namespace sylva::voxel {
namespace {

std::shared_ptr<const WorldGenerator> generator() {
  static auto g = [] {
    WorldGenSettings s;
    s.seed = 11;
    return *WorldGenerator::create(s);
  }();
  return g;
}

// One surface chunk column position after another (every chunk holds ground and plants).
void BM_GenerateChunk(benchmark::State& state) {
  auto g = generator();
  std::int64_t i = 0;
  for (auto _ : state) {
    const GeneratedChunk c = g->generate({i % 64, 0, i / 64});
    benchmark::DoNotOptimize(c.plants.data());
    ++i;
  }
  state.counters["chunks_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_GenerateChunk)->Unit(benchmark::kMicrosecond);

// A 9x9 chunk area (all generated chunk layers) populated and meshed with the bitmask mesher.
void BM_PopulateAndMesh(benchmark::State& state) {
  auto g = generator();
  WorkerPool pool(static_cast<int>(state.range(0)));
  std::int64_t y0, y1;
  chunk_y_range(g->settings(), y0, y1);
  std::size_t chunks = 0;
  std::int64_t shift = 0;
  for (auto _ : state) {
    World world;
    const auto coords = chunk_box({shift, 0, 0}, 4, y0, y1);
    shift += 100;
    populate(world, *g, coords, pool);
    remesh_parallel(world, pool, MesherKind::kBitmask);
    chunks += coords.size();
  }
  state.counters["chunks_per_s"] = benchmark::Counter(static_cast<double>(chunks), benchmark::Counter::kIsRate);
  state.SetLabel(std::to_string(state.range(0)) + " workers");
}
BENCHMARK(BM_PopulateAndMesh)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace sylva::voxel
