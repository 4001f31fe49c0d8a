#include "support/models.hpp"

#include <sylva/core/assert.hpp>

#include <map>
#include <memory>
#include <mutex>
#include <utility>

namespace sylva::vegetation::testing {
namespace {

Branch make_branch(int id, int level, int parent, float x, float length, const glm::vec3& dir, const glm::vec3& r_hint,
                   const TreeModel& m) {
  Branch b;
  b.id = id;
  b.level = level;
  b.parent = parent;
  b.parent_x = x;
  b.length = length;
  b.frame.t = glm::normalize(dir);
  b.frame.r = r_hint;
  SYLVA_ASSERT(orthonormalize(b.frame), "bad test frame for branch {}", id);
  b.start = parent < 0 ? glm::vec3(0.0f) : m.branches[static_cast<std::size_t>(parent)].axis_point(x);
  b.radius_base = 0.02f * length + 0.003f;
  b.radius_tip = 0.25f * b.radius_base;
  return b;
}

Leaf make_leaf(int id, int parent, float x, const TreeModel& m) {
  Leaf l;
  l.id = id;
  l.parent = parent;
  l.parent_x = x;
  const BranchFrame& f = m.branches[static_cast<std::size_t>(parent)].frame;
  l.tangent = glm::normalize(f.t + f.r);
  l.normal = glm::normalize(glm::cross(f.s, l.tangent));
  l.bitangent = glm::cross(l.tangent, l.normal);
  l.width = 0.06f;
  l.length = 0.1f;
  l.number = 0.125f * static_cast<float>(id % 8);
  return l;
}

}  // namespace

TreeModel small_tree(std::uint32_t seed) {
  TreeModel m;
  m.name = "small";
  m.seed = seed;
  m.branches.push_back(make_branch(10, 0, -1, 0.0f, 4.0f, {0.05f, 1.0f, 0.0f}, {1, 0, 0}, m));
  m.branches.push_back(make_branch(11, 1, 0, 0.5f, 2.0f, {1.0f, 0.8f, 0.0f}, {0, 1, 0}, m));
  m.branches.push_back(make_branch(12, 1, 0, 0.8f, 1.5f, {-0.7f, 0.6f, 0.5f}, {0, 1, 0}, m));
  m.branches.push_back(make_branch(13, 2, 1, 0.6f, 1.0f, {0.3f, 0.9f, 0.8f}, {1, 0, 0}, m));
  m.branches.push_back(make_branch(14, 2, 2, 0.3f, 0.0f, {0.0f, 1.0f, -1.0f}, {1, 0, 0}, m));  // zero length
  m.branches.push_back(make_branch(15, 3, 3, 0.9f, 0.5f, {0.2f, -0.3f, 1.0f}, {0, 1, 0}, m));
  // A child off the parent's axis (OBJT gives start points explicitly).
  Branch off = make_branch(16, 2, 1, 0.3f, 0.7f, {0.0f, 0.2f, -1.0f}, {1, 0, 0}, m);
  off.start += 0.01f * m.branches[1].frame.r;
  m.branches.push_back(off);
  m.leaves.push_back(make_leaf(0, 1, 0.7f, m));
  m.leaves.push_back(make_leaf(1, 3, 1.0f, m));
  m.leaves.push_back(make_leaf(2, 5, 0.0f, m));
  m.leaves.push_back(make_leaf(3, 5, 0.5f, m));
  m.leaves.push_back(make_leaf(4, 4, 0.5f, m));
  assign_bending_data(m, 0.009f);
  const Status s = validate(m);
  SYLVA_ASSERT(s.ok(), "small_tree invalid: {}", s.error().message);
  return m;
}

const TreeModel& preset_tree(SpeciesPreset preset, std::uint32_t seed) {
  static std::mutex mutex;
  static std::map<std::pair<int, std::uint32_t>, std::unique_ptr<TreeModel>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[{static_cast<int>(preset), seed}];
  if (!slot) {
    Result<TreeModel> m = generate_tree(species_preset(preset, seed));
    SYLVA_ASSERT(m.ok(), "preset failed: {}", m.error().message);
    slot = std::make_unique<TreeModel>(std::move(m).value());
  }
  return *slot;
}

const TreeMesh& preset_mesh(SpeciesPreset preset, std::uint32_t seed) {
  static std::mutex mutex;
  static std::map<std::pair<int, std::uint32_t>, std::unique_ptr<TreeMesh>> cache;
  const TreeModel& model = preset_tree(preset, seed);
  std::lock_guard lock(mutex);
  auto& slot = cache[{static_cast<int>(preset), seed}];
  if (!slot) slot = std::make_unique<TreeMesh>(build_tree_mesh(model));
  return *slot;
}

TreeModel single_leaf() {
  TreeModel m;
  m.name = "leaf";
  Branch b;
  b.id = 0;
  b.length = 0.5f;
  b.frame = {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}};
  b.radius_base = 0.01f;
  b.radius_tip = 0.005f;
  m.branches.push_back(b);
  Leaf l;
  l.parent = 0;
  l.parent_x = 1.0f;
  l.tangent = {0, 1, 0};
  l.normal = {0, 0, 1};
  l.bitangent = glm::cross(l.tangent, l.normal);
  l.width = 1.0f;
  l.length = 1.4f;
  l.number = 0.5f;
  m.leaves.push_back(l);
  assign_bending_data(m, 0.009f);
  return m;
}

std::string seed_example_objt() {
  return R"(name = "example"
// a trunk and one branch, in the layout of the seed's format description
B 0 {
    l    0
    d    5
    z    0 0 0
    k    0 5 0
    r    1 0 0
    s    0 0 -1
    t    0 1 0
    p    -1
    x    0
}
B 1 {                                // branch identifier
    l    1                           // level in the hierarchy
    d    2
    z    0 3 0
    k    2 3 0
    r    0 1 0
    s    0 0 1
    t    1 0 0
    p    0
    x    0.6
}
L 5
{
    r    0 1 0
    s    0 0 1
    t    1 0 0
    p    1
    x    0.9
}
)";
}

}  // namespace sylva::vegetation::testing
