// Vegetation stability cases for --stability from the public tree API (modules/vegetation):
// the CPU reference of the hierarchical bending, which the vertex shader mirrors, under wind
// x10 and x100, 1e5 s, zero wind and zero-length branches. GL-free.
#include "stability.hpp"

#include <sylva/vegetation/animation.hpp>
#include <sylva/vegetation/generator.hpp>
#include <sylva/vegetation/tree_mesh.hpp>
#include <sylva/vegetation/tree_model.hpp>

#include <fmt/format.h>

#include <cmath>

namespace sylva::bench {
namespace {

struct TreeProbe {
  std::uint64_t non_finite = 0;
  float max_length_change = 0.0f;  // relative, over all branches
  float max_rest_offset = 0.0f;    // largest |deformed - rest| of a bark vertex [m]
  std::size_t branches = 0;
  std::string error;
};

std::uint64_t bad(const glm::vec3& v) {
  return static_cast<std::uint64_t>(!std::isfinite(v.x)) + !std::isfinite(v.y) + !std::isfinite(v.z);
}

// Generates a broadleaf tree, bends it with the wind (world vector) at `time`, and measures the
// arc length of every branch axis (64-segment polyline) against its rest length.
TreeProbe probe(const glm::vec3& wind, double time, float wind_scale, bool zero_length_branches) {
  TreeProbe p;
  auto model = vegetation::generate_tree(vegetation::species_preset(vegetation::SpeciesPreset::kBroadleaf, 3));
  if (!model.ok()) {
    p.error = model.error().message;
    return p;
  }
  if (zero_length_branches) {
    for (std::size_t b = 1; b < model->branches.size(); b += 5) model->branches[b].length = 0.0f;
  }
  const vegetation::TreeMesh mesh = vegetation::build_tree_mesh(*model);
  vegetation::AnimationSettings settings;
  settings.wind_scale = wind_scale;
  const vegetation::AnimationGpu anim = vegetation::make_animation_gpu(settings, time);
  vegetation::TreeInstance instance;
  const vegetation::InstanceGpu inst = vegetation::make_instance_gpu(instance, glm::dvec3(0.0), wind * wind_scale);
  p.branches = model->branches.size();
  for (std::uint32_t b = 0; b < model->branches.size(); ++b) {
    const float rest = model->branches[b].length;
    float arc = 0.0f;
    glm::vec3 prev = vegetation::branch_axis_point(mesh.data, anim, inst, b, 0.0f);
    p.non_finite += bad(prev);
    for (int k = 1; k <= 64; ++k) {
      const glm::vec3 q = vegetation::branch_axis_point(mesh.data, anim, inst, b, static_cast<float>(k) / 64.0f);
      p.non_finite += bad(q);
      arc += glm::length(q - prev);
      prev = q;
    }
    if (rest > 1e-3f && std::isfinite(arc)) p.max_length_change = std::max(p.max_length_change, std::abs(arc - rest) / rest);
  }
  for (const vegetation::BranchVertex& v : mesh.branch_vertices) {
    const vegetation::DeformedVertex d = vegetation::deform_branch_vertex(mesh.data, anim, inst, v);
    p.non_finite += bad(d.position) + bad(d.normal);
    if (std::isfinite(glm::length(d.position - v.position))) {
      p.max_rest_offset = std::max(p.max_rest_offset, glm::length(d.position - v.position));
    }
  }
  return p;
}

StabilityOutcome length_case(float wind_scale, double time, float bound) {
  const TreeProbe p = probe({6.0f, 0.0f, 2.0f}, time, wind_scale, false);
  StabilityOutcome o;
  if (!p.error.empty()) {
    o.detail = p.error;
    return o;
  }
  o.nan_count = p.non_finite;
  o.passed = p.max_length_change <= bound;
  o.detail = fmt::format("{} branches, 6.3 m/s wind x{} at t = {} s: largest branch length change {:.3f} % "
                         "(allowed {:.1f} %)",
                         p.branches, wind_scale, time, 100.0 * p.max_length_change, 100.0 * bound);
  return o;
}

}  // namespace

void add_vegetation_stability_cases(std::vector<StabilityCase>& cases) {
  cases.push_back({"vegetation", "wind_x10_length", "wind x10: every branch keeps its length within 1 %, no NaN", false,
                   [] { return length_case(10.0f, 3.0, 0.01f); }});
  cases.push_back({"vegetation", "wind_x100_length", "wind x100 (630 m/s): branch lengths within 1 %, no NaN", false,
                   [] { return length_case(100.0f, 3.0, 0.01f); }});
  cases.push_back({"vegetation", "late_time_1e5s", "t = 1e5 s with wind x10: branch lengths within 1 %, no NaN", false,
                   [] { return length_case(10.0f, 1.0e5, 0.01f); }});
  cases.push_back({"vegetation", "zero_wind_is_rest", "no wind: every bark vertex stays at its rest position (< 1e-5 m)",
                   false, [] {
                     const TreeProbe p = probe({0, 0, 0}, 7.0, 1.0f, false);
                     StabilityOutcome o;
                     o.nan_count = p.non_finite;
                     o.passed = p.error.empty() && p.max_rest_offset < 1e-5f;
                     o.detail = p.error.empty() ? fmt::format("largest offset from rest {:.2e} m", p.max_rest_offset)
                                                : p.error;
                     return o;
                   }});
  cases.push_back({"vegetation", "zero_length_branches", "every fifth branch of length 0 under wind x100: no NaN",
                   false, [] {
                     const TreeProbe p = probe({6.0f, 0.0f, 2.0f}, 3.0, 100.0f, true);
                     StabilityOutcome o;
                     o.nan_count = p.non_finite;
                     o.passed = p.error.empty();
                     o.detail = p.error.empty() ? fmt::format("{} branches, {} non-finite values", p.branches,
                                                              p.non_finite)
                                                : p.error;
                     return o;
                   }});
}

}  // namespace sylva::bench
