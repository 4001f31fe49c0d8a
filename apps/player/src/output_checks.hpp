#pragma once
// Where the player will write (--screenshot, --stats), checked before any work: an output that
// cannot be written fails the run with exit code 1 before the scene is loaded, not after every
// frame was rendered; and an output that is one of the run's inputs (the scene file, its maps)
// is refused instead of replacing the user's file.

#include "player_options.hpp"

#include <sylva/core/result.hpp>
#include <sylva/scene/scene_document.hpp>

namespace sylva::player {

// The folder, the file and (for --screenshot) the image format of each output.
Status check_outputs(const PlayerOptions& options);

// No output is the scene file or a map file the document names.
Status check_outputs_are_not_inputs(const PlayerOptions& options, const scene::SceneDocument& document);

}  // namespace sylva::player
