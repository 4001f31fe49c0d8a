// Meshing throughput: voxels per nanosecond (n^3 / time) and quads produced: the culled and
// greedy meshers on 32^3 and 64^3 random 50 %, terrain-like and checkerboard chunks, the bitmask
// mesher on every bench content and size 32, 48, 62, 63, 64, with and without AO.
// The same-run race with the public binary greedy mesher (cgerikj/binary-greedy-meshing) is a
// harness outside the repository (peer code stays out); README.md says how it is built.

#include <benchmark/benchmark.h>

#include "bench_chunks.hpp"

namespace sylva::voxel::bench {
namespace {

void BM_Mesh(benchmark::State& state) {
  const auto kind = static_cast<MesherKind>(state.range(0));
  const auto content = static_cast<Content>(state.range(1));
  const int n = static_cast<int>(state.range(2));
  const PaddedBlocks blocks = make_content(content, n);
  MesherOptions options;
  options.ambient_occlusion = state.range(3) != 0;
  auto mesher = make_mesher(kind, options);
  ChunkMesh mesh;
  for (auto _ : state) {
    mesher->mesh(blocks, BlockPalette::standard(), mesh);
    benchmark::DoNotOptimize(mesh.opaque.data());
  }
  const double voxels = static_cast<double>(n) * n * n;
  state.counters["voxels_per_ns"] =
      benchmark::Counter(voxels * static_cast<double>(state.iterations()) * 1e-9, benchmark::Counter::kIsRate);
  state.counters["quads"] = static_cast<double>(mesh.quad_count());
  state.SetLabel(std::string(to_string(kind)) + "/" + content_name(content) + "/" + std::to_string(n) +
                 (options.ambient_occlusion ? "" : "/no_ao"));
}

void args(benchmark::internal::Benchmark* b) {
  for (int n : {32, 64})
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 2; ++k) b->Args({k, c, n, 1});
  // The bitmask mesher on every content and on sizes between the specialised 32 and 64 (issue
  // #18: any size within 1.1x per voxel of the best one; 62 is the peer's chunk), with AO and
  // without (as the public binary greedy mesher measures).
  for (int ao : {1, 0})
    for (int n : {32, 48, 62, 63, 64})
      for (int c = 0; c < kContentCount; ++c) b->Args({2, c, n, ao});
}

BENCHMARK(BM_Mesh)->Apply(args)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace sylva::voxel::bench
