#include <sylva/vegetation/animation.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/core/noise.hpp>
#include <sylva/vegetation/bending.hpp>

#include <bit>
#include <cmath>

namespace sylva::vegetation {
namespace {

const LevelAnimation& level_settings(const AnimationSettings& s, int k) {
  switch (k) {
    case 0: return s.trunk;
    case 1: return s.level1;
    case 2: return s.level2;
    default: return s.level3;
  }
}

// Seeds of the two leaf field components, derived from the wind's turbulence seed so the field
// belongs to the wind (every tree and every model sees the same field).
std::uint32_t leaf_field_seed(const WindGpuParams& wind, std::uint32_t component) {
  return wind.seeds[1] + 0x9e3779b9u * (component + 1u);
}

// One bending step (see animation.hpp, step 3): moves `o` to the bent axis point at x and turns
// the frame. A = 0 takes the rest path o + (x L) t, bit-identical to Branch::axis_point.
void bend_step(ChainState& c, const BranchGpu& b, float x, glm::vec2 amp, float eps) {
  const float length = b.r_parent.w;
  const float a = std::sqrt(amp.x * amp.x + amp.y * amp.y);
  if (a == 0.0f) {
    c.origin = c.origin + (x * length) * c.t;
    return;
  }
  const float inv_a = 1.0f / a;
  const float er = amp.x * inv_a;
  const float es = amp.y * inv_a;
  const glm::vec3 e = er * c.r + es * c.s;
  const float sat = saturate_amplitude(a, b.attach_object.w);
  const BendPoint p = bend_profile(x, sat, b.s_parent.w, b.t_parent.w, eps);
  c.origin = c.origin + length * (p.along * c.t + p.across * e);
  const glm::vec3 delta = -p.sin_theta * c.t + (p.cos_theta - 1.0f) * e;
  const glm::vec3 t_new = p.cos_theta * c.t + p.sin_theta * e;
  c.r = c.r + er * delta;
  c.s = c.s + es * delta;
  c.t = t_new;
}

}  // namespace

AnimationGpu make_animation_gpu(const AnimationSettings& s, double time) {
  AnimationGpu g{};
  if (!std::isfinite(time)) time = 0.0;
  for (int k = 0; k < kMaxLevels; ++k) {
    const LevelAnimation& l = level_settings(s, k);
    g.level[k] = glm::vec4(l.response, l.turbulence, l.frequency, l.enabled ? 1.0f : 0.0f);
    const NoiseCoord1 c = split_noise_coord(time * static_cast<double>(l.frequency));
    g.clock_cell[k] = c.cell;
    g.clock_offset[k] = c.offset;
  }
  const int octave = s.leaf_field_octave < 0 ? 0 : (s.leaf_field_octave > 6 ? 6 : s.leaf_field_octave);
  g.leaf = glm::vec4(s.leaf_amplitude, s.leaf_twist, s.leaf_flutter, s.leaf_max > 0.0f ? s.leaf_max : 1.0f);
  g.leaf2 = glm::vec4(s.leaf_frequency, static_cast<float>(1 << octave), s.leaves_enabled ? 1.0f : 0.0f,
                      static_cast<float>(octave));
  const NoiseCoord1 lc = split_noise_coord(time * static_cast<double>(s.leaf_frequency));
  g.leaf_clock = glm::ivec4(lc.cell, octave, 0, 0);
  g.leaf_clock_offset = glm::vec4(lc.offset, 0.0f, 0.0f, 0.0f);
  g.misc = glm::vec4(s.epsilon, s.frame_transport ? 1.0f : 0.0f, s.wind_scale, 0.0f);
  return g;
}

AnimationGpu rest_animation() {
  AnimationSettings s;
  s.trunk.enabled = s.level1.enabled = s.level2.enabled = s.level3.enabled = false;
  s.leaves_enabled = false;
  return make_animation_gpu(s, 0.0);
}

InstanceGpu make_instance_gpu(const TreeInstance& inst, const glm::dvec3& camera_origin, const glm::vec3& wind_world) {
  InstanceGpu g{};
  const glm::vec3 rel(inst.position - camera_origin);
  g.translation_scale = glm::vec4(rel, inst.scale);
  const float c = std::cos(inst.yaw);
  const float s = std::sin(inst.yaw);
  g.rotation = glm::vec4(c, s, inst.time_offset, inst.season_offset);
  // Non-finite wind counts as calm; speeds beyond kMaxWindSpeed are scaled down to it (every
  // amplitude saturates long before, this only keeps |W| and its products finite).
  glm::dvec3 w(wind_world);
  if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z)) w = glm::dvec3(0.0);
  const double speed = glm::length(w);
  if (speed > kMaxWindSpeed) w *= kMaxWindSpeed / speed;
  const glm::vec3 wo(static_cast<float>(c * w.x - s * w.z), static_cast<float>(w.y), static_cast<float>(s * w.x + c * w.z));
  g.wind = glm::vec4(wo, std::sqrt(wo.x * wo.x + wo.y * wo.y + wo.z * wo.z));
  g.variation = glm::vec4(inst.color_variation, inst.number);
  return g;
}

InstanceGpu make_instance_gpu(const TreeInstance& inst, const glm::dvec3& camera_origin, const WindField& wind,
                              double time, const AnimationSettings& settings) {
  return make_instance_gpu(inst, camera_origin, wind.evaluate(inst.position, time) * settings.wind_scale);
}

glm::vec3 instance_vector(const InstanceGpu& inst, const glm::vec3& v) {
  const float c = inst.rotation.x;
  const float s = inst.rotation.y;
  return glm::vec3(c * v.x + s * v.z, v.y, -s * v.x + c * v.z);
}

glm::vec3 instance_point(const InstanceGpu& inst, const glm::vec3& p) {
  return glm::vec3(inst.translation_scale) + instance_vector(inst, inst.translation_scale.w * p);
}

glm::vec2 branch_control(const BranchGpu& b, const AnimationGpu& anim, const InstanceGpu& inst, int level,
                         const glm::vec3& r, const glm::vec3& s) {
  const glm::vec4 lp = anim.level[level];
  if (lp.w == 0.0f) return glm::vec2(0.0f);
  const glm::vec3 w(inst.wind);
  const float offset = anim.clock_offset[level] + b.r_object.w + inst.rotation.z * lp.z;
  const float nr = gradient_noise1(anim.clock_cell[level], offset, b.seeds.x);
  const float ns = gradient_noise1(anim.clock_cell[level], offset, b.seeds.y);
  const float turb = lp.y * inst.wind.w;
  return glm::vec2(lp.x * glm::dot(w, r) + turb * nr, lp.x * glm::dot(w, s) + turb * ns);
}

glm::vec2 leaf_control(const LeafGpu& leaf, const AnimationGpu& anim, const InstanceGpu& inst, const WindGpuParams& wind) {
  if (anim.leaf2.z == 0.0f) return glm::vec2(0.0f);
  const float speed = inst.wind.w;
  const auto octave = static_cast<std::uint32_t>(anim.leaf_clock.y);
  const glm::ivec3 cell(static_cast<std::int32_t>(static_cast<std::uint32_t>(wind.cells[0]) << octave),
                        static_cast<std::int32_t>(static_cast<std::uint32_t>(wind.cells[1]) << octave),
                        static_cast<std::int32_t>(static_cast<std::uint32_t>(wind.cells[2]) << octave));
  const glm::vec3 rel = instance_point(inst, glm::vec3(leaf.origin));
  const glm::vec3 toff(wind.turbulence_offset[0], wind.turbulence_offset[1], wind.turbulence_offset[2]);
  const glm::vec3 off = (toff + rel * wind.turbulence[2]) * anim.leaf2.y;
  const float fx = gradient_noise3(cell, off, leaf_field_seed(wind, 0u));
  const float fy = gradient_noise3(cell, off, leaf_field_seed(wind, 1u));
  const std::uint32_t seed = std::bit_cast<std::uint32_t>(leaf.origin.w);
  const float foff = anim.leaf_clock_offset.x + leaf.n_parent.w + inst.rotation.z * anim.leaf2.x;
  const float nx = gradient_noise1(anim.leaf_clock.x, foff, seed);
  const float ny = gradient_noise1(anim.leaf_clock.x, foff, seed + 1u);
  const float mix = anim.leaf.z;
  const float ax = anim.leaf.x * speed * ((1.0f - mix) * fx + mix * nx);
  const float ay = anim.leaf.x * anim.leaf.y * speed * ((1.0f - mix) * fy + mix * ny);
  const auto sat = [&](float a) {
    const float q = a / anim.leaf.w;
    return a / std::sqrt(1.0f + q * q);
  };
  return glm::vec2(sat(ax), sat(ay));
}

ChainState evaluate_chain(const TreeGpuData& data, const AnimationGpu& anim, const InstanceGpu& inst,
                          std::uint32_t branch, const glm::vec4& xvec) {
  SYLVA_ASSERT(branch < data.branches.size(), "branch={} count={}", branch, data.branches.size());
  const BranchGpu& own = data.branches[branch];
  const int level = static_cast<int>(own.s_object.w);
  const bool transport = anim.misc.y != 0.0f;
  const float eps = anim.misc.x;
  ChainState c;
  for (int k = 0; k <= level; ++k) {
    const BranchGpu& b = data.branches[static_cast<std::size_t>(own.chain[k])];
    if (k == 0) {
      c.origin = glm::vec3(b.attach_object);
      c.t = glm::vec3(b.t_object);
      c.r = glm::vec3(b.r_object);
      c.s = glm::vec3(b.s_object);
    } else if (transport) {
      const glm::vec3 ap(b.attach_parent);
      c.origin = c.origin + (ap.x * c.r + ap.y * c.s + ap.z * c.t);
      const glm::vec3 r = b.r_parent.x * c.r + b.r_parent.y * c.s + b.r_parent.z * c.t;
      const glm::vec3 s = b.s_parent.x * c.r + b.s_parent.y * c.s + b.s_parent.z * c.t;
      const glm::vec3 t = b.t_parent.x * c.r + b.t_parent.y * c.s + b.t_parent.z * c.t;
      c.r = r;
      c.s = s;
      c.t = t;
    } else {
      c.origin = c.origin + glm::vec3(b.attach_object);
      c.t = glm::vec3(b.t_object);
      c.r = glm::vec3(b.r_object);
      c.s = glm::vec3(b.s_object);
    }
    const glm::vec2 amp = branch_control(b, anim, inst, k, c.r, c.s);
    bend_step(c, b, xvec[k], amp, eps);
  }
  return c;
}

DeformedVertex deform_branch_vertex(const TreeGpuData& data, const AnimationGpu& anim, const InstanceGpu& inst,
                                    const BranchVertex& v) {
  const ChainState c = evaluate_chain(data, anim, inst, v.branch, v.xvec);
  DeformedVertex out;
  out.position = c.origin + (v.local.x * c.r + v.local.y * c.s + v.local.z * c.t);
  out.normal = v.normal.x * c.r + v.normal.y * c.s + v.normal.z * c.t;
  out.tangent = c.t;
  return out;
}

DeformedVertex deform_leaf_vertex(const TreeGpuData& data, const AnimationGpu& anim, const InstanceGpu& inst,
                                  const WindGpuParams& wind, const LeafVertex& v) {
  SYLVA_ASSERT(v.leaf < data.leaves.size(), "leaf={} count={}", v.leaf, data.leaves.size());
  const ChainState c = evaluate_chain(data, anim, inst, v.branch, v.xvec);
  const LeafGpu& leaf = data.leaves[v.leaf];
  glm::vec3 t0;
  glm::vec3 n0;
  if (anim.misc.y != 0.0f) {
    t0 = leaf.t_parent.x * c.r + leaf.t_parent.y * c.s + leaf.t_parent.z * c.t;
    n0 = leaf.n_parent.x * c.r + leaf.n_parent.y * c.s + leaf.n_parent.z * c.t;
  } else {
    t0 = glm::vec3(leaf.t_object);
    n0 = glm::vec3(leaf.n_object);
  }
  const glm::vec2 a = leaf_control(leaf, anim, inst, wind);
  glm::vec3 t1 = t0;
  glm::vec3 n2 = n0;
  glm::vec3 b2 = glm::cross(t0, n0);
  if (a.x != 0.0f || a.y != 0.0f) {
    const glm::vec3 b0 = b2;
    t1 = glm::normalize(t0 + n0 * a.x);
    const glm::vec3 n1 = glm::cross(b0, t1);
    n2 = glm::normalize(n1 + b0 * a.y);
    b2 = glm::cross(t1, n2);
  }
  DeformedVertex out;
  out.position = c.origin + (v.corner.x * b2 + v.corner.y * t1);
  out.normal = n2;
  out.tangent = t1;
  return out;
}

glm::vec4 hierarchy_vector(const TreeGpuData& data, std::uint32_t branch, float x) {
  SYLVA_ASSERT(branch < data.branches.size(), "branch={} count={}", branch, data.branches.size());
  const BranchGpu& own = data.branches[branch];
  const int level = static_cast<int>(own.s_object.w);
  glm::vec4 xv(0.0f);
  for (int k = 0; k < level; ++k)
    xv[k] = data.branches[static_cast<std::size_t>(own.chain[k + 1])].attach_parent.w;
  xv[level] = x;
  return xv;
}

glm::vec3 branch_axis_point(const TreeGpuData& data, const AnimationGpu& anim, const InstanceGpu& inst,
                            std::uint32_t branch, float x) {
  return evaluate_chain(data, anim, inst, branch, hierarchy_vector(data, branch, x)).origin;
}

}  // namespace sylva::vegetation
