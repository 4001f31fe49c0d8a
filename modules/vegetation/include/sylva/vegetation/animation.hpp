#pragma once
// CPU reference of the LOD0 wind animation (seed 000 §3.1, §4.4). The vertex shaders include
// shaders/lib/tree_animation.glsl, which performs the same float operations in the same order on
// the same packed inputs, so the GPU result can be checked against this code (tree_animation_gl_test).
//
// Per vertex, from the trunk down the vertex's branch chain (hierarchical vertex displacement,
// §3.1.2), for each level k with branch b_k and hierarchy value x_k:
//  1. frame: the root starts from its rest frame at its start point; a child takes its rest frame
//     expressed in the parent's frame and maps it through the parent's *bent* frame at the
//     attachment point (frame transport, switchable: off, children keep their rest orientation,
//     seed Fig. 3.8b);
//  2. control signal (§3.1.4, eq. 3.17): A = response_k * (W . r, W . s) + turbulence_k * |W| *
//     (n_r(t), n_s(t)), with W the wind at the tree in object space (the core WindField, one wind
//     for trees and grass) projected on the current frame, and n 1D gradient noise of time at
//     frequency_k, per branch seed and phase, plus a per-instance time offset. The noise is an
//     analytic, C2-continuous function of time (core noise, evaluated from a per-frame split of
//     time * frequency into an integer cell and a float offset), so any frame time - 0, 1 s or
//     1e7 s - gives a smooth, bounded motion and there is no integration state to blow up;
//  3. bend (bending.hpp): the amplitude |A| saturates below the branch's amplitude limit, the
//     axis point at x_k moves by the length-corrected u(x) in the plane of A (the seed bends r and
//     s separately; bending in the plane of the resultant makes the correction exact for
//     diagonal winds), and the frame turns by the tangent angle atan(u'(x_k)) in that plane - an
//     exact rotation, so frames stay orthonormal (the seed's first-order update followed by
//     normalize() does not, and its t update has a typo, errata 10).
// A bark vertex then sits at origin + local.r r + local.s s + local.t t with normal
// n.r r + n.s s + n.t t. A leaf vertex (§3.1.3) takes its rest frame (n0, t0) through the
// parent's bent frame, tilts and twists it by the leaf signals (eq. 3.16, normalised as in the
// shader, with b = t x n so that the rest pose is reproduced exactly):
//     t1 = normalize(t0 + n0 A_x),  n1 = b0 x t1,  n2 = normalize(n1 + b0 A_y),  b2 = t1 x n2,
//     P = O + P_x b2 + P_y t1,
// where (A_x, A_y) = leaf_amplitude * |W| * mix(field, flutter): field = two 3D gradient-noise
// fields sampled at the leaf's rest position on the core wind's turbulence lattice (advected with
// the mean wind, so a gust visibly travels through the crown, §3.1.4 eq. 3.18's purpose without its
// unnormalised weights and its division by |W|), flutter = 1D noise of time per leaf; each
// saturates below leaf_max.
//
// Rest pose: with W = 0 every amplitude is exactly 0, bending and leaf rotation are skipped, and
// the evaluation reduces to the rest chain: the deformed mesh equals the model's rest mesh.
//
// Units: positions metres, W m/s, response and turbulence 1/(m/s) (A is relative to the branch
// length), frequencies noise cells per second (a cell is roughly half a sway period).

#include <sylva/core/params.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/vegetation/tree_mesh.hpp>

#include <glm/glm.hpp>

#include <cstdint>

namespace sylva::vegetation {

struct LevelAnimation {
  float response = 0.01f;     // control amplitude per m/s of wind across the branch
  float turbulence = 0.005f;  // noise amplitude per m/s of wind speed
  float frequency = 0.5f;     // noise cells per second
  bool enabled = true;

  template <class V>
  void visit(V& v) {
    v(response, "response", {.min = 0.0, .max = 10.0, .unit = "1/(m/s)", .help = "Directional bend per m/s of wind"});
    v(turbulence, "turbulence", {.min = 0.0, .max = 10.0, .unit = "1/(m/s)", .help = "Random sway per m/s of wind"});
    v(frequency, "frequency", {.min = 0.0, .max = 100.0, .unit = "1/s", .help = "Sway noise cells per second"});
    v(enabled, "enabled", {.help = "Animate this branch level"});
  }
};

struct AnimationSettings {
  LevelAnimation trunk{0.0035f, 0.0015f, 0.25f, true};
  LevelAnimation level1{0.010f, 0.006f, 0.55f, true};
  LevelAnimation level2{0.018f, 0.012f, 0.9f, true};
  LevelAnimation level3{0.025f, 0.02f, 1.4f, true};
  float leaf_amplitude = 0.06f;   // leaf tilt per m/s of wind speed
  float leaf_twist = 0.8f;        // twist amplitude relative to the tilt
  float leaf_flutter = 0.5f;      // share of the per-leaf flutter against the travelling field
  float leaf_frequency = 2.5f;    // flutter noise cells per second
  float leaf_max = 1.2f;          // saturation of the leaf signals (tan of the largest tilt)
  int leaf_field_octave = 1;      // leaf field scale = wind turbulence scale / 2^octave
  bool leaves_enabled = true;
  bool frame_transport = true;    // seed §3.1.2; off is cheaper, children flatten under bending
  float epsilon = 1.0e-6f;        // guard of u' in the length correction
  float wind_scale = 1.0f;        // multiplies the wind (tests use x10, x100)

  template <class V>
  void visit(V& v) {
    v(trunk, "trunk");
    v(level1, "level1");
    v(level2, "level2");
    v(level3, "level3");
    v(leaf_amplitude, "leaf_amplitude", {.min = 0.0, .max = 10.0, .unit = "1/(m/s)", .help = "Leaf tilt per m/s of wind"});
    v(leaf_twist, "leaf_twist", {.min = 0.0, .max = 10.0, .help = "Leaf twist relative to tilt"});
    v(leaf_flutter, "leaf_flutter", {.min = 0.0, .max = 1.0, .help = "Share of per-leaf flutter vs the travelling gust field"});
    v(leaf_frequency, "leaf_frequency", {.min = 0.0, .max = 100.0, .unit = "1/s", .help = "Leaf flutter noise cells per second"});
    v(leaf_max, "leaf_max", {.min = 0.01, .max = 100.0, .help = "Saturation of leaf signals (tan of the largest tilt)"});
    v(leaf_field_octave, "leaf_field_octave", {.min = 0, .max = 6, .help = "Leaf field scale = wind turbulence scale / 2^octave"});
    v(leaves_enabled, "leaves_enabled", {.help = "Animate leaves"});
    v(frame_transport, "frame_transport", {.help = "Carry bent frames down the hierarchy (seed 3.1.2)"});
    v(epsilon, "epsilon", {.min = 1e-12, .max = 1e-2, .help = "Guard of u' in the length correction", .log_scale = true});
    v(wind_scale, "wind_scale", {.min = 0.0, .max = 1000.0, .help = "Multiplier of the wind seen by the trees"});
  }
};

// Per-frame animation block, std140 (shaders/lib/tree_animation.glsl: SylvaTreeAnimation).
struct AnimationGpu {
  glm::vec4 level[kMaxLevels];  // x response, y turbulence, z frequency, w enabled (0 / 1)
  glm::ivec4 clock_cell;        // per level: integer cell of time * frequency
  glm::vec4 clock_offset;       // per level: offset in [0, 1) of time * frequency
  glm::vec4 leaf;               // x amplitude, y twist, z flutter share, w leaf_max
  glm::vec4 leaf2;              // x flutter frequency, y 2^octave, z enabled, w octave
  glm::ivec4 leaf_clock;        // x cell of time * leaf_frequency
  glm::vec4 leaf_clock_offset;  // x offset
  glm::vec4 misc;               // x epsilon, y frame transport (0 / 1), z wind scale
};
static_assert(sizeof(AnimationGpu) == 176, "AnimationGpu must match the std140 layout of SylvaTreeAnimation");

// Builds the block for scene time `time` [s] (split in double precision, see above).
AnimationGpu make_animation_gpu(const AnimationSettings& settings, double time);
// The block that produces the rest pose (everything disabled).
AnimationGpu rest_animation();

// One tree instance for the shaders (std430, 80 bytes).
struct InstanceGpu {
  glm::vec4 translation_scale;  // xyz camera-relative position of the object origin [m], w scale
  glm::vec4 rotation;           // x cos(yaw), y sin(yaw), z time offset [s], w season offset
  glm::vec4 wind;               // xyz wind at the tree in object space [m/s] (scaled), w its length
  glm::vec4 variation;          // rgb colour variation, w instance number in [0, 1)
  glm::vec4 lod{1.0f, 0.0f, 0.0f, 0.0f};  // x LOD transition fade in [0, 1] (1 = opaque, dithered
                                          // below, lod_selection.hpp), y LOD coordinate
};
static_assert(sizeof(InstanceGpu) == 80);

// A placed tree (world space, double precision).
struct TreeInstance {
  glm::dvec3 position{0.0};    // world position of the tree's object origin [m]
  float yaw = 0.0f;            // rotation about +y [rad]
  float scale = 1.0f;          // uniform scale, > 0
  float time_offset = 0.0f;    // animation phase [s], [0, 100)
  float season_offset = 0.0f;  // added to the season coordinate
  glm::vec3 color_variation{0.0f};  // added to the leaf colour (linear RGB)
  float number = 0.0f;         // instanceSpecificNumber in [0, 1)
};

// Wind speeds above this are scaled down to it in make_instance_gpu [m/s].
inline constexpr double kMaxWindSpeed = 1.0e5;

// The wind at the instance (WindField::evaluate at its position and time, times wind_scale),
// rotated into object space; translation relative to `camera_origin`.
InstanceGpu make_instance_gpu(const TreeInstance& instance, const glm::dvec3& camera_origin, const WindField& wind,
                              double time, const AnimationSettings& settings);
// The same with an explicit world-space wind vector [m/s]; non-finite wind counts as calm.
InstanceGpu make_instance_gpu(const TreeInstance& instance, const glm::dvec3& camera_origin, const glm::vec3& wind_world);

// Object space -> camera-relative world space (rotation about y, uniform scale, translation).
glm::vec3 instance_point(const InstanceGpu& instance, const glm::vec3& object);
glm::vec3 instance_vector(const InstanceGpu& instance, const glm::vec3& object);

// The bent state of a chain: axis point and frame.
struct ChainState {
  glm::vec3 origin{0.0f};
  glm::vec3 t{0.0f, 1.0f, 0.0f};
  glm::vec3 r{1.0f, 0.0f, 0.0f};
  glm::vec3 s{0.0f, 0.0f, -1.0f};
};

// Evaluates levels 0..level(branch) with x values xvec (steps 1-3 above), in object space.
ChainState evaluate_chain(const TreeGpuData& data, const AnimationGpu& anim, const InstanceGpu& instance,
                          std::uint32_t branch, const glm::vec4& xvec);

// Control signal of branch `branch` at hierarchy level `level` for the current frame (r, s).
glm::vec2 branch_control(const BranchGpu& branch, const AnimationGpu& anim, const InstanceGpu& instance, int level,
                         const glm::vec3& r, const glm::vec3& s);
// Leaf signals (A_x, A_y); `wind` is the frame's wind block (WindField::frame(time, camera_origin).gpu).
glm::vec2 leaf_control(const LeafGpu& leaf, const AnimationGpu& anim, const InstanceGpu& instance,
                       const WindGpuParams& wind);

struct DeformedVertex {
  glm::vec3 position{0.0f};  // object space (instance_point gives world)
  glm::vec3 normal{0.0f};
  glm::vec3 tangent{0.0f};
};

DeformedVertex deform_branch_vertex(const TreeGpuData& data, const AnimationGpu& anim, const InstanceGpu& instance,
                                    const BranchVertex& vertex);
DeformedVertex deform_leaf_vertex(const TreeGpuData& data, const AnimationGpu& anim, const InstanceGpu& instance,
                                  const WindGpuParams& wind, const LeafVertex& vertex);

// The bent axis point of a branch at x (object space), for tests of the invariants.
glm::vec3 branch_axis_point(const TreeGpuData& data, const AnimationGpu& anim, const InstanceGpu& instance,
                            std::uint32_t branch, float x);
// Hierarchy vector that puts a point at x on `branch`.
glm::vec4 hierarchy_vector(const TreeGpuData& data, std::uint32_t branch, float x);

}  // namespace sylva::vegetation
