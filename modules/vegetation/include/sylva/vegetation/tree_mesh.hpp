#pragma once
// GPU-ready tree data: the packed per-branch and per-leaf records the animation reads (a storage
// buffer instead of the seed's RGBA32F data texture, table 4.1) and the LOD0 mesh whose vertices
// carry the per-vertex half of seed 000 table 3.1: the actual (rest) position, the position
// relative to the branch, the hierarchy vector of x values and the reference to the branch.
//
// Branches are tapered tubes (one straight cone per branch, rings along it, an optional tip cap),
// leaves are quads in the leaf's (b, t) plane drawn two-sided. Rest positions are computed by the
// animation's own hierarchy evaluation with no wind (animation.hpp, rest_animation()), so the
// deformed mesh at zero wind reproduces them bit for bit on the CPU; tree_mesh_test checks them
// against the model's geometry built independently.
//
// The records are std430-compatible (vec4 / ivec4 / uvec4 members only); the GLSL declarations
// are in shaders/lib/tree_data.glsl. Everything here is GL-free; issue 6 (image-based levels)
// bakes its slices from this mesh and reads the branch records for its backward transform.

#include <sylva/core/params.hpp>
#include <sylva/vegetation/tree_model.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sylva::vegetation {

// One branch for the vertex shader (160 bytes). "parent frame" = the parent's rest frame (r, s, t);
// for a root the object axes.
struct BranchGpu {
  glm::vec4 r_parent;       // xyz rest r in parent frame coordinates, w length L [m]
  glm::vec4 s_parent;       // xyz rest s in parent frame coordinates, w c2
  glm::vec4 t_parent;       // xyz rest t in parent frame coordinates, w c4
  glm::vec4 attach_parent;  // xyz start minus the parent's axis point at parent_x, parent frame; w parent_x
  glm::vec4 attach_object;  // xyz the same offset in object space (a root: its start); w amplitude limit
  glm::vec4 r_object;       // xyz rest r (object), w noise phase [cells]
  glm::vec4 s_object;       // xyz rest s (object), w level
  glm::vec4 t_object;       // xyz rest t (object), w radius_base [m]
  glm::uvec4 seeds;         // x noise seed of the r signal, y of the s signal, z branch id, w 0
  glm::ivec4 chain;         // branch indices of the ancestors by level (chain[level] = this), -1 beyond
};
static_assert(sizeof(BranchGpu) == 160, "BranchGpu must match the std430 layout of SylvaTreeBranch");

// One leaf (80 bytes).
struct LeafGpu {
  glm::vec4 t_parent;  // xyz rest blade axis in the parent branch's frame, w leafSpecificNumber
  glm::vec4 n_parent;  // xyz rest normal in the parent branch's frame, w flutter phase [cells]
  glm::vec4 t_object;  // xyz rest blade axis (object), w width [m]
  glm::vec4 n_object;  // xyz rest normal (object), w length [m]
  glm::vec4 origin;    // xyz rest attachment point (object), w flutter seed (uint bits)
};
static_assert(sizeof(LeafGpu) == 80, "LeafGpu must match the std430 layout of SylvaTreeLeaf");

struct TreeGpuData {
  std::vector<BranchGpu> branches;  // same order as TreeModel::branches
  std::vector<LeafGpu> leaves;      // same order as TreeModel::leaves
};

// Packs a validated model (asserts on an invalid one).
TreeGpuData pack_tree(const TreeModel& model);

// Bark vertex (64 bytes): table 3.1 per vertex.
struct BranchVertex {
  glm::vec3 position;  // rest position, object space [m] ("actual position")
  glm::vec3 local;     // offset from the axis point in the branch frame (r, s, t) [m]
  glm::vec3 normal;    // normal in the branch frame (r, s, t)
  glm::vec2 uv;        // bark texture coordinates (u around, v along, metres / bark scale)
  glm::vec4 xvec;      // hierarchy vector: x on the level-k ancestor where the next one starts,
                       // x of this vertex on its own branch at [level], 0 beyond
  std::uint32_t branch;  // index into TreeGpuData::branches
};
static_assert(sizeof(BranchVertex) == 64);

// Leaf vertex (64 bytes).
struct LeafVertex {
  glm::vec3 position;   // rest position, object space [m]
  glm::vec3 normal;     // rest normal, object space (the front side)
  glm::vec2 corner;     // (P_x, P_y) in the leaf frame (b, t) [m] (seed eq. 3.16)
  glm::vec2 uv;         // leaf texture coordinates, v from base (0) to tip (1)
  glm::vec4 xvec;       // hierarchy vector of the parent branch, [level] = the leaf's parent_x
  std::uint32_t branch; // parent branch index
  std::uint32_t leaf;   // index into TreeGpuData::leaves
};
static_assert(sizeof(LeafVertex) == 64);

struct MeshSettings {
  int trunk_segments = 12;   // vertices around a level-0 tube
  int level1_segments = 8;
  int level2_segments = 6;
  int level3_segments = 4;
  float ring_spacing = 0.5f; // metres between rings along a branch (at least min rings per level)
  int max_rings = 24;
  float bark_scale = 0.6f;   // metres of branch per bark texture repeat (v) per metre circumference
  bool tip_caps = true;      // close branch tips with a cone point

  template <class V>
  void visit(V& v) {
    v(trunk_segments, "trunk_segments", {.min = 3, .max = 64, .help = "Vertices around the trunk", .rebuild = Rebuild::kGpu});
    v(level1_segments, "level1_segments", {.min = 3, .max = 64, .help = "Vertices around level-1 branches", .rebuild = Rebuild::kGpu});
    v(level2_segments, "level2_segments", {.min = 3, .max = 64, .help = "Vertices around level-2 branches", .rebuild = Rebuild::kGpu});
    v(level3_segments, "level3_segments", {.min = 3, .max = 64, .help = "Vertices around level-3 branches", .rebuild = Rebuild::kGpu});
    v(ring_spacing, "ring_spacing", {.min = 0.01, .max = 100.0, .unit = "m", .help = "Distance between rings along a branch", .rebuild = Rebuild::kGpu});
    v(max_rings, "max_rings", {.min = 1, .max = 256, .help = "Most rings on one branch", .rebuild = Rebuild::kGpu});
    v(bark_scale, "bark_scale", {.min = 0.01, .max = 100.0, .unit = "m", .help = "Branch length per bark texture repeat", .rebuild = Rebuild::kGpu});
    v(tip_caps, "tip_caps", {.help = "Close branch tips with a cone point", .rebuild = Rebuild::kGpu});
  }
};

struct TreeMesh {
  TreeGpuData data;
  std::vector<BranchVertex> branch_vertices;
  std::vector<std::uint32_t> branch_indices;  // triangles
  std::vector<LeafVertex> leaf_vertices;
  std::vector<std::uint32_t> leaf_indices;    // triangles (two per leaf)
  glm::vec3 bounds_min{0.0f};                 // rest pose, object space
  glm::vec3 bounds_max{0.0f};
  // Number of rings on each branch (same order as the model), for tests and LOD baking.
  std::vector<int> rings;
};

TreeMesh build_tree_mesh(const TreeModel& model, const MeshSettings& settings = {});

}  // namespace sylva::vegetation
