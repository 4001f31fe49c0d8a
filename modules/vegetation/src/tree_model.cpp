#include <sylva/vegetation/tree_model.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/core/rng.hpp>
#include <sylva/vegetation/bending.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace sylva::vegetation {
namespace {

bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool unit(const glm::vec3& v, float tol) { return std::fabs(glm::length(v) - 1.0f) <= tol; }

// Taper used for the bending constants: r_tip / r_base, 1 (uniform) when the base radius is 0.
float taper_of(const Branch& b) {
  if (!(b.radius_base > 0.0f)) return 1.0f;
  return b.radius_tip / b.radius_base;
}

}  // namespace

int TreeModel::depth() const {
  int d = 0;
  for (const Branch& b : branches) d = std::max(d, b.level + 1);
  return d;
}

std::vector<int> TreeModel::chain(int branch) const {
  SYLVA_ASSERT(branch >= 0 && branch < static_cast<int>(branches.size()), "branch={} count={}", branch,
               branches.size());
  std::vector<int> out(static_cast<std::size_t>(branches[static_cast<std::size_t>(branch)].level + 1), -1);
  int b = branch;
  for (std::size_t k = out.size(); k-- > 0;) {
    SYLVA_ASSERT(b >= 0, "broken parent chain at branch index {}", branch);
    out[k] = b;
    b = branches[static_cast<std::size_t>(b)].parent;
  }
  return out;
}

glm::vec3 TreeModel::bounds_min() const {
  glm::vec3 lo(std::numeric_limits<float>::max());
  for (const Branch& b : branches) {
    const float r = std::max(b.radius_base, b.radius_tip);
    lo = glm::min(lo, glm::min(b.start, b.end()) - glm::vec3(r));
  }
  for (const Leaf& l : leaves) {
    const glm::vec3 o = branches[static_cast<std::size_t>(l.parent)].axis_point(l.parent_x);
    const float r = std::max(l.width, l.length);
    lo = glm::min(lo, o - glm::vec3(r));
  }
  return branches.empty() ? glm::vec3(0.0f) : lo;
}

glm::vec3 TreeModel::bounds_max() const {
  glm::vec3 hi(std::numeric_limits<float>::lowest());
  for (const Branch& b : branches) {
    const float r = std::max(b.radius_base, b.radius_tip);
    hi = glm::max(hi, glm::max(b.start, b.end()) + glm::vec3(r));
  }
  for (const Leaf& l : leaves) {
    const glm::vec3 o = branches[static_cast<std::size_t>(l.parent)].axis_point(l.parent_x);
    const float r = std::max(l.width, l.length);
    hi = glm::max(hi, o + glm::vec3(r));
  }
  return branches.empty() ? glm::vec3(0.0f) : hi;
}

bool orthonormalize(BranchFrame& f) {
  const float tl = glm::length(f.t);
  if (!(tl > 1.0e-12f) || !std::isfinite(tl)) return false;
  const glm::vec3 t = f.t / tl;
  glm::vec3 r = f.r - glm::dot(f.r, t) * t;
  const float rl = glm::length(r);
  if (!(rl > 1.0e-6f * std::max(glm::length(f.r), 1.0e-30f)) || !std::isfinite(rl)) return false;
  r /= rl;
  f.t = t;
  f.r = r;
  f.s = glm::cross(t, r);
  return true;
}

void scale_tree_model(TreeModel& model, float factor) {
  SYLVA_ASSERT(factor > 0.0f && std::isfinite(factor), "scale_tree_model: factor {} must be positive and finite", factor);
  for (Branch& b : model.branches) {
    b.start *= factor;
    b.length *= factor;
    b.radius_base *= factor;
    b.radius_tip *= factor;
  }
  for (Leaf& l : model.leaves) {
    l.width *= factor;
    l.length *= factor;
  }
}

Status validate(const TreeModel& model) {
  const auto n = static_cast<int>(model.branches.size());
  for (int i = 0; i < n; ++i) {
    const Branch& b = model.branches[static_cast<std::size_t>(i)];
    const auto fail = [&](const std::string& what) {
      return make_error(ErrorCode::kInvalidArgument, fmt::format("tree '{}': branch {}: {}", model.name, b.id, what));
    };
    if (b.level < 0 || b.level >= kMaxLevels)
      return fail(fmt::format("level {} is outside [0, {}]", b.level, kMaxLevels - 1));
    if (b.parent < 0) {
      if (b.level != 0) return fail(fmt::format("has no parent but level {} (roots have level 0)", b.level));
    } else {
      if (b.parent >= i) return fail(fmt::format("parent index {} does not precede it (index {})", b.parent, i));
      const Branch& p = model.branches[static_cast<std::size_t>(b.parent)];
      if (p.level != b.level - 1)
        return fail(fmt::format("level {} but its parent {} has level {}", b.level, p.id, p.level));
    }
    if (!(b.parent_x >= 0.0f && b.parent_x <= 1.0f)) return fail(fmt::format("x = {} is outside [0, 1]", b.parent_x));
    if (!(b.length >= 0.0f) || !std::isfinite(b.length)) return fail(fmt::format("length d = {} must be >= 0", b.length));
    if (!finite3(b.start)) return fail("start z is not finite");
    if (!(b.radius_base >= 0.0f && b.radius_tip >= 0.0f) || !std::isfinite(b.radius_base) ||
        !std::isfinite(b.radius_tip))
      return fail(fmt::format("radii {} / {} must be finite and >= 0", b.radius_base, b.radius_tip));
    const BranchFrame& f = b.frame;
    if (!finite3(f.r) || !finite3(f.s) || !finite3(f.t)) return fail("frame has a non-finite vector");
    constexpr float kTol = 1.0e-3f;
    if (!unit(f.r, kTol) || !unit(f.s, kTol) || !unit(f.t, kTol)) return fail("frame vectors are not unit length");
    if (std::fabs(glm::dot(f.r, f.s)) > kTol || std::fabs(glm::dot(f.r, f.t)) > kTol ||
        std::fabs(glm::dot(f.s, f.t)) > kTol)
      return fail("frame vectors are not orthogonal");
    if (glm::dot(glm::cross(f.r, f.s), f.t) < 0.0f) return fail("frame is left-handed (r x s = -t)");
    if (!std::isfinite(b.c2) || !std::isfinite(b.c4)) return fail("bending constants are not finite");
    if (!(b.amplitude_limit > 0.0f) || !std::isfinite(b.amplitude_limit))
      return fail(fmt::format("amplitude limit {} must be > 0", b.amplitude_limit));
    if (!std::isfinite(b.noise_phase)) return fail("noise phase is not finite");
  }
  for (const Leaf& l : model.leaves) {
    const auto fail = [&](const std::string& what) {
      return make_error(ErrorCode::kInvalidArgument, fmt::format("tree '{}': leaf {}: {}", model.name, l.id, what));
    };
    if (l.parent < 0 || l.parent >= n) return fail(fmt::format("parent index {} does not exist", l.parent));
    if (!(l.parent_x >= 0.0f && l.parent_x <= 1.0f)) return fail(fmt::format("x = {} is outside [0, 1]", l.parent_x));
    if (!finite3(l.normal) || !finite3(l.bitangent) || !finite3(l.tangent)) return fail("frame has a non-finite vector");
    constexpr float kTol = 1.0e-3f;
    if (!unit(l.normal, kTol) || !unit(l.bitangent, kTol) || !unit(l.tangent, kTol))
      return fail("frame vectors are not unit length");
    if (glm::length(glm::cross(l.tangent, l.normal) - l.bitangent) > 2.0f * kTol)
      return fail("frame is not orthonormal with b = t x n");
    if (!(l.width > 0.0f) || !(l.length > 0.0f) || !std::isfinite(l.width) || !std::isfinite(l.length))
      return fail(fmt::format("size {} x {} must be positive", l.width, l.length));
    if (!(l.number >= 0.0f && l.number < 1.0f)) return fail(fmt::format("number {} is outside [0, 1)", l.number));
  }
  return ok_status();
}

void assign_bending_data(TreeModel& model, float max_length_error, bool keep_constants) {
  // Explicit constants repeat across branches (files written by write_objt carry the fitted
  // values of a few taper buckets), so limits are computed once per distinct pair.
  std::map<std::pair<float, float>, float> limits;
  for (Branch& b : model.branches) {
    const float alpha = taper_of(b);
    if (!keep_constants) {
      const BendConstants c = bend_constants_for_taper(alpha);
      b.c2 = c.c2;
      b.c4 = c.c4;
      b.amplitude_limit = bend_amplitude_limit_for_taper(alpha, max_length_error);
    } else {
      const std::pair<float, float> key{b.c2, b.c4};
      auto it = limits.find(key);
      if (it == limits.end()) it = limits.emplace(key, bend_amplitude_limit(b.c2, b.c4, max_length_error)).first;
      b.amplitude_limit = it->second;
    }
    const auto id = static_cast<std::uint32_t>(b.id);
    b.noise_seed = hash_u32(id, model.seed, 0x6272u);
    b.noise_phase = hash_to_unit_float(hash_u32(id, model.seed, 0x7068u)) * 64.0f;
  }
}

}  // namespace sylva::vegetation
