// Out-of-core bake (bake.hpp) against the in-memory ChunkTree::build (+ save_chunk_file) of the same
// field, in one run. Both cores (threads = 0), default tree settings (leaf 33). The bake runs
// first, so the process's peak RSS after it is the bake's own (the field moved in and released);
// the in-memory rows report the peak after them (max RSS only grows; the caller keeps its field).
// Field size via --benchmark_filter=.../4097 or /16385. Iterations(1): a 4k run takes minutes.
#include "bench_fields.hpp"

#include <sylva/terrain/bake.hpp>
#include <sylva/terrain/chunk_file.hpp>
#include <sylva/terrain/height_source.hpp>

#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <filesystem>

namespace sylva::terrain {
namespace {

double peak_rss_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

std::filesystem::path out_file(const char* name) {
  return std::filesystem::temp_directory_path() / fmt::format("sylva_bake_bench_{}_{}", ::getpid(), name);
}

void BM_Bake(benchmark::State& state) {
  // A fresh field, not cached: the peak RSS holds one field, as a bake of a raster file does.
  HeightField f = bench_field(static_cast<int>(state.range(0)));
  const auto out = out_file("baked.sylvaterrain");
  BakeReport report;
  for (auto _ : state) {
    auto r = bake_chunk_file(std::move(f), out, BakeOptions{});  // released once in the height grid
    if (!r) {
      state.SkipWithError(r.error().describe().c_str());
      return;
    }
    report = *r;
  }
  state.counters["peak_rss_mib"] = peak_rss_mib();
  state.counters["grids_ms"] = report.prepare_ms;
  state.counters["meshes_ms"] = report.meshes_ms;
  state.counters["merge_ms"] = report.merge_ms;
  state.counters["file_mb"] = static_cast<double>(report.bytes) / 1e6;
  state.counters["triangles"] = static_cast<double>(report.triangles);
  std::filesystem::remove(out);
}
BENCHMARK(BM_Bake)->Arg(4097)->Arg(16385)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

void BM_InMemoryBuild(benchmark::State& state) {
  const HeightField f = bench_field(static_cast<int>(state.range(0)));  // fresh, not cached: one field in the peak RSS, as a bake of a raster file
  const auto out = out_file("memory.sylvaterrain");
  const bool save = state.range(1) != 0;
  ChunkTreeSettings settings;
  settings.keep_meshes = state.range(2) != 0;  // 16k: metadata only (its meshes need ~17 GB)
  for (auto _ : state) {
    auto tree = ChunkTree::build(f, settings);
    if (!tree) {
      state.SkipWithError(tree.error().describe().c_str());
      return;
    }
    if (save && !save_chunk_file(out, *tree, 0, &f).ok()) state.SkipWithError("save failed");  // as the bake: with the ground
    state.counters["triangles"] = static_cast<double>(tree->report().triangles());
  }
  state.counters["peak_rss_mib"] = peak_rss_mib();
  std::filesystem::remove(out);
}
BENCHMARK(BM_InMemoryBuild)->Args({4097, 0, 1})->Args({4097, 1, 1})->Args({16385, 0, 0})->Unit(benchmark::kSecond)
    ->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace sylva::terrain
