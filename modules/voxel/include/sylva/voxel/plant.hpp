#pragma once
// Turtle interpretation of derived L-system strings into plants made of blocks (seed 004 §4.5.2-
// §4.5.4, LSystemExecutor) and a per-seed cache of plant variants (§4.7).
//
// Turtle (seed §4.5.2): position, block size, output array, yaw and pitch in degrees, and the
// frame front = (cos yaw cos pitch, sin pitch, sin yaw cos pitch), right = normalize(front x Y),
// up = normalize(right x front), rebuilt and re-normalised after every turn. Pitch guard: when
// cos(pitch) is within 1e-4 of zero the pitch is nudged by -0.01 degrees, so front is never
// parallel to world up and right never degenerates.
//
// Alphabet (seed §4.5.3):
//   U u   move the turtle up by the block size, then lay a block there (case only matters for rules)
//   F f   move forward by the block size, then lay a block there
//         (moving first means branches that start at one point never lay the same block twice;
//          the seed leaves this order open. The plant origin is the centre of the ground block.)
//   x X S shrink (size *= shrink_ratio), enlarge (size /= shrink_ratio), reset to the start size
//   + -   yaw left / right by yaw_angle;   ^ &  pitch up / down by pitch_angle
//   [ ]   push / pop a copy of the whole turtle (size and output array included)
//   0..9  switch the output array (trunk, leaves, ... mapped to blocks by the species)
//   other symbols are only rewritten, never interpreted.
// Every turn is jittered by x * angle with x uniform in [-angle_variation, angle_variation]
// (default 0.2, seed §4.5.4). Block size stays within [1e-3, 1e3] x the start size.

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/voxel/lsystem.hpp>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace sylva::voxel {

inline constexpr int kPlantOutputs = 10;

// One block laid by the turtle: a cube of edge `size` centred at `position` (plant space, y up,
// in blocks), turned by `orientation` when parts follow the turtle frame (identity otherwise).
struct PlantPart {
  glm::vec3 position{0.0f};
  float size = 1.0f;
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
};

struct PlantModel {
  std::array<std::vector<PlantPart>, kPlantOutputs> outputs;  // by output array 0..9
  int derivations = 0;
  float start_size = 1.0f;
  glm::vec3 bounds_min{0.0f};  // axis-aligned bounds of all parts (cube corners included)
  glm::vec3 bounds_max{0.0f};
  std::size_t symbol_count = 0;  // length of the derived string

  std::size_t part_count() const;
};

struct LSystemExecutorSettings {
  // Derivation count range; the count is drawn per plant from the salt (seed §4.5.4). Growth
  // stages are this range: the shrubland bushes use 2..4 (seed §4.6.1).
  int min_derivations = 2;
  int max_derivations = 4;
  // Turn jitter as a fraction of the angle (seed default 0.2 = +-20 %).
  float angle_variation = 0.2f;
  // Start block size at min and max derivations; linear in between, so trunk thickness grows
  // linearly with the number of derivations (seed §4.6.1).
  float size_at_min = 0.6f;
  float size_at_max = 1.0f;
  // Parts follow the turtle frame (rotated off the grid) instead of staying axis-aligned as in
  // the seed (its model matrices had no rotation, §1.2).
  bool orient_parts = false;
  ExpansionLimits limits;

  template <class V>
  void visit(V& v) {
    v(min_derivations, "min_derivations", {.min = 0, .max = 32, .help = "Fewest derivation steps of a plant", .rebuild = Rebuild::kOffline});
    v(max_derivations, "max_derivations", {.min = 0, .max = 32, .help = "Most derivation steps of a plant", .rebuild = Rebuild::kOffline});
    v(angle_variation, "angle_variation",
      {.min = 0.0, .max = 1.0, .help = "Turn jitter as a fraction of the grammar's angle (seed default 0.2)", .rebuild = Rebuild::kOffline});
    v(size_at_min, "size_at_min", {.min = 0.01, .max = 16.0, .unit = "blocks", .help = "Start block size at the fewest derivations", .rebuild = Rebuild::kOffline});
    v(size_at_max, "size_at_max", {.min = 0.01, .max = 16.0, .unit = "blocks", .help = "Start block size at the most derivations", .rebuild = Rebuild::kOffline});
    v(orient_parts, "orient_parts", {.help = "Turn each block with the turtle frame instead of keeping it axis-aligned", .rebuild = Rebuild::kOffline});
  }
};

// Derivation count and start size for a salt (shared by generate_plant and the tests).
int derivations_for(const LSystemExecutorSettings& settings, std::uint64_t salt);
float start_size_for(const LSystemExecutorSettings& settings, int derivations);

// Interprets an already derived string (angles jittered by a stream seeded from `salt`).
// kLimit when the plant would exceed limits.max_parts or limits.max_depth.
Result<PlantModel> interpret(const LSystem& system, std::string_view derived, float start_size,
                             const LSystemExecutorSettings& settings, std::uint64_t salt);
// derive() + interpret(): the seed's LSystemExecutor. Deterministic for (system, settings, salt).
// kInvalidArgument for min_derivations > max_derivations.
Result<PlantModel> generate_plant(const LSystem& system, const LSystemExecutorSettings& settings, std::uint64_t salt);

// Pre-generated variants of one species, drawn by position (seed §4.7: "a buffer of bushes is
// generated from the seed before terrain generation; a position-dependent random index picks
// one"). Thread-safe after construction.
class PlantVariants {
 public:
  // `count` variants with salts derived from (world_seed, species_salt, index).
  static Result<PlantVariants> build(const LSystem& system, const LSystemExecutorSettings& settings,
                                     std::uint64_t world_seed, std::uint32_t species_salt, int count);
  std::size_t size() const { return models_.size(); }
  const PlantModel& at(std::size_t i) const { return *models_[i]; }
  // Variant index for a world block position (stable for a seed).
  std::size_t index_for(std::int64_t x, std::int64_t z) const;
  const PlantModel& for_position(std::int64_t x, std::int64_t z) const { return at(index_for(x, z)); }

 private:
  std::vector<std::shared_ptr<const PlantModel>> models_;
  std::uint32_t seed_ = 0;
};

}  // namespace sylva::voxel
