#pragma once
// TreeModel: the branch hierarchy the wind animation needs, exactly the per-branch data of seed 000
// table 3.1 ("coefficients c2, c4, length L; definition of the branch coordinate system; bending
// control signals; reference to the parent branch"). The per-vertex half of table 3.1 lives in
// tree_mesh.hpp. The model is GL-free; it is what the OBJT loader (objt.hpp) and the procedural
// generator (generator.hpp) produce, and what the image-based levels of the next issue bake from.
//
// Conventions. Object space, metres, y up. A branch is a straight truncated cone (seed §3.1.1: the
// bending model assumes straight rest branches) from `start` along its frame's t axis for `length`
// metres. Its frame (r, s, t) is orthonormal and right-handed: r x s = t (the LOD0 convention of the
// seed, §4.4 `t = cross(r, s)`). A point on the branch axis is start + x * length * t with the
// normalised coordinate x in [0, 1] (x = 0 at the fixed end).
//
// Hierarchy. Level 0 branches are roots (trunks; a shrub may have several). A branch of level l > 0
// has a parent of level l - 1 and starts at parent_x along it; `start` may lie off the parent's
// axis (OBJT gives the start point explicitly), the offset is carried through the animation.
// At most kMaxLevels levels (trunk + 3): the seed's data texture holds levels 0..3 (table 4.1), and
// each vertex carries one x value per level in a vec4. Branches are stored parents-first, so a
// parent's index is always smaller than its children's.
//
// Leaves hang on a branch at parent_x. Leaf frame (seed eq. 3.16: n, b, t): `normal` n (the
// upper/front side faces +n), `tangent` t along the blade from the attachment point, and
// `bitangent` b = t x n across the blade. A leaf is a width x length quad in the (b, t) plane with
// its base centre at the attachment point.

#include <sylva/core/result.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sylva::vegetation {

inline constexpr int kMaxLevels = 4;

struct BranchFrame {
  glm::vec3 r{1.0f, 0.0f, 0.0f};  // first bending axis ("normal")
  glm::vec3 s{0.0f, 0.0f, -1.0f}; // second bending axis ("binormal")
  glm::vec3 t{0.0f, 1.0f, 0.0f};  // longitudinal axis, r x s = t
};

struct Branch {
  int id = 0;                 // identifier in the OBJT file (unique among branches)
  int level = 0;              // 0 = root (trunk)
  int parent = -1;            // index into TreeModel::branches, -1 for a root
  float parent_x = 0.0f;      // where on the parent the branch starts, [0, 1]
  float length = 1.0f;        // L [m], >= 0 (0 is allowed: a degenerate branch never produces NaN)
  glm::vec3 start{0.0f};      // rest position of the fixed end, object space [m]
  BranchFrame frame;          // rest frame, object space
  float radius_base = 0.05f;  // cone radius at x = 0 [m], >= 0
  float radius_tip = 0.01f;   // cone radius at x = 1 [m], >= 0
  // Bending constants of u(x) = c2 x^2 + c4 x^4 (seed eq. 3.8), fitted to the Euler-Bernoulli
  // shape of a cone with this branch's taper (bending.hpp); the seed uses 0.374570 / 0.129428
  // (taper 0.2) for every branch.
  float c2 = 0.374570f;
  float c4 = 0.129428f;
  // Control signals (seed §3.1.4): their static description. The signals themselves are
  // evaluated per frame (animation.hpp) from the wind and 1D noise; each branch reads its own
  // noise (seed: "unique per branch") through these.
  float amplitude_limit = 0.3f;  // A_max: the control amplitude saturates towards it so the
                                 // length correction keeps the branch length within the bound
                                 // (bending.hpp, bend_amplitude_limit)
  float noise_phase = 0.0f;      // offset of this branch's noise signal [noise cells], [0, 64)
  std::uint32_t noise_seed = 0;  // seed of its two noise signals (r and s components)

  glm::vec3 axis_point(float x) const { return start + (x * length) * frame.t; }
  glm::vec3 end() const { return axis_point(1.0f); }
  float radius_at(float x) const { return radius_base + (radius_tip - radius_base) * x; }
};

struct Leaf {
  int id = 0;              // identifier in the OBJT file (unique among leaves)
  int parent = 0;          // index into TreeModel::branches
  float parent_x = 1.0f;   // attachment point on the parent, [0, 1]
  glm::vec3 normal{0.0f, 0.0f, 1.0f};     // n (OBJT "r")
  glm::vec3 bitangent{1.0f, 0.0f, 0.0f};  // b = t x n (OBJT "s")
  glm::vec3 tangent{0.0f, 1.0f, 0.0f};    // t along the blade (OBJT "t")
  float width = 0.05f;     // [m] > 0
  float length = 0.08f;    // [m] > 0
  float number = 0.0f;     // leafSpecificNumber in [0, 1): season offset and colour variation (§4.6)
};

struct TreeModel {
  std::string name;
  std::uint32_t seed = 0;        // seeds per-branch noise; generated models record their seed
  std::vector<Branch> branches;  // parents before children
  std::vector<Leaf> leaves;

  int depth() const;  // number of levels present (0 for an empty model)
  // Indices of the ancestors of branch b from its root down to b itself (size = level + 1).
  std::vector<int> chain(int branch) const;
  // Object-space bounds of the rest pose (branch cones with radii and leaf quads).
  glm::vec3 bounds_min() const;
  glm::vec3 bounds_max() const;
};

// Checks every invariant stated above (indices, levels, parents-first order, depth, finite
// values, unit orthonormal right-handed frames within 1e-3, x in [0, 1], non-negative lengths and
// radii, positive leaf sizes). kInvalidArgument naming the branch or leaf (its OBJT id) and field.
Status validate(const TreeModel& model);

// Scales the rest geometry uniformly by `factor` (> 0, finite): branch starts, lengths and radii,
// leaf sizes. Frames, x values, bending constants and amplitude limits are relative and stay (a
// species file's `units`, metres per file unit).
void scale_tree_model(TreeModel& model, float factor);

// Orthonormalises a frame keeping t's direction: t normalised, r made orthogonal to t, s = t x r.
// Returns false (frame untouched) when t is zero or r is (nearly) parallel to t.
bool orthonormalize(BranchFrame& frame);

// Fills c2, c4 from each branch's taper (radius_tip / radius_base), amplitude_limit for
// max_length_error (bending.hpp), and noise_phase / noise_seed from model.seed and the branch id.
// The generator and the OBJT loader call it; explicit OBJT "c" constants are kept when
// keep_constants is true.
void assign_bending_data(TreeModel& model, float max_length_error, bool keep_constants = false);

}  // namespace sylva::vegetation
