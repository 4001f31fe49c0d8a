#pragma once
// `sylva-bench --suite species` (issue #16, "Benchmarks"): what a user's own plant files cost.
//
//   load   per tree species file: the scene built (species file, OBJT or preset, images, textures,
//          the LOD1/LOD2 slice bake) with an empty slice cache ("cold") and again with the cache
//          the cold build filled ("cached"), beside the same scene without trees ("ground"), so
//          cold - ground is the species' load + bake. Milliseconds of wall time.
//   grammar per species of a voxel species table read from disk (default: the shipped
//          modules/voxel/data/species.json and its .lsys files, read as a user's): plants
//          generated (derive + turtle, the species' derivation range and sizes) per second.
//   forest a mixed three-species forest (default: scenes/species/painted_birch.json,
//          slender_conifer.json, sapling.json) against each of its species alone at the same
//          instance count, same camera, rendered in interleaved rounds: mean ms per frame
//          (wall time of render + glFinish, the run's cost on llvmpipe as on a GPU).
//
// The user's files: `--set vegetation.species_files.0.file=oak.json` (.1, .2) replace the
// forest's species (and the load rows), `--set voxel.flora.species_file=plants.json` the grammar
// table; any other `--set` (e.g. render.shadows.enabled=false) goes to every scene the suite
// builds, checked before anything runs. Rows go to the output (one line each, "key=value"
// fields) and to results.csv in --out (written atomically). Counts are exact; times are wall
// clock (a noisy machine: compare the rows of one run, not runs).

#include "sweep.hpp"

#include <glm/glm.hpp>

#include <filesystem>
#include <iosfwd>
#include <vector>

namespace sylva::bench {

struct SpeciesSuiteOptions {
  glm::ivec2 size{256, 144};          // frame size [px]
  int frames = 24;                    // measured frames per forest and round
  int rounds = 3;                     // interleaved rounds (mixed, one, one, one, mixed, ...)
  int warmup = 2;                     // unmeasured frames per forest before the rounds (--warmup)
  int plants = 1000;                  // plants generated (and timed) per grammar species
  std::vector<Assignment> overrides;  // --set: the user's files (see above)
  std::filesystem::path out;          // results.csv
};

// Runs the three parts (needs a current GL 4.5 context); returns the bench exit code (0 ok,
// 1 a part failed, 2 a --set the scenes lack, 3 the vegetation module is not in this build).
int run_species_suite(const SpeciesSuiteOptions& options, std::ostream& out, std::ostream& err);

}  // namespace sylva::bench
