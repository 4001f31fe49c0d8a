#include <sylva/vegetation/tree_mesh.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/core/rng.hpp>
#include <sylva/vegetation/animation.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>

namespace sylva::vegetation {
namespace {

glm::vec3 coords_in(const BranchFrame& f, const glm::vec3& v) {
  return glm::vec3(glm::dot(v, f.r), glm::dot(v, f.s), glm::dot(v, f.t));
}

// A seed stored in a float slot: 24 random bits in the sign and mantissa of a number in
// +-[1, 2), so the slot never holds a NaN, infinity or denormal pattern a driver might touch.
float seed_as_float(std::uint32_t h) { return std::bit_cast<float>((h & 0x807fffffu) | 0x3f800000u); }

int segments_for(const MeshSettings& s, int level) {
  switch (level) {
    case 0: return s.trunk_segments;
    case 1: return s.level1_segments;
    case 2: return s.level2_segments;
    default: return s.level3_segments;
  }
}

constexpr int kMinRings[kMaxLevels] = {4, 2, 1, 1};

}  // namespace

TreeGpuData pack_tree(const TreeModel& model) {
  SYLVA_ASSERT(validate(model).ok(), "pack_tree needs a valid model: {}", validate(model).error().message);
  TreeGpuData d;
  d.branches.reserve(model.branches.size());
  for (std::size_t i = 0; i < model.branches.size(); ++i) {
    const Branch& b = model.branches[i];
    BranchGpu g{};
    const bool root = b.parent < 0;
    const BranchFrame pf = root ? BranchFrame{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}
                                : model.branches[static_cast<std::size_t>(b.parent)].frame;
    const glm::vec3 offset =
        root ? b.start : b.start - model.branches[static_cast<std::size_t>(b.parent)].axis_point(b.parent_x);
    g.r_parent = glm::vec4(root ? b.frame.r : coords_in(pf, b.frame.r), b.length);
    g.s_parent = glm::vec4(root ? b.frame.s : coords_in(pf, b.frame.s), b.c2);
    g.t_parent = glm::vec4(root ? b.frame.t : coords_in(pf, b.frame.t), b.c4);
    g.attach_parent = glm::vec4(root ? offset : coords_in(pf, offset), b.parent_x);
    g.attach_object = glm::vec4(offset, b.amplitude_limit);
    g.r_object = glm::vec4(b.frame.r, b.noise_phase);
    g.s_object = glm::vec4(b.frame.s, static_cast<float>(b.level));
    g.t_object = glm::vec4(b.frame.t, b.radius_base);
    g.seeds = glm::uvec4(b.noise_seed, hash_u32(b.noise_seed, 0x73u), static_cast<std::uint32_t>(b.id), 0u);
    const std::vector<int> chain = model.chain(static_cast<int>(i));
    g.chain = glm::ivec4(-1);
    for (std::size_t k = 0; k < chain.size(); ++k) g.chain[static_cast<int>(k)] = chain[k];
    d.branches.push_back(g);
  }
  d.leaves.reserve(model.leaves.size());
  for (const Leaf& l : model.leaves) {
    const Branch& p = model.branches[static_cast<std::size_t>(l.parent)];
    LeafGpu g{};
    const auto id = static_cast<std::uint32_t>(l.id);
    g.t_parent = glm::vec4(coords_in(p.frame, l.tangent), l.number);
    g.n_parent = glm::vec4(coords_in(p.frame, l.normal), hash_to_unit_float(hash_u32(id, model.seed, 0x6670u)) * 64.0f);
    g.t_object = glm::vec4(l.tangent, l.width);
    g.n_object = glm::vec4(l.normal, l.length);
    g.origin = glm::vec4(p.axis_point(l.parent_x), seed_as_float(hash_u32(id, model.seed, 0x6c66u)));
    d.leaves.push_back(g);
  }
  return d;
}

TreeMesh build_tree_mesh(const TreeModel& model, const MeshSettings& settings) {
  TreeMesh m;
  m.data = pack_tree(model);
  const AnimationGpu rest = rest_animation();
  const InstanceGpu origin = make_instance_gpu(TreeInstance{}, glm::dvec3(0.0), glm::vec3(0.0f));
  const WindGpuParams no_wind{};

  for (std::size_t i = 0; i < model.branches.size(); ++i) {
    const Branch& b = model.branches[i];
    const auto bi = static_cast<std::uint32_t>(i);
    const int segments = std::max(3, segments_for(settings, b.level));
    const int wanted = static_cast<int>(std::ceil(b.length / std::max(settings.ring_spacing, 1.0e-3f)));
    const int rings = std::clamp(wanted, std::min(kMinRings[b.level], settings.max_rings), std::max(1, settings.max_rings));
    m.rings.push_back(rings);
    const float slope = b.length > 0.0f ? (b.radius_base - b.radius_tip) / b.length : 0.0f;
    const auto base = static_cast<std::uint32_t>(m.branch_vertices.size());
    for (int j = 0; j <= rings; ++j) {
      const float x = static_cast<float>(j) / static_cast<float>(rings);
      const float radius = b.radius_at(x);
      const glm::vec4 xv = hierarchy_vector(m.data, bi, x);
      for (int k = 0; k <= segments; ++k) {
        const float phi = 2.0f * std::numbers::pi_v<float> * static_cast<float>(k % segments) / static_cast<float>(segments);
        BranchVertex v{};
        v.local = glm::vec3(radius * std::cos(phi), radius * std::sin(phi), 0.0f);
        v.normal = glm::normalize(glm::vec3(std::cos(phi), std::sin(phi), slope));
        v.uv = glm::vec2(static_cast<float>(k) / static_cast<float>(segments), x * b.length / settings.bark_scale);
        v.xvec = xv;
        v.branch = bi;
        v.position = deform_branch_vertex(m.data, rest, origin, v).position;
        m.branch_vertices.push_back(v);
      }
    }
    const auto row = static_cast<std::uint32_t>(segments + 1);
    for (int j = 0; j < rings; ++j) {
      for (int k = 0; k < segments; ++k) {
        const std::uint32_t a = base + static_cast<std::uint32_t>(j) * row + static_cast<std::uint32_t>(k);
        const std::uint32_t c = a + row;
        m.branch_indices.insert(m.branch_indices.end(), {a, a + 1, c + 1, a, c + 1, c});
      }
    }
    if (settings.tip_caps && b.radius_tip > 0.0f) {
      BranchVertex v{};
      v.local = glm::vec3(0.0f, 0.0f, b.radius_tip);
      v.normal = glm::vec3(0.0f, 0.0f, 1.0f);
      v.uv = glm::vec2(0.5f, (b.length + b.radius_tip) / settings.bark_scale);
      v.xvec = hierarchy_vector(m.data, bi, 1.0f);
      v.branch = bi;
      v.position = deform_branch_vertex(m.data, rest, origin, v).position;
      const auto tip = static_cast<std::uint32_t>(m.branch_vertices.size());
      m.branch_vertices.push_back(v);
      const std::uint32_t last = base + static_cast<std::uint32_t>(rings) * row;
      for (int k = 0; k < segments; ++k) {
        const std::uint32_t a = last + static_cast<std::uint32_t>(k);
        m.branch_indices.insert(m.branch_indices.end(), {a, a + 1, tip});
      }
    }
  }

  for (std::size_t j = 0; j < model.leaves.size(); ++j) {
    const Leaf& l = model.leaves[j];
    const glm::vec4 xv = hierarchy_vector(m.data, static_cast<std::uint32_t>(l.parent), l.parent_x);
    const auto base = static_cast<std::uint32_t>(m.leaf_vertices.size());
    const glm::vec2 corners[4] = {{-0.5f * l.width, 0.0f}, {0.5f * l.width, 0.0f}, {0.5f * l.width, l.length},
                                  {-0.5f * l.width, l.length}};
    const glm::vec2 uvs[4] = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
    for (int c = 0; c < 4; ++c) {
      LeafVertex v{};
      v.corner = corners[c];
      v.uv = uvs[c];
      v.xvec = xv;
      v.branch = static_cast<std::uint32_t>(l.parent);
      v.leaf = static_cast<std::uint32_t>(j);
      const DeformedVertex d = deform_leaf_vertex(m.data, rest, origin, no_wind, v);
      v.position = d.position;
      v.normal = d.normal;
      m.leaf_vertices.push_back(v);
    }
    m.leaf_indices.insert(m.leaf_indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }

  glm::vec3 lo(std::numeric_limits<float>::max());
  glm::vec3 hi(std::numeric_limits<float>::lowest());
  for (const BranchVertex& v : m.branch_vertices) {
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
  }
  for (const LeafVertex& v : m.leaf_vertices) {
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
  }
  if (m.branch_vertices.empty() && m.leaf_vertices.empty()) lo = hi = glm::vec3(0.0f);
  m.bounds_min = lo;
  m.bounds_max = hi;
  return m;
}

}  // namespace sylva::vegetation
