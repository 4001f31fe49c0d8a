#include <sylva/vegetation/generator.hpp>

#include <sylva/core/rng.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva::vegetation {
namespace {

constexpr float kDeg = std::numbers::pi_v<float> / 180.0f;
const glm::vec3 kUp(0.0f, 1.0f, 0.0f);

// A unit vector orthogonal to t, preferring the component of `hint` orthogonal to t.
glm::vec3 orthogonal_to(const glm::vec3& t, const glm::vec3& hint) {
  glm::vec3 r = hint - glm::dot(hint, t) * t;
  if (glm::length(r) < 1.0e-4f) {
    const glm::vec3 alt = std::fabs(t.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 0.0f, 1.0f);
    r = alt - glm::dot(alt, t) * t;
  }
  return glm::normalize(r);
}

BranchFrame frame_along(const glm::vec3& dir, const glm::vec3& r_hint) {
  BranchFrame f;
  f.t = glm::normalize(dir);
  f.r = orthogonal_to(f.t, r_hint);
  f.s = glm::cross(f.t, f.r);
  return f;
}

// Direction tilted towards +y (g > 0) or -y (g < 0); keeps d when the result would vanish.
glm::vec3 apply_gravitropism(const glm::vec3& d, float g) {
  const glm::vec3 v = d + g * kUp;
  const float len = glm::length(v);
  return len > 1.0e-3f ? v / len : d;
}

float crown_profile(CrownShape shape, float xn) {
  switch (shape) {
    case CrownShape::kConical:
      return 1.0f - 0.92f * xn;  // to a narrow spire (spruce, fir)
    case CrownShape::kSpherical:
      return 0.3f + 0.7f * std::sin(std::numbers::pi_v<float> * (0.12f + 0.8f * xn));
    case CrownShape::kColumnar:
      return 1.0f - 0.3f * xn;
  }
  return 1.0f;
}

int varied_count(Pcg32& rng, int count, float variation) {
  const float c = static_cast<float>(count) * (1.0f + variation * rng.uniform(-1.0f, 1.0f));
  return std::max(0, static_cast<int>(std::lround(c)));
}

Status check_settings(const TreeSpecies& s) {
  if (Status st = validate_params(s, "species"); !st.ok()) return st;
  const LevelSettings* levels[] = {&s.level1, &s.level2, &s.level3};
  const char* names[] = {"level1", "level2", "level3"};
  for (int i = 0; i < 3; ++i) {
    if (levels[i]->start > levels[i]->end)
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("species.{}.start: {} is after species.{}.end = {}", names[i], levels[i]->start,
                                    names[i], levels[i]->end));
  }
  return ok_status();
}

struct Builder {
  const TreeSpecies& species;
  const GeneratorLimits& limits;
  TreeModel model;

  Pcg32 rng_for(std::uint32_t id, std::uint32_t salt) const {
    return Pcg32(hash_u32(id, species.seed, salt), hash_u32(salt, species.seed));
  }

  Status add_branch(Branch b) {
    if (model.branches.size() >= limits.max_branches)
      return make_error(ErrorCode::kLimit, fmt::format("species '{}': more than {} branches (reduce levelN.count)",
                                                       species.name, limits.max_branches));
    b.id = static_cast<int>(model.branches.size());
    model.branches.push_back(b);
    return ok_status();
  }

  Status trunks() {
    Pcg32 rng = rng_for(0xffffffffu, 1u);
    const int n = species.trunk_count;
    for (int i = 0; i < n; ++i) {
      const float azimuth = (static_cast<float>(i) + 0.35f * rng.uniform(-1.0f, 1.0f)) * 2.0f *
                            std::numbers::pi_v<float> / static_cast<float>(n);
      const float spread = n > 1 ? species.trunk_spread_deg * kDeg * (0.7f + 0.3f * rng.next_float()) : 0.0f;
      const float lean = species.trunk_lean_deg * kDeg * rng.next_float();
      const float lean_az = rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
      glm::vec3 dir(std::sin(spread) * std::cos(azimuth), std::cos(spread), std::sin(spread) * std::sin(azimuth));
      dir = glm::normalize(dir + std::sin(lean) * glm::vec3(std::cos(lean_az), 0.0f, std::sin(lean_az)));
      Branch b;
      b.level = 0;
      b.parent = -1;
      b.parent_x = 0.0f;
      b.length = species.trunk_length * (1.0f + species.trunk_length_variation * rng.uniform(-1.0f, 1.0f));
      const float base_offset = n > 1 ? 0.08f : 0.0f;
      b.start = glm::vec3(base_offset * std::cos(azimuth), 0.0f, base_offset * std::sin(azimuth));
      b.frame = frame_along(dir, glm::vec3(1.0f, 0.0f, 0.0f));
      SYLVA_TRY(add_branch(b));
    }
    return ok_status();
  }

  Status children(int level) {
    const LevelSettings& ls = level == 1 ? species.level1 : level == 2 ? species.level2 : species.level3;
    const std::size_t parents_end = model.branches.size();
    for (std::size_t pi = 0; pi < parents_end; ++pi) {
      if (model.branches[pi].level != level - 1) continue;
      const Branch parent = model.branches[pi];
      Pcg32 rng = rng_for(static_cast<std::uint32_t>(parent.id), 2u + static_cast<std::uint32_t>(level));
      const int count = varied_count(rng, ls.count, ls.count_variation);
      if (count == 0 || parent.length <= 0.0f) continue;
      const int per_node = std::max(1, ls.per_node);
      const int nodes = (count + per_node - 1) / per_node;
      const float roll0 = rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
      int made = 0;
      for (int j = 0; j < nodes; ++j) {
        const float u = nodes == 1 ? 0.5f : (static_cast<float>(j) + 0.25f * rng.uniform(-1.0f, 1.0f)) / static_cast<float>(nodes - 1);
        const float un = std::clamp(u, 0.0f, 1.0f);
        const float x = std::clamp(ls.start + (ls.end - ls.start) * un, 0.0f, 1.0f);
        const float node_roll = roll0 + static_cast<float>(j) * ls.roll_deg * kDeg;
        for (int m = 0; m < per_node && made < count; ++m, ++made) {
          const float roll = node_roll + static_cast<float>(m) * 2.0f * std::numbers::pi_v<float> / static_cast<float>(per_node) +
                             0.15f * rng.uniform(-1.0f, 1.0f);
          const float angle = (ls.angle_deg + ls.angle_variation_deg * rng.uniform(-1.0f, 1.0f)) * kDeg;
          const glm::vec3 radial = std::cos(roll) * parent.frame.r + std::sin(roll) * parent.frame.s;
          glm::vec3 dir = std::cos(angle) * parent.frame.t + std::sin(angle) * radial;
          dir = apply_gravitropism(glm::normalize(dir), ls.gravitropism);
          const float profile = level == 1 ? crown_profile(species.crown_shape, un) : 1.0f - 0.6f * un;
          const float shaped = 1.0f - ls.length_profile * (1.0f - profile);
          Branch b;
          b.level = level;
          b.parent = static_cast<int>(pi);
          b.parent_x = x;
          b.length = std::max(0.0f, parent.length * ls.length_ratio * shaped *
                                        (1.0f + ls.length_variation * rng.uniform(-1.0f, 1.0f)));
          b.start = parent.axis_point(x);
          b.frame = frame_along(dir, parent.frame.t);
          SYLVA_TRY(add_branch(b));
        }
      }
    }
    return ok_status();
  }

  // da Vinci radii, bottom-up (children have larger indices than their parents).
  void radii() {
    const float D = species.da_vinci_exponent;
    std::vector<double> sum(model.branches.size(), 0.0);  // sum of children's r_base^D
    for (std::size_t i = model.branches.size(); i-- > 0;) {
      Branch& b = model.branches[i];
      b.radius_tip = species.twig_radius;
      const double tip = std::pow(static_cast<double>(species.twig_radius), static_cast<double>(D));
      // A branch without children still thickens towards its base as if one twig left it.
      const double below = sum[i] > 0.0 ? sum[i] : tip;
      b.radius_base = static_cast<float>(std::pow(tip + below, 1.0 / static_cast<double>(D)));
      if (b.parent >= 0) sum[static_cast<std::size_t>(b.parent)] += std::pow(static_cast<double>(b.radius_base), static_cast<double>(D));
    }
  }

  Status leaves() {
    const LeafSettings& ls = species.leaves;
    if (ls.levels <= 0) return ok_status();
    const int first_level = std::max(0, species.levels - ls.levels);
    for (std::size_t bi = 0; bi < model.branches.size(); ++bi) {
      const Branch& b = model.branches[bi];
      if (b.level < first_level) continue;
      Pcg32 rng = rng_for(static_cast<std::uint32_t>(b.id), 17u);
      const float span = b.length * (1.0f - ls.start);
      int n = std::min(ls.max_per_branch, static_cast<int>(std::floor(ls.per_metre * span + rng.next_float())));
      n = std::max(n, 0);
      int per_node = 1;
      float roll_step = std::numbers::pi_v<float>;  // alternate: two ranks
      switch (ls.arrangement) {
        case LeafArrangement::kAlternate: break;
        case LeafArrangement::kOpposite: per_node = 2; roll_step = 0.5f * std::numbers::pi_v<float>; break;
        case LeafArrangement::kWhorled: per_node = 3; roll_step = std::numbers::pi_v<float> / 3.0f; break;
        case LeafArrangement::kSpiral: roll_step = 137.5f * kDeg; break;
      }
      const int nodes = (n + per_node - 1) / per_node;
      const float roll0 = rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
      int made = 0;
      for (int j = 0; j < nodes; ++j) {
        const float u = (static_cast<float>(j) + 0.5f + 0.3f * rng.uniform(-1.0f, 1.0f)) / static_cast<float>(nodes);
        const float x = std::clamp(ls.start + (1.0f - ls.start) * u, 0.0f, 1.0f);
        for (int m = 0; m < per_node && made < n; ++m, ++made) {
          const float roll = roll0 + static_cast<float>(j) * roll_step +
                             static_cast<float>(m) * 2.0f * std::numbers::pi_v<float> / static_cast<float>(per_node);
          SYLVA_TRY(add_leaf(rng, b, static_cast<int>(bi), x, roll, ls.petiole_angle_deg * kDeg));
        }
      }
      if (ls.terminal_leaf) SYLVA_TRY(add_leaf(rng, b, static_cast<int>(bi), 1.0f, roll0, 0.15f));
    }
    return ok_status();
  }

  Status add_leaf(Pcg32& rng, const Branch& b, int parent, float x, float roll, float petiole) {
    const LeafSettings& ls = species.leaves;
    if (model.leaves.size() >= limits.max_leaves)
      return make_error(ErrorCode::kLimit, fmt::format("species '{}': more than {} leaves (reduce leaves.per_metre)",
                                                       species.name, limits.max_leaves));
    const glm::vec3 radial = std::cos(roll) * b.frame.r + std::sin(roll) * b.frame.s;
    glm::vec3 t = std::cos(petiole) * b.frame.t + std::sin(petiole) * radial;
    t = apply_gravitropism(glm::normalize(t), -ls.droop);
    // Normal: towards the sky by phototropism, else facing out of the branch; then jittered.
    const glm::vec3 sky = orthogonal_to(t, kUp);
    const glm::vec3 out = orthogonal_to(t, radial);
    glm::vec3 n = orthogonal_to(t, ls.phototropism * sky + (1.0f - ls.phototropism) * out);
    const float jitter = ls.orientation_jitter * rng.uniform(-1.0f, 1.0f);
    const glm::vec3 bt = glm::cross(t, n);
    n = std::cos(jitter) * n + std::sin(jitter) * bt;  // twist about t
    const float tilt = 0.5f * ls.orientation_jitter * rng.uniform(-1.0f, 1.0f);
    const glm::vec3 t2 = glm::normalize(std::cos(tilt) * t + std::sin(tilt) * n);  // tilt about b
    const glm::vec3 n2 = orthogonal_to(t2, n);
    Leaf l;
    l.id = static_cast<int>(model.leaves.size());
    l.parent = parent;
    l.parent_x = x;
    l.tangent = t2;
    l.normal = n2;
    l.bitangent = glm::cross(t2, n2);
    const float size = 1.0f + ls.size_variation * rng.uniform(-1.0f, 1.0f);
    l.width = ls.width * size;
    l.length = ls.length * size;
    l.number = rng.next_float();
    model.leaves.push_back(l);
    return ok_status();
  }
};

}  // namespace

TreeSpecies species_preset(SpeciesPreset preset, std::uint32_t seed) {
  TreeSpecies s;
  s.seed = seed;
  switch (preset) {
    case SpeciesPreset::kBroadleaf:
      s.name = "broadleaf";
      s.levels = 4;
      s.trunk_length = 9.0f;
      s.crown_shape = CrownShape::kSpherical;
      s.level1 = {.count = 9, .count_variation = 0.15f, .start = 0.35f, .end = 0.92f, .per_node = 1, .roll_deg = 137.5f,
                  .angle_deg = 50.0f, .angle_variation_deg = 10.0f, .length_ratio = 0.55f, .length_variation = 0.15f,
                  .length_profile = 0.7f, .gravitropism = 0.15f};
      s.level2 = {.count = 7, .count_variation = 0.2f, .start = 0.2f, .end = 0.95f, .per_node = 1, .roll_deg = 137.5f,
                  .angle_deg = 45.0f, .angle_variation_deg = 12.0f, .length_ratio = 0.5f, .length_variation = 0.2f,
                  .length_profile = 0.5f, .gravitropism = 0.05f};
      s.level3 = {.count = 5, .count_variation = 0.25f, .start = 0.3f, .end = 0.95f, .per_node = 1, .roll_deg = 180.0f,
                  .angle_deg = 45.0f, .angle_variation_deg = 15.0f, .length_ratio = 0.55f, .length_variation = 0.2f,
                  .length_profile = 0.4f, .gravitropism = 0.0f};
      s.leaves = {.levels = 2, .per_metre = 14.0f, .max_per_branch = 40, .start = 0.15f, .width = 0.46f, .length = 0.52f,
                  .size_variation = 0.2f, .arrangement = LeafArrangement::kAlternate, .petiole_angle_deg = 50.0f,
                  .droop = 0.3f, .phototropism = 0.6f, .orientation_jitter = 0.3f, .terminal_leaf = true};
      s.leaf_shape = LeafShape::kOvate;
      s.twig_radius = 0.008f;
      s.da_vinci_exponent = 2.0f;
      break;
    case SpeciesPreset::kConifer:
      s.name = "conifer";
      s.levels = 3;
      s.trunk_length = 14.0f;
      s.trunk_lean_deg = 1.5f;
      s.crown_shape = CrownShape::kConical;
      s.level1 = {.count = 56, .count_variation = 0.1f, .start = 0.16f, .end = 0.96f, .per_node = 4, .roll_deg = 45.0f,
                  .angle_deg = 85.0f, .angle_variation_deg = 6.0f, .length_ratio = 0.28f, .length_variation = 0.12f,
                  .length_profile = 1.0f, .gravitropism = -0.3f};
      s.level2 = {.count = 10, .count_variation = 0.2f, .start = 0.12f, .end = 0.92f, .per_node = 2, .roll_deg = 90.0f,
                  .angle_deg = 55.0f, .angle_variation_deg = 10.0f, .length_ratio = 0.35f, .length_variation = 0.2f,
                  .length_profile = 0.5f, .gravitropism = -0.1f};
      s.leaves = {.levels = 2, .per_metre = 14.0f, .max_per_branch = 40, .start = 0.05f, .width = 0.5f, .length = 0.65f,
                  .size_variation = 0.15f, .arrangement = LeafArrangement::kSpiral, .petiole_angle_deg = 60.0f,
                  .droop = 0.15f, .phototropism = 0.5f, .orientation_jitter = 0.7f, .terminal_leaf = true};
      s.leaf_shape = LeafShape::kNeedles;
      s.twig_radius = 0.006f;
      s.da_vinci_exponent = 2.2f;
      break;
    case SpeciesPreset::kBirch:
      s.name = "birch";
      s.levels = 4;
      s.trunk_length = 11.0f;
      s.trunk_lean_deg = 3.0f;
      s.crown_shape = CrownShape::kColumnar;
      s.level1 = {.count = 9, .count_variation = 0.15f, .start = 0.4f, .end = 0.95f, .per_node = 1, .roll_deg = 137.5f,
                  .angle_deg = 35.0f, .angle_variation_deg = 8.0f, .length_ratio = 0.38f, .length_variation = 0.15f,
                  .length_profile = 0.6f, .gravitropism = 0.1f};
      s.level2 = {.count = 5, .count_variation = 0.2f, .start = 0.3f, .end = 0.95f, .per_node = 1, .roll_deg = 137.5f,
                  .angle_deg = 40.0f, .angle_variation_deg = 12.0f, .length_ratio = 0.55f, .length_variation = 0.2f,
                  .length_profile = 0.4f, .gravitropism = -0.35f};
      s.level3 = {.count = 4, .count_variation = 0.25f, .start = 0.25f, .end = 0.95f, .per_node = 1, .roll_deg = 180.0f,
                  .angle_deg = 30.0f, .angle_variation_deg = 10.0f, .length_ratio = 0.6f, .length_variation = 0.2f,
                  .length_profile = 0.3f, .gravitropism = -0.8f};
      s.leaves = {.levels = 2, .per_metre = 15.0f, .max_per_branch = 40, .start = 0.15f, .width = 0.3f, .length = 0.36f,
                  .size_variation = 0.2f, .arrangement = LeafArrangement::kAlternate, .petiole_angle_deg = 55.0f,
                  .droop = 0.5f, .phototropism = 0.5f, .orientation_jitter = 0.4f, .terminal_leaf = true};
      s.leaf_shape = LeafShape::kBirch;
      s.twig_radius = 0.005f;
      s.da_vinci_exponent = 2.1f;
      break;
    case SpeciesPreset::kShrub:
      s.name = "shrub";
      s.levels = 3;
      s.trunk_count = 6;
      s.trunk_length = 1.6f;
      s.trunk_length_variation = 0.25f;
      s.trunk_lean_deg = 8.0f;
      s.trunk_spread_deg = 35.0f;
      s.crown_shape = CrownShape::kSpherical;
      s.level1 = {.count = 6, .count_variation = 0.3f, .start = 0.25f, .end = 0.95f, .per_node = 1, .roll_deg = 137.5f,
                  .angle_deg = 40.0f, .angle_variation_deg = 12.0f, .length_ratio = 0.55f, .length_variation = 0.25f,
                  .length_profile = 0.5f, .gravitropism = 0.2f};
      s.level2 = {.count = 4, .count_variation = 0.3f, .start = 0.3f, .end = 0.95f, .per_node = 2, .roll_deg = 90.0f,
                  .angle_deg = 45.0f, .angle_variation_deg = 12.0f, .length_ratio = 0.5f, .length_variation = 0.25f,
                  .length_profile = 0.3f, .gravitropism = 0.1f};
      s.leaves = {.levels = 2, .per_metre = 16.0f, .max_per_branch = 24, .start = 0.1f, .width = 0.2f, .length = 0.24f,
                  .size_variation = 0.2f, .arrangement = LeafArrangement::kOpposite, .petiole_angle_deg = 55.0f,
                  .droop = 0.2f, .phototropism = 0.5f, .orientation_jitter = 0.35f, .terminal_leaf = true};
      s.leaf_shape = LeafShape::kElliptic;
      s.twig_radius = 0.0025f;
      s.da_vinci_exponent = 2.2f;
      break;
  }
  return s;
}

Result<TreeModel> generate_tree(const TreeSpecies& species, const GeneratorLimits& limits) {
  SYLVA_TRY(check_settings(species));
  Builder b{species, limits, {}};
  b.model.name = species.name;
  b.model.seed = species.seed;
  SYLVA_TRY(b.trunks());
  for (int level = 1; level < species.levels; ++level) SYLVA_TRY(b.children(level));
  b.radii();
  SYLVA_TRY(b.leaves());
  assign_bending_data(b.model, species.max_length_error);
  if (Status s = validate(b.model); !s.ok()) return s.error();
  return std::move(b.model);
}

}  // namespace sylva::vegetation
