#pragma once
// `sylva-bake tree`: exports a species through modules/vegetation's tree exporter (tree_export.hpp)
// into the --out folder, with a summary line on `out` (files, vertices, triangles, bounds, time).

#include "bake_options.hpp"

#include <ostream>

namespace sylva::bake {

// Exit status: 0 done, 1 error (the message names the species file, the folder or the file that
// could not be written; nothing of a failed export replaces an earlier one).
int run_tree_export(const BakeCommand& command, std::ostream& out, std::ostream& err);

}  // namespace sylva::bake
