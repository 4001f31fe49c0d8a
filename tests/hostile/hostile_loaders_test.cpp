// File kinds that no shipped executable reads yet (OBJT trees, .lsys grammars, OBJ meshes,
// voxel region files, terrain chunk files), made hostile and handed to their loaders in-process:
// each must fail with an error naming the file, never crash, hang or accept the junk. One row
// per (loader, bytes); the module's own tests and fuzz/ go deeper.

#include "hostile_bytes.hpp"

#include <sylva/terrain/chunk_file.hpp>
#include <sylva/terrain/mesh.hpp>
#include <sylva/vegetation/objt.hpp>
#include <sylva/voxel/lsystem.hpp>
#include <sylva/voxel/region.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <unistd.h>

namespace sylva::hostile {
namespace {

namespace fs = std::filesystem;

struct LoaderCase {
  std::string name;
  std::string file;                                  // written into a fresh folder
  std::function<std::string()> bytes{};
  std::function<Status(const fs::path&)> load{};      // the loader under test, as a Status
};

void PrintTo(const LoaderCase& c, std::ostream* os) { *os << c.name; }

template <class T>
Status status_of(const Result<T>& r) {
  if (!r.ok()) return r.error();
  return ok_status();
}
Status objt(const fs::path& p) { return status_of(vegetation::load_objt(p)); }
Status lsys(const fs::path& p) { return status_of(voxel::load_lsystems(p)); }
Status obj(const fs::path& p) { return status_of(terrain::load_obj(p)); }
Status region(const fs::path& p) { return status_of(voxel::read_region_file(p, voxel::BlockPalette::standard())); }
Status chunks(const fs::path& p) { return status_of(terrain::ChunkFile::open(p)); }

std::vector<LoaderCase> cases() {
  return {
      {"ObjtBinaryJunk", "tree.objt", [] { return junk(4000); }, objt},
      {"ObjtNestedBranches", "tree.objt", [] { return std::string(200'000, '['); }, objt},
      {"ObjtNaNVertices", "tree.objt", [] { return std::string("v nan nan nan\nv inf 0 0\n"); }, objt},
      {"LsysBinaryJunk", "g.lsys", [] { return junk(4000); }, lsys},
      {"LsysTruncatedHeader", "g.lsys", [] { return std::string("20 20"); }, lsys},
      {"LsysNaNAngle", "g.lsys", [] { return std::string("nan nan nan\nF\nF > FF\n"); }, lsys},
      {"ObjBinaryJunk", "m.obj", [] { return junk(4000); }, obj},
      {"ObjFaceIndexOutOfRange", "m.obj", [] { return std::string("v 0 0 0\nv 1 0 0\nf 1 2 99999999999\n"); }, obj},
      {"ObjNaNVertex", "m.obj", [] { return std::string("v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"); }, obj},
      {"RegionBinaryJunk", "r.0.0.0.svr", [] { return junk(4000); }, region},
      {"RegionMagicOnly", "r.0.0.0.svr", [] { return std::string("SYLVAVXR"); }, region},
      {"RegionEmpty", "r.0.0.0.svr", [] { return std::string(); }, region},
      {"ChunkFileBinaryJunk", "t.chunks", [] { return junk(4000); }, chunks},
      {"ChunkFileEmpty", "t.chunks", [] { return std::string(); }, chunks},
  };
}

class HostileLoader : public ::testing::TestWithParam<LoaderCase> {};

TEST_P(HostileLoader, RefusesWithTheFileName) {
  const LoaderCase& c = GetParam();
  const fs::path dir = fs::temp_directory_path() / ("sylva_hostile_loader_" + std::to_string(::getpid())) / c.name;
  fs::create_directories(dir);
  const fs::path file = dir / c.file;
  std::ofstream(file, std::ios::binary) << c.bytes();
  const Status s = c.load(file);
  ASSERT_FALSE(s.ok()) << c.file << " was accepted";
  EXPECT_NE(s.error().message.find(c.file), std::string::npos) << s.error().message;
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Files, HostileLoader, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<LoaderCase>& info) { return info.param.name; });

}  // namespace
}  // namespace sylva::hostile
