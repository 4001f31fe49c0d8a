#include <sylva/voxel/plant.hpp>

#include <sylva/core/rng.hpp>

#include <fmt/format.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva::voxel {

std::size_t PlantModel::part_count() const {
  std::size_t n = 0;
  for (const auto& o : outputs) n += o.size();
  return n;
}

namespace {

constexpr glm::vec3 kWorldUp{0.0f, 1.0f, 0.0f};

// The seed's 3D turtle (§4.5.2).
struct Turtle {
  glm::vec3 position{0.0f};
  float size = 1.0f;
  int output = 0;
  float yaw = 0.0f;    // degrees
  float pitch = 0.0f;  // degrees
  glm::vec3 front{1.0f, 0.0f, 0.0f};
  glm::vec3 right{0.0f, 0.0f, 1.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};

  void update_frame() {
    // Pitch guard: multiples of 90 degrees are excluded so front never aligns with world up.
    while (std::abs(std::cos(glm::radians(pitch))) < 1e-4f) pitch -= 0.01f;
    // Keep the angles bounded so long turn sequences do not lose float precision.
    yaw = std::remainder(yaw, 360.0f);
    pitch = std::remainder(pitch, 360.0f);
    glm::vec3 f;
    f.x = std::cos(glm::radians(yaw)) * std::cos(glm::radians(pitch));
    f.y = std::sin(glm::radians(pitch));
    f.z = std::sin(glm::radians(yaw)) * std::cos(glm::radians(pitch));
    front = glm::normalize(f);
    right = glm::normalize(glm::cross(front, kWorldUp));
    up = glm::normalize(glm::cross(right, front));
  }

  glm::quat orientation() const {
    // Local x = front, y = up, z = right (right-handed: front x up = right).
    return glm::quat_cast(glm::mat3(front, up, right));
  }
};

}  // namespace

int derivations_for(const LSystemExecutorSettings& settings, std::uint64_t salt) {
  if (settings.max_derivations <= settings.min_derivations) return settings.min_derivations;
  Pcg32 rng(salt, 0x4445u);  // stream "DE": derivation count
  return rng.uniform_int(settings.min_derivations, settings.max_derivations);
}

float start_size_for(const LSystemExecutorSettings& settings, int derivations) {
  const int span = settings.max_derivations - settings.min_derivations;
  if (span <= 0) return settings.size_at_max;
  const float t = static_cast<float>(derivations - settings.min_derivations) / static_cast<float>(span);
  return settings.size_at_min + (settings.size_at_max - settings.size_at_min) * std::clamp(t, 0.0f, 1.0f);
}

Result<PlantModel> interpret(const LSystem& system, std::string_view derived, float start_size,
                             const LSystemExecutorSettings& settings, std::uint64_t salt) {
  if (!(start_size > 0.0f) || !std::isfinite(start_size)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: start block size {} must be positive and finite", system.where(), start_size));
  }
  if (!(settings.angle_variation >= 0.0f && settings.angle_variation <= 1.0f)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("voxel.lsystem.angle_variation: {} outside [0, 1]",
                                                               settings.angle_variation));
  }
  Pcg32 rng(salt, 0x414eu);  // stream "AN": angle jitter
  auto jitter = [&](float angle) {
    if (settings.angle_variation <= 0.0f) return angle;
    return angle + rng.uniform(-settings.angle_variation, settings.angle_variation) * angle;
  };
  const float min_size = start_size * 1e-3f;
  const float max_size = start_size * 1e3f;

  PlantModel model;
  model.start_size = start_size;
  model.symbol_count = derived.size();
  Turtle t;
  t.size = start_size;
  t.update_frame();
  std::vector<Turtle> stack;
  std::size_t parts = 0;
  glm::vec3 lo(std::numeric_limits<float>::max());
  glm::vec3 hi(std::numeric_limits<float>::lowest());

  auto lay = [&](const glm::vec3& direction) -> Status {
    if (++parts > settings.limits.max_parts) {
      return make_error(ErrorCode::kLimit,
                        fmt::format("{}: plant exceeds max_parts={} blocks ({} derivations, {} symbols)",
                                    system.where(), settings.limits.max_parts, model.derivations, derived.size()));
    }
    t.position += direction * t.size;
    PlantPart part;
    part.position = t.position;
    part.size = t.size;
    if (settings.orient_parts) part.orientation = t.orientation();
    model.outputs[static_cast<std::size_t>(t.output)].push_back(part);
    // Bounds of the cube (the rotated cube fits in the sphere of radius size * sqrt(3) / 2).
    const float r = settings.orient_parts ? t.size * 0.8660254f : t.size * 0.5f;
    lo = glm::min(lo, t.position - glm::vec3(r));
    hi = glm::max(hi, t.position + glm::vec3(r));
    return ok_status();
  };

  for (char c : derived) {
    switch (c) {
      case 'U':
      case 'u': SYLVA_TRY(lay(t.up)); break;
      case 'F':
      case 'f': SYLVA_TRY(lay(t.front)); break;
      case 'x': t.size = std::max(min_size, t.size * system.shrink_ratio); break;
      case 'X': t.size = std::min(max_size, t.size / system.shrink_ratio); break;
      case 'S': t.size = start_size; break;
      case '+': t.yaw += jitter(system.yaw_angle); t.update_frame(); break;
      case '-': t.yaw -= jitter(system.yaw_angle); t.update_frame(); break;
      case '^': t.pitch += jitter(system.pitch_angle); t.update_frame(); break;
      case '&': t.pitch -= jitter(system.pitch_angle); t.update_frame(); break;
      case '[':
        if (stack.size() >= settings.limits.max_depth) {
          return make_error(ErrorCode::kLimit, fmt::format("{}: branch nesting exceeds max_depth={}", system.where(),
                                                           settings.limits.max_depth));
        }
        stack.push_back(t);
        break;
      case ']':
        if (stack.empty()) {
          return make_error(ErrorCode::kParse, fmt::format("{}: ']' without '[' in the derived string", system.where()));
        }
        t = stack.back();
        stack.pop_back();
        break;
      default:
        if (c >= '0' && c <= '9') t.output = c - '0';
        break;
    }
  }
  if (parts == 0) {
    lo = hi = glm::vec3(0.0f);
  }
  model.bounds_min = lo;
  model.bounds_max = hi;
  return model;
}

Result<PlantModel> generate_plant(const LSystem& system, const LSystemExecutorSettings& settings, std::uint64_t salt) {
  if (settings.min_derivations < 0 || settings.min_derivations > settings.max_derivations) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("voxel.lsystem: min_derivations {} must be in [0, max_derivations {}]",
                                  settings.min_derivations, settings.max_derivations));
  }
  const int n = derivations_for(settings, salt);
  auto derived = derive(system, n, salt, settings.limits);
  if (!derived.ok()) return derived.error();
  auto model = interpret(system, *derived, start_size_for(settings, n), settings, salt);
  if (!model.ok()) return model.error();
  model->derivations = n;
  return model;
}

Result<PlantVariants> PlantVariants::build(const LSystem& system, const LSystemExecutorSettings& settings,
                                           std::uint64_t world_seed, std::uint32_t species_salt, int count) {
  if (count < 1) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: variant count {} < 1", system.where(), count));
  }
  PlantVariants v;
  v.seed_ = hash_u32(static_cast<std::uint32_t>(world_seed), static_cast<std::uint32_t>(world_seed >> 32), species_salt);
  for (int i = 0; i < count; ++i) {
    const std::uint64_t salt = (static_cast<std::uint64_t>(v.seed_) << 32) | hash_u32(static_cast<std::uint32_t>(i), v.seed_);
    auto model = generate_plant(system, settings, salt);
    if (!model.ok()) return model.error();
    v.models_.push_back(std::make_shared<const PlantModel>(std::move(*model)));
  }
  return v;
}

std::size_t PlantVariants::index_for(std::int64_t x, std::int64_t z) const {
  const auto ux = static_cast<std::uint64_t>(x);
  const auto uz = static_cast<std::uint64_t>(z);
  const std::uint32_t h = hash_u32(static_cast<std::uint32_t>(ux), static_cast<std::uint32_t>(ux >> 32),
                                   static_cast<std::uint32_t>(uz), static_cast<std::uint32_t>(uz >> 32) ^ seed_);
  return h % models_.size();
}

}  // namespace sylva::voxel
