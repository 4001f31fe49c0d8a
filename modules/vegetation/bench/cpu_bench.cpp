// CPU kernels of the vegetation module: tree generation, mesh building, the CPU reference of the
// animation per vertex, texture generation, placement, and loading a species file.
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/height_field.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/vegetation/animation.hpp>
#include <sylva/vegetation/generator.hpp>
#include <sylva/vegetation/objt.hpp>
#include <sylva/vegetation/placement.hpp>
#include <sylva/vegetation/species_file.hpp>
#include <sylva/vegetation/textures.hpp>
#include <sylva/vegetation/tree_mesh.hpp>

#include <benchmark/benchmark.h>

#include <filesystem>
#include <unistd.h>

namespace {

using namespace sylva;
using namespace sylva::vegetation;

void BM_GenerateTree(benchmark::State& state) {
  const TreeSpecies s = species_preset(static_cast<SpeciesPreset>(state.range(0)));
  std::size_t leaves = 0;
  for (auto _ : state) {
    Result<TreeModel> m = generate_tree(s);
    leaves = m->leaves.size();
    benchmark::DoNotOptimize(m.ok());
  }
  state.counters["leaves"] = static_cast<double>(leaves);
}
BENCHMARK(BM_GenerateTree)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

void BM_BuildMesh(benchmark::State& state) {
  const TreeModel m = generate_tree(species_preset(SpeciesPreset::kBroadleaf)).value();
  std::size_t vertices = 0;
  for (auto _ : state) {
    const TreeMesh mesh = build_tree_mesh(m);
    vertices = mesh.branch_vertices.size() + mesh.leaf_vertices.size();
    benchmark::DoNotOptimize(mesh.bounds_max);
  }
  state.counters["vertices"] = static_cast<double>(vertices);
}
BENCHMARK(BM_BuildMesh)->Unit(benchmark::kMillisecond);

void BM_CpuDeformTree(benchmark::State& state) {
  const TreeMesh mesh = build_tree_mesh(generate_tree(species_preset(SpeciesPreset::kBroadleaf)).value());
  const WindField wind;
  const AnimationGpu anim = make_animation_gpu(AnimationSettings{}, 3.0);
  const WindGpuParams wp = wind.frame(3.0).gpu;
  const InstanceGpu inst = make_instance_gpu(TreeInstance{}, glm::dvec3(0.0), glm::vec3(6.0f, 0.0f, 2.0f));
  for (auto _ : state) {
    glm::vec3 acc(0.0f);
    for (const BranchVertex& v : mesh.branch_vertices) acc += deform_branch_vertex(mesh.data, anim, inst, v).position;
    for (const LeafVertex& v : mesh.leaf_vertices) acc += deform_leaf_vertex(mesh.data, anim, inst, wp, v).position;
    benchmark::DoNotOptimize(acc);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(mesh.branch_vertices.size() + mesh.leaf_vertices.size()));
}
BENCHMARK(BM_CpuDeformTree)->Unit(benchmark::kMillisecond);

void BM_LeafTextures(benchmark::State& state) {
  LeafTextureSettings s = leaf_texture_settings_for(LeafShape::kOvate);
  s.size = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(generate_leaf_textures(s).ok());
}
BENCHMARK(BM_LeafTextures)->Arg(128)->Arg(256)->Unit(benchmark::kMillisecond);

// A species file naming the preset's tree written as OBJT (issue #16): read, parse, validate
// and scale; what a scene pays per species file before textures and the slice bake.
void BM_LoadSpeciesFile(benchmark::State& state) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("sylva_bench_species_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const TreeModel model = generate_tree(species_preset(static_cast<SpeciesPreset>(state.range(0)))).value();
  if (!save_objt(dir / "tree.objt", model).ok() ||
      !write_file_atomic(dir / "tree.json", R"({"model": {"objt": "tree.objt"}, "units": 1.5})").ok()) {
    state.SkipWithError("cannot write the species files");
    return;
  }
  std::size_t bytes = std::filesystem::file_size(dir / "tree.objt");
  for (auto _ : state) {
    std::vector<std::string> warnings;
    Result<SpeciesFile> s = load_species_file(dir / "tree.json", warnings);
    benchmark::DoNotOptimize(s.ok());
  }
  state.counters["branches"] = static_cast<double>(model.branches.size());
  state.counters["leaves"] = static_cast<double>(model.leaves.size());
  state.counters["MB/s"] = benchmark::Counter(static_cast<double>(bytes), benchmark::Counter::kIsIterationInvariantRate);
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_LoadSpeciesFile)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_PoissonPlacement(benchmark::State& state) {
  HeightField ground(257, 257, 4.0);
  PlacementSettings s;
  s.min_distance = 8.0f;
  std::size_t trees = 0;
  for (auto _ : state) {
    Result<std::vector<TreeInstance>> t = place_poisson_disk(ground, s);
    trees = t->size();
  }
  state.counters["trees"] = static_cast<double>(trees);
}
BENCHMARK(BM_PoissonPlacement)->Unit(benchmark::kMillisecond);

}  // namespace
