#pragma once
// sylva-player's run loop, separate from main() so tests can drive it in-process.

#include "player_options.hpp"

#include <ostream>

namespace sylva::player {

// Runs the player with parsed options. Returns the process exit code: 0 on success, 1 when a
// run-time step failed (context, shaders, writing outputs), 2 for bad input (scene file,
// --set). Messages go to `out` (normal output) and `err` (errors), each naming the file,
// parameter or step.
int run_player(const PlayerOptions& options, std::ostream& out, std::ostream& err);

}  // namespace sylva::player
