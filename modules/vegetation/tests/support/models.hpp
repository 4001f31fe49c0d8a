#pragma once
// Test models: a small hand-built tree with every level and a zero-length branch, and cached
// generated presets (generation takes a moment in Debug builds).

#include <sylva/vegetation/generator.hpp>
#include <sylva/vegetation/tree_mesh.hpp>
#include <sylva/vegetation/tree_model.hpp>

#include <string>

namespace sylva::vegetation::testing {

// Trunk (4 m) with two level-1 branches, a level-2 and a level-3 branch, a zero-length level-2
// branch, and leaves on levels 1..3 (one at x = 0 of its branch). Valid; bending data assigned.
TreeModel small_tree(std::uint32_t seed = 7);

// A generated preset (cached per preset and seed).
const TreeModel& preset_tree(SpeciesPreset preset, std::uint32_t seed = 1);
const TreeMesh& preset_mesh(SpeciesPreset preset, std::uint32_t seed = 1);

// One large leaf (1 m x 1.4 m, its base 0.5 m up) facing +z on a short stalk.
TreeModel single_leaf();

// The seed's example shape of an OBJT file (extraction section 3.1) with two branches and a leaf.
std::string seed_example_objt();

}  // namespace sylva::vegetation::testing
