// sylva-fuzz-seeds OUT_DIR: writes valid examples of the binary inputs (region file, chunk file,
// slice cache, image maps) and one assignment per scene parameter, as OUT_DIR/<target>/<file>,
// so the fuzzers start from inputs that pass every check instead of rediscovering the formats.
// Generated rather than committed: they follow the formats when those change.
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/log.hpp>
#include <sylva/scene/scene_document.hpp>
#include <sylva/terrain/chunk_file.hpp>
#include <sylva/vegetation/slice_bake.hpp>
#include <sylva/voxel/region.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace sylva;

namespace {

bool fail(const std::string& what) {
  std::fprintf(stderr, "sylva-fuzz-seeds: %s\n", what.c_str());
  return false;
}

bool write_bytes(const fs::path& file, std::string_view bytes) {
  fs::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return out ? true : fail("cannot write " + file.string());
}

bool region_seed(const fs::path& out) {
  using namespace sylva::voxel;
  const BlockPalette& palette = BlockPalette::standard();
  const RegionCoord r{-1, 0, 2};
  Chunk solid(palette.id("stone"));
  Chunk mixed;
  for (int i = 0; i < kChunkSize; ++i) mixed.set(i, i, (i * 7) % kChunkSize, palette.id("dirt"));
  const std::pair<ChunkCoord, const Chunk*> chunks[] = {{{-8, 0, 16}, &solid}, {{-5, 3, 17}, &mixed}};
  const std::vector<std::uint8_t> bytes = encode_region(r, palette, chunks);
  return write_bytes(out / "region" / "two_chunks.svr", {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
}

bool chunk_file_seed(const fs::path& out) {
  using namespace sylva::terrain;
  HeightField field(17, 17, 4.0);
  for (int j = 0; j < 17; ++j)
    for (int i = 0; i < 17; ++i) field.sample(i, j) = 3.0f * std::sin(0.7f * i) + 0.25f * static_cast<float>(j);
  field.update_range();
  ChunkTreeSettings settings;
  settings.leaf_dimension = 9;
  auto tree = ChunkTree::build(field, settings);
  if (!tree.ok()) return fail("chunk tree: " + tree.error().message);
  const fs::path file = out / "chunk_file" / "small.chunks";
  fs::create_directories(file.parent_path());
  const Status saved = save_chunk_file(file, *tree);
  return saved.ok() ? true : fail(saved.error().message);
}

bool slice_cache_seed(const fs::path& out) {
  using namespace sylva::vegetation;
  BakedTree tree;
  for (BakedLod& lod : tree.lod) {
    lod.layout.directions = 1;
    lod.layout.layers = 1;
    SliceImages& im = lod.images;
    im.resolution = 16;
    im.count = 1;
    im.color.assign(im.texels() * 4, 200);
    im.normal.assign(im.texels() * 4, 128);
    im.depth.assign(im.texels(), 0.5f);
    im.branch.assign(im.texels() * 4, 0.25f);
  }
  return write_bytes(out / "slice_cache" / "one_slice.bin", serialize_slices(tree, 0x5eed));
}

// image_map inputs are one byte choosing the extension (image_map_fuzz.cpp), then the file.
bool image_seed(const fs::path& out, const std::string& name, std::uint8_t selector, PixelFormat format) {
  Image image(5, 4, 1, format);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x) image.at(x, y) = 0.1f * static_cast<float>(x + y);
  const char* extensions[] = {".png", ".exr", ".tif", ".pgm"};
  const fs::path temp = out / ("tmp" + std::string(extensions[selector & 3u]));
  const Status written = write_image(temp, image);
  if (!written.ok()) return fail(written.error().message);
  auto bytes = read_file(temp);
  fs::remove(temp);
  if (!bytes.ok()) return fail(bytes.error().message);
  return write_bytes(out / "image_map" / name, std::string(1, static_cast<char>(selector)) + *bytes);
}

bool params_seeds(const fs::path& out) {
  std::vector<std::string> warnings;
  auto document = scene::default_scene(warnings);
  if (!document.ok()) return fail(document.error().message);
  const ParamRegistry params = document->params();
  int n = 0;
  for (const ParamDescriptor& p : params.describe()) {
    auto value = params.get(p.path);
    if (!value.ok()) return fail(value.error().message);
    if (!write_bytes(out / "params_set" / ("p" + std::to_string(n++)), p.path + "=" + *value + "\n")) return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: sylva-fuzz-seeds OUT_DIR\n");
    return 2;
  }
  set_log_level(LogLevel::kError);
  const fs::path out = argv[1];
  fs::create_directories(out);
  const bool ok = region_seed(out) && chunk_file_seed(out) && slice_cache_seed(out) &&
                  image_seed(out, "u16.png", 0, PixelFormat::kU16) && image_seed(out, "f32.exr", 1, PixelFormat::kF32) &&
                  image_seed(out, "f32_repair.tif", 6, PixelFormat::kF32) && image_seed(out, "u8.pgm", 3, PixelFormat::kU8) &&
                  params_seeds(out);
  return ok ? 0 : 1;
}
