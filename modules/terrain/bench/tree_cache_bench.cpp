// The chunk-tree cache (tree_cache.hpp, issue 15): what a launch pays for the tree of a field
// without a cache (ChunkTree::build), on the first launch (a miss: hash + build + write) and on
// every later one (a hit: hash + read + verify + decode). Both cores (threads = 0), default tree
// settings (leaf 33), fBm as in bench_terrain_bake. Field side via --benchmark_filter=.../4097.
// Wall time (UseRealTime): the cache is I/O as much as CPU. The hit reads a file the miss just
// wrote, so it is in the page cache (as on a second launch of the same scene).
#include "bench_fields.hpp"

#include <sylva/core/timer.hpp>
#include <sylva/terrain/height_source.hpp>
#include <sylva/terrain/tree_cache.hpp>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <unistd.h>

namespace sylva::terrain {
namespace {

const HeightField& field(int size) {
  static std::map<int, HeightField> fields;
  auto it = fields.find(size);
  if (it == fields.end()) {
    it = fields.emplace(size, bench_field(size)).first;
  }
  return it->second;
}

std::filesystem::path cache_dir(int size) {
  return std::filesystem::temp_directory_path() / fmt::format("sylva_tree_cache_bench_{}_{}", ::getpid(), size);
}

TreeCacheSettings cache_settings(int size) {
  TreeCacheSettings c;
  c.directory = cache_dir(size).string();
  c.min_samples = 0;
  return c;
}

void report(benchmark::State& state, const CachedChunkTree& t) {
  state.counters["key_ms"] = t.key_ms;
  state.counters["load_ms"] = t.load_ms;
  state.counters["build_ms"] = t.build_ms;
  state.counters["save_ms"] = t.save_ms;
  std::error_code ec;
  if (!t.file.empty()) state.counters["file_mb"] = static_cast<double>(std::filesystem::file_size(t.file, ec)) / 1e6;
  state.counters["triangles"] = static_cast<double>(t.tree.report().triangles());
}

void BM_Build(benchmark::State& state) {
  const HeightField& f = field(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    auto tree = ChunkTree::build(f, ChunkTreeSettings{});
    if (!tree) return state.SkipWithError(tree.error().describe().c_str());
    benchmark::DoNotOptimize(tree->chunk_count());
  }
}

void BM_CacheMiss(benchmark::State& state) {
  const int size = static_cast<int>(state.range(0));
  const HeightField& f = field(size);
  for (auto _ : state) {
    state.PauseTiming();
    std::filesystem::remove_all(cache_dir(size));
    state.ResumeTiming();
    auto t = build_or_load_chunk_tree(f, ChunkTreeSettings{}, cache_settings(size), {});
    if (!t || t->cache != TreeCacheOutcome::kMiss) return state.SkipWithError("not a miss");
    report(state, *t);
  }
}

void BM_CacheHit(benchmark::State& state) {
  const int size = static_cast<int>(state.range(0));
  const HeightField& f = field(size);
  for (auto _ : state) {
    auto t = build_or_load_chunk_tree(f, ChunkTreeSettings{}, cache_settings(size), {});
    if (!t || t->cache != TreeCacheOutcome::kHit) return state.SkipWithError("not a hit (run BM_CacheMiss first)");
    report(state, *t);
  }
  std::filesystem::remove_all(cache_dir(size));
}

// In this order in one run: the hit reads what the miss wrote.
BENCHMARK(BM_Build)->Arg(1025)->Arg(2049)->Arg(4097)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_CacheMiss)->Arg(1025)->Arg(2049)->Arg(4097)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_CacheHit)->Arg(1025)->Arg(2049)->Arg(4097)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace sylva::terrain
