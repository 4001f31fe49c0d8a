// CPU kernels of the vegetation module: tree generation, mesh building, the CPU reference of the
// animation per vertex, texture generation and placement.
#include <sylva/core/height_field.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/vegetation/animation.hpp>
#include <sylva/vegetation/generator.hpp>
#include <sylva/vegetation/placement.hpp>
#include <sylva/vegetation/textures.hpp>
#include <sylva/vegetation/tree_mesh.hpp>

#include <benchmark/benchmark.h>

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
