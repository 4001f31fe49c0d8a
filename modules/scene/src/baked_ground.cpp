// The scene's ground from a baked chunk file (baked_ground.hpp).
#include "baked_ground.hpp"

#include <sylva/core/log.hpp>

#if SYLVA_HAS_TERRAIN
#include <sylva/terrain/chunk_file.hpp>
#endif

#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace sylva::scene {

namespace {
std::uint64_t g_ground_limit = 0;  // 0: none set by ScopedBakedGroundLimit
constexpr const char* kGroundLimitVariable = "SYLVA_BAKED_GROUND_MAX_SAMPLES";
}  // namespace

std::uint64_t baked_ground_limit() {
  if (g_ground_limit != 0) return g_ground_limit;
  const char* text = std::getenv(kGroundLimitVariable);
  if (text == nullptr || *text == '\0') return kMaxBakedGroundSamples;
  char* end = nullptr;
  const unsigned long long n = std::strtoull(text, &end, 10);
  if (*end != '\0' || n < 4) {
    log_warn("{}={}: not a sample count of at least 4; the ground limit stays {}", kGroundLimitVariable, text,
             kMaxBakedGroundSamples);
    return kMaxBakedGroundSamples;
  }
  return n;
}

ScopedBakedGroundLimit::ScopedBakedGroundLimit(std::uint64_t max_samples) : previous_(g_ground_limit) {
  g_ground_limit = max_samples;
}

ScopedBakedGroundLimit::~ScopedBakedGroundLimit() { g_ground_limit = previous_; }

bool is_chunk_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char magic[8] = {};
  return static_cast<bool>(in.read(magic, 8)) && std::memcmp(magic, "SYLVACHK", 8) == 0;
}

Result<MapGrid> read_baked_ground(const std::filesystem::path& file, std::uint64_t max_samples,
                                  BakedGroundRead* read) {
#if SYLVA_HAS_TERRAIN
  auto chunks = terrain::ChunkFile::open(file);
  if (!chunks) return chunks.error();
  const int stride = (*chunks)->height_stride(max_samples);
  const std::uint32_t overview = (*chunks)->height_overview();
  const bool from_overview = overview != 0 && stride % static_cast<int>(overview) == 0;
  if (stride > 1 && overview == 0) {
    // Only a version-2 file lacks the overview because of its version; a current bake leaves it
    // out when the field fits the ground limit it was baked under (a lowered limit reads it here).
    log_info("{}: reading every {}th ground sample from all of the field's height tiles (chunk file version {}, "
             "no overview of its ground){}",
             file.string(), stride, (*chunks)->version(),
             (*chunks)->version() < terrain::kChunkFileVersion
                 ? ": re-baking it with `sylva-bake terrain` makes opening it faster"
                 : std::string(" (baked for a ground limit it fits)"));
  }
  auto field = (*chunks)->read_heights(stride);
  if (!field) return field.error();
  if (read != nullptr) *read = BakedGroundRead{(*chunks)->height_bytes_read(), from_overview};
  MapGrid grid;
  grid.width = field->columns();
  grid.height = field->rows();
  grid.values = std::move(field->samples());
  grid.texel_size = {field->spacing(), field->spacing()};
  grid.texel_origin = field->origin();
  log_info("{}: the ground is the baked field's heights, {}x{} samples {:.3f} m apart{}", file.string(), grid.width,
           grid.height, grid.texel_size.x,
           stride > 1 ? fmt::format(" (every {}th sample{}: the field has more than {} samples)", stride,
                                    from_overview ? ", from its overview" : "", max_samples)
                      : std::string());
  return grid;
#else
  (void)max_samples;
  (void)read;
  return make_error(ErrorCode::kUnsupported,
                    fmt::format("{}: a baked chunk file needs the terrain module, which this program was built without",
                                file.string()));
#endif
}

}  // namespace sylva::scene
