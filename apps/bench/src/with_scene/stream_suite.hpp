#pragma once
// `sylva-bench --suite stream` (issue #15, "Benchmarks"): flight frame times of a terrain
// streamed from its baked chunk file against the same terrain built in memory. Same field (the
// terrain suite's fBm, at 4097^2 unless --set terrain.resolution says otherwise), same tree
// settings, same `flight` camera path, same frame size, both in this one run:
//
//   bake      the field generated from the scene's height keys and baked (terrain::bake_chunk_file,
//             what `sylva-bake terrain` runs) into a temporary chunk file, deleted at the end
//   memory    the scene with the field built in memory (ChunkTree::build)
//   streamed  the same scene naming the baked file (terrain.baked_file) within
//             terrain.stream.budget_mb (default 64 MiB, far below a 4097^2 file's 1.1 GB)
//
// Each scene is built (wall time of factory + prepare), renders --warmup frames at the path's
// first pose, then --frames frames along the path (default 120) at 1/30 s per frame; a frame's
// time is the wall time of render + glFinish. Rows: p50, p99 and longest frame; for the streamed
// scene also the largest resident bytes of any frame (never above the budget), the chunks
// requested, loaded, evicted, and the misses (a parent drawn for non-resident children, summed
// over frames). The loader thread runs beside the frames, so the streaming counts differ run to
// run; times are wall clock (compare the rows of one run, not runs).
//
// Output: one "stream: ..." line per scene ("key=value" fields) and results.csv in --out
// (kind,name,count,value,unit; written atomically).

#include "sweep.hpp"

#include <glm/glm.hpp>

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace sylva::bench {

struct StreamSuiteOptions {
  glm::ivec2 size{256, 144};          // frame size [px]
  int frames = 120;                   // measured frames along the flight path, per scene
  int warmup = 2;                     // unmeasured frames at the first pose, per scene
  std::vector<Assignment> overrides;  // --set, applied to both scenes and to the baked field
  std::filesystem::path out;          // results.csv
};

// Runs the bake and both scenes (needs a current GL 4.5 context). Returns the bench exit code: 0
// ok, 1 a bake or scene failed, 2 a --set the scene lacks, 3 the terrain module is not in the
// scene registry.
int run_stream_suite(const StreamSuiteOptions& options, std::ostream& out, std::ostream& err);

// The terrain suite's scene text (with_scene/scene_suites.cpp): its field and `flight` path.
std::string terrain_suite_scene();

}  // namespace sylva::bench
