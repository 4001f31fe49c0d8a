// The scene's ground from a baked chunk file (baked_ground.hpp).
#include "baked_ground.hpp"

#include <sylva/core/log.hpp>

#if SYLVA_HAS_TERRAIN
#include <sylva/terrain/chunk_file.hpp>
#endif

#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <string>

namespace sylva::scene {

bool is_chunk_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char magic[8] = {};
  return static_cast<bool>(in.read(magic, 8)) && std::memcmp(magic, "SYLVACHK", 8) == 0;
}

Result<MapGrid> read_baked_ground(const std::filesystem::path& file, std::uint64_t max_samples) {
#if SYLVA_HAS_TERRAIN
  auto chunks = terrain::ChunkFile::open(file);
  if (!chunks) return chunks.error();
  const int stride = (*chunks)->height_stride(max_samples);
  auto field = (*chunks)->read_heights(stride);
  if (!field) return field.error();
  MapGrid grid;
  grid.width = field->columns();
  grid.height = field->rows();
  grid.values = std::move(field->samples());
  grid.texel_size = {field->spacing(), field->spacing()};
  grid.texel_origin = field->origin();
  log_info("{}: the ground is the baked field's heights, {}x{} samples {:.3f} m apart{}", file.string(), grid.width,
           grid.height, grid.texel_size.x,
           stride > 1 ? fmt::format(" (every {}th sample: the field has more than {} samples)", stride, max_samples)
                      : std::string());
  return grid;
#else
  (void)max_samples;
  return make_error(ErrorCode::kUnsupported,
                    fmt::format("{}: a baked chunk file needs the terrain module, which this program was built without",
                                file.string()));
#endif
}

}  // namespace sylva::scene
