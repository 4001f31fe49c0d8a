#pragma once
// Procedural tree generator: species settings -> TreeModel. Deterministic for a seed (every random
// draw comes from a PCG32 stream keyed by (seed, branch id), so the same settings give the same
// tree on every machine and build type).
//
// Structure (seed 000 §4.3.1: branches are cones, leaves are quads; the bending model assumes
// straight rest branches, §6.1, so every branch is one straight tapered tube):
//  * trunk_count roots (1 for a tree, several stems for a shrub) of trunk_length, leaning by up to
//    trunk_lean_deg, spread by trunk_spread_deg when there are several;
//  * levels - 1 branching levels, each with its LevelSettings: `count` children per parent spread
//    from x = start to x = end in nodes of `per_node` (1 alternate/spiral, 2 opposite, >2 whorls),
//    rotated by `roll_deg` from node to node (137.5 deg: the golden angle of spiral phyllotaxis);
//    child axis at angle_deg from the parent axis, then bent towards +y (gravitropism > 0) or -y
//    (< 0); length = parent length * length_ratio * profile(x) where the level-1 profile is the
//    crown shape and deeper levels shorten towards the parent's tip;
//  * radii by the da Vinci rule (Leonardo; Eloy 2011): a branch's base cross-section equals its
//    tip's plus its children's, r_base^D = r_tip^D + sum r_child^D, with D = da_vinci_exponent
//    (2 = area preserving), computed bottom-up from twig_radius at every branch tip. The trunk
//    radius follows from the number of twigs, as in real trees;
//  * leaves on the last `leaves.levels` branch levels: `per_metre` along the branch from
//    x = leaves.start, in the chosen arrangement, at petiole_angle_deg from the branch, drooping
//    and turned towards the sky (phototropism), plus an optional terminal leaf.
// Each branch then gets its bending constants from its taper and its amplitude limit from
// max_length_error (bending.hpp, tree_model.hpp assign_bending_data).
//
// Failure: generate_tree validates the settings (kInvalidArgument naming the parameter path) and
// caps the output (kLimit naming the count) instead of exhausting memory.

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/vegetation/tree_model.hpp>

#include <array>
#include <cstdint>
#include <string>

namespace sylva::vegetation {

enum class CrownShape { kConical, kSpherical, kColumnar };
constexpr std::array<EnumName<CrownShape>, 3> enum_names(CrownShape) {
  return {{{CrownShape::kConical, "conical"}, {CrownShape::kSpherical, "spherical"}, {CrownShape::kColumnar, "columnar"}}};
}

enum class LeafArrangement { kAlternate, kOpposite, kWhorled, kSpiral };
constexpr std::array<EnumName<LeafArrangement>, 4> enum_names(LeafArrangement) {
  return {{{LeafArrangement::kAlternate, "alternate"},
           {LeafArrangement::kOpposite, "opposite"},
           {LeafArrangement::kWhorled, "whorled"},
           {LeafArrangement::kSpiral, "spiral"}}};
}

// Outline family of the procedural leaf texture (textures.hpp).
enum class LeafShape { kOvate, kElliptic, kBirch, kNeedles };
constexpr std::array<EnumName<LeafShape>, 4> enum_names(LeafShape) {
  return {{{LeafShape::kOvate, "ovate"}, {LeafShape::kElliptic, "elliptic"}, {LeafShape::kBirch, "birch"},
           {LeafShape::kNeedles, "needles"}}};
}

struct LevelSettings {
  int count = 6;                      // children per parent branch
  float count_variation = 0.2f;       // relative random spread of count
  float start = 0.3f;                 // x of the first child on the parent
  float end = 0.95f;                  // x of the last child
  int per_node = 1;                   // children per node: 1 alternate/spiral, 2 opposite, >2 whorl
  float roll_deg = 137.5f;            // rotation about the parent from one node to the next
  float angle_deg = 45.0f;            // angle between child and parent axes
  float angle_variation_deg = 10.0f;  // random spread of the angle
  float length_ratio = 0.6f;          // child length / parent length
  float length_variation = 0.15f;     // relative random spread of the length
  float length_profile = 0.6f;        // 0: every child as long; 1: full crown / tip profile
  float gravitropism = 0.0f;          // bend of the axis towards +y (> 0) or -y (< 0)

  template <class V>
  void visit(V& v) {
    v(count, "count", {.min = 0, .max = 64, .help = "Children per parent branch", .rebuild = Rebuild::kOffline});
    v(count_variation, "count_variation", {.min = 0.0, .max = 1.0, .help = "Relative random spread of the count", .rebuild = Rebuild::kOffline});
    v(start, "start", {.min = 0.0, .max = 1.0, .help = "Position of the first child along the parent", .rebuild = Rebuild::kOffline});
    v(end, "end", {.min = 0.0, .max = 1.0, .help = "Position of the last child along the parent", .rebuild = Rebuild::kOffline});
    v(per_node, "per_node", {.min = 1, .max = 8, .help = "Children per node (2 opposite, >2 whorl)", .rebuild = Rebuild::kOffline});
    v(roll_deg, "roll_deg", {.min = 0.0, .max = 360.0, .unit = "deg", .help = "Rotation about the parent between nodes", .rebuild = Rebuild::kOffline});
    v(angle_deg, "angle_deg", {.min = 0.0, .max = 180.0, .unit = "deg", .help = "Angle between child and parent axes", .rebuild = Rebuild::kOffline});
    v(angle_variation_deg, "angle_variation_deg", {.min = 0.0, .max = 90.0, .unit = "deg", .help = "Random spread of the angle", .rebuild = Rebuild::kOffline});
    v(length_ratio, "length_ratio", {.min = 0.0, .max = 2.0, .help = "Child length relative to the parent", .rebuild = Rebuild::kOffline});
    v(length_variation, "length_variation", {.min = 0.0, .max = 1.0, .help = "Relative random spread of the length", .rebuild = Rebuild::kOffline});
    v(length_profile, "length_profile", {.min = 0.0, .max = 1.0, .help = "Strength of the crown / tip length profile", .rebuild = Rebuild::kOffline});
    v(gravitropism, "gravitropism", {.min = -2.0, .max = 2.0, .help = "Bend towards +y (>0) or -y (<0)", .rebuild = Rebuild::kOffline});
  }
};

struct LeafSettings {
  int levels = 1;                          // leaves on the last `levels` branch levels (0 = none)
  float per_metre = 12.0f;                 // leaves per metre of branch
  int max_per_branch = 48;
  float start = 0.25f;                     // x of the first leaf
  float width = 0.05f;                     // [m]
  float length = 0.08f;                    // [m]
  float size_variation = 0.2f;             // relative random spread of the size
  LeafArrangement arrangement = LeafArrangement::kAlternate;
  float petiole_angle_deg = 50.0f;         // angle between the leaf axis and the branch
  float droop = 0.3f;                      // tilt of the leaf axis towards -y
  float phototropism = 0.6f;               // how much the leaf normal turns to the sky [0, 1]
  float orientation_jitter = 0.25f;        // random turn of the leaf frame [rad]
  bool terminal_leaf = true;               // one leaf at every leafy branch tip

  template <class V>
  void visit(V& v) {
    v(levels, "levels", {.min = 0, .max = kMaxLevels, .help = "Leaves on the last N branch levels", .rebuild = Rebuild::kOffline});
    v(per_metre, "per_metre", {.min = 0.0, .max = 1000.0, .unit = "1/m", .help = "Leaves per metre of branch", .rebuild = Rebuild::kOffline});
    v(max_per_branch, "max_per_branch", {.min = 0, .max = 4096, .help = "Cap of leaves on one branch", .rebuild = Rebuild::kOffline});
    v(start, "start", {.min = 0.0, .max = 1.0, .help = "Position of the first leaf along the branch", .rebuild = Rebuild::kOffline});
    v(width, "width", {.min = 1e-4, .max = 10.0, .unit = "m", .help = "Leaf width", .rebuild = Rebuild::kOffline});
    v(length, "length", {.min = 1e-4, .max = 10.0, .unit = "m", .help = "Leaf length", .rebuild = Rebuild::kOffline});
    v(size_variation, "size_variation", {.min = 0.0, .max = 0.9, .help = "Relative random spread of the size", .rebuild = Rebuild::kOffline});
    v(arrangement, "arrangement", {.help = "Phyllotaxis of the leaves along a branch", .rebuild = Rebuild::kOffline});
    v(petiole_angle_deg, "petiole_angle_deg", {.min = 0.0, .max = 180.0, .unit = "deg", .help = "Angle between leaf and branch", .rebuild = Rebuild::kOffline});
    v(droop, "droop", {.min = -2.0, .max = 2.0, .help = "Tilt of the leaf axis towards -y", .rebuild = Rebuild::kOffline});
    v(phototropism, "phototropism", {.min = 0.0, .max = 1.0, .help = "How much leaf normals turn to the sky", .rebuild = Rebuild::kOffline});
    v(orientation_jitter, "orientation_jitter", {.min = 0.0, .max = 3.14159, .unit = "rad", .help = "Random turn of each leaf", .rebuild = Rebuild::kOffline});
    v(terminal_leaf, "terminal_leaf", {.help = "One leaf at every leafy branch tip", .rebuild = Rebuild::kOffline});
  }
};

struct TreeSpecies {
  std::string name = "broadleaf";
  std::uint32_t seed = 1;
  int levels = 4;                       // branch levels including the trunk, [1, kMaxLevels]
  int trunk_count = 1;                  // stems from the ground
  float trunk_length = 9.0f;            // [m]
  float trunk_length_variation = 0.1f;  // relative
  float trunk_lean_deg = 4.0f;          // random lean of each stem
  float trunk_spread_deg = 25.0f;       // angle of the stems from vertical when trunk_count > 1
  float twig_radius = 0.004f;           // radius at every branch tip [m]
  float da_vinci_exponent = 2.3f;       // D in r_base^D = r_tip^D + sum r_child^D
  CrownShape crown_shape = CrownShape::kSpherical;
  LevelSettings level1;
  LevelSettings level2;
  LevelSettings level3;
  LeafSettings leaves;
  LeafShape leaf_shape = LeafShape::kOvate;
  float max_length_error = 0.009f;      // bending length bound per branch (bending.hpp)

  template <class V>
  void visit(V& v) {
    v(name, "name", {.max = 64, .help = "Species name (written into OBJT files)", .rebuild = Rebuild::kOffline});
    v(seed, "seed", {.min = 0.0, .max = 4294967295.0, .help = "Random seed of the tree", .rebuild = Rebuild::kOffline});
    v(levels, "levels", {.min = 1, .max = kMaxLevels, .help = "Branch levels including the trunk", .rebuild = Rebuild::kOffline});
    v(trunk_count, "trunk_count", {.min = 1, .max = 32, .help = "Stems from the ground", .rebuild = Rebuild::kOffline});
    v(trunk_length, "trunk_length", {.min = 0.0, .max = 200.0, .unit = "m", .help = "Trunk length", .rebuild = Rebuild::kOffline});
    v(trunk_length_variation, "trunk_length_variation", {.min = 0.0, .max = 1.0, .help = "Relative random spread of the trunk length", .rebuild = Rebuild::kOffline});
    v(trunk_lean_deg, "trunk_lean_deg", {.min = 0.0, .max = 90.0, .unit = "deg", .help = "Random lean of each stem", .rebuild = Rebuild::kOffline});
    v(trunk_spread_deg, "trunk_spread_deg", {.min = 0.0, .max = 90.0, .unit = "deg", .help = "Stem angle from vertical (several stems)", .rebuild = Rebuild::kOffline});
    v(twig_radius, "twig_radius", {.min = 1e-5, .max = 1.0, .unit = "m", .help = "Radius at branch tips", .rebuild = Rebuild::kOffline});
    v(da_vinci_exponent, "da_vinci_exponent", {.min = 1.5, .max = 4.0, .help = "Exponent of the da Vinci rule (2 = area preserving)", .rebuild = Rebuild::kOffline});
    v(crown_shape, "crown_shape", {.help = "Length profile of the level-1 branches", .rebuild = Rebuild::kOffline});
    v(level1, "level1");
    v(level2, "level2");
    v(level3, "level3");
    v(leaves, "leaves");
    v(leaf_shape, "leaf_shape", {.help = "Outline of the procedural leaf texture", .rebuild = Rebuild::kOffline});
    v(max_length_error, "max_length_error", {.min = 1e-4, .max = 0.5, .help = "Largest relative branch length change under any wind", .rebuild = Rebuild::kOffline});
  }
};

enum class SpeciesPreset { kBroadleaf, kConifer, kBirch, kShrub };
constexpr std::array<EnumName<SpeciesPreset>, 4> enum_names(SpeciesPreset) {
  return {{{SpeciesPreset::kBroadleaf, "broadleaf"},
           {SpeciesPreset::kConifer, "conifer"},
           {SpeciesPreset::kBirch, "birch"},
           {SpeciesPreset::kShrub, "shrub"}}};
}

TreeSpecies species_preset(SpeciesPreset preset, std::uint32_t seed = 1);

struct GeneratorLimits {
  std::size_t max_branches = 50000;
  std::size_t max_leaves = 500000;
};

Result<TreeModel> generate_tree(const TreeSpecies& species, const GeneratorLimits& limits = {});

}  // namespace sylva::vegetation
