#pragma once
// Runs a parsed sylva-bake command: reads the raster, bakes (or merges) with progress lines
// (percent, elapsed, ETA) on `err`, and a summary (chunks, triangles, bytes, time, peak RSS);
// `tree` exports a species (bake_tree.hpp).

#include "bake_options.hpp"

#include <atomic>
#include <ostream>

namespace sylva::bake {

// Exit status: 0 done, 1 error (the message names the file, and the chunk or share), 130
// cancelled (`cancel` raised, e.g. by SIGINT/SIGTERM; no output file is left).
int run_bake(const BakeCommand& command, const std::atomic<bool>& cancel, std::ostream& out, std::ostream& err);

}  // namespace sylva::bake
