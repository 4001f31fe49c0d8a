// L-system throughput: derivation (symbols per second) and full plant generation (derive +
// turtle) for the shipped species.

#include <benchmark/benchmark.h>

#include <sylva/voxel/plant.hpp>

#include <map>
#include <string>
#include <vector>

namespace sylva::voxel {
namespace {

const LSystem& grammar(const char* file, std::size_t index = 0) {
  static std::map<std::string, std::vector<LSystem>> cache;
  auto it = cache.find(file);
  if (it == cache.end()) it = cache.emplace(file, *load_builtin_lsystems(file)).first;
  return it->second.at(index);
}

void BM_DeriveAcacia(benchmark::State& state) {
  const LSystem& s = grammar("acacia.lsys");
  const int n = static_cast<int>(state.range(0));
  std::size_t symbols = 0;
  std::uint64_t salt = 0;
  for (auto _ : state) {
    auto r = derive(s, n, ++salt);
    symbols += r->size();
    benchmark::DoNotOptimize(r->data());
  }
  state.counters["symbols_per_s"] = benchmark::Counter(static_cast<double>(symbols), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DeriveAcacia)->Arg(4)->Arg(6)->Arg(8)->Unit(benchmark::kMicrosecond);

void BM_GeneratePlant(benchmark::State& state) {
  static const char* kFiles[] = {"acacia.lsys", "broadleaf.lsys", "jungle.lsys", "bushes.lsys"};
  const LSystem& s = grammar(kFiles[state.range(0)]);
  LSystemExecutorSettings e;
  e.min_derivations = e.max_derivations = static_cast<int>(state.range(1));
  std::size_t parts = 0;
  std::uint64_t salt = 0;
  for (auto _ : state) {
    auto m = generate_plant(s, e, ++salt);
    parts += m->part_count();
    benchmark::DoNotOptimize(m->outputs.data());
  }
  state.counters["plants_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["parts_per_plant"] = static_cast<double>(parts) / static_cast<double>(state.iterations());
  state.SetLabel(kFiles[state.range(0)]);
}
BENCHMARK(BM_GeneratePlant)->Args({0, 5})->Args({1, 5})->Args({2, 5})->Args({3, 4})->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace sylva::voxel
