// L-system throughput: derivation (symbols per second) and full plant generation (derive +
// turtle) for the shipped species; a species table read from files as a user's is (issue #16)
// with its plant caches built.

#include <benchmark/benchmark.h>

#include <sylva/voxel/plant.hpp>
#include <sylva/voxel/species.hpp>
#include <sylva/voxel/worldgen.hpp>

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

// data/species.json and its grammars read from disk through load_species_table (the path of a
// scene's voxel.flora.species_file), then the generator's variant caches (seed §4.7) built:
// 6 species x variants_per_species plants.
void BM_LoadSpeciesTableAndBuildCaches(benchmark::State& state) {
  WorldGenSettings settings;
  settings.variants_per_species = static_cast<int>(state.range(0));
  std::size_t plants = 0;
  for (auto _ : state) {
    std::vector<std::string> warnings;
    auto table = load_species_table(std::string(SYLVA_VOXEL_DATA_DIR) + "/species.json", BlockPalette::standard(), warnings);
    if (!table.ok() || !table->rejected.empty()) {
      state.SkipWithError("species.json does not load");
      return;
    }
    const std::size_t species = table->species.size();
    auto g = WorldGenerator::create(settings, BlockPalette::standard(), std::make_shared<const SpeciesTable>(std::move(*table)));
    if (!g.ok()) {
      state.SkipWithError("the generator fails");
      return;
    }
    plants += species * static_cast<std::size_t>(settings.variants_per_species);
    benchmark::DoNotOptimize(g->get());
  }
  state.counters["plants_per_s"] = benchmark::Counter(static_cast<double>(plants), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_LoadSpeciesTableAndBuildCaches)->Arg(1)->Arg(12)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sylva::voxel
