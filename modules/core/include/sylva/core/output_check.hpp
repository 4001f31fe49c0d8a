#pragma once
// Checking where a run will write before it does any work. A screenshot, statistics file or
// report folder that cannot be written used to be reported only after every frame was rendered
// (issue 17); the player, editor and bench call these first and exit before loading anything.
// Every error is kIo (kUnsupported for an unknown image format) and names the path as the user
// gave it, never a temporary file.

#include <sylva/core/result.hpp>

#include <filesystem>
#include <span>

namespace sylva {

// The file can be created or replaced: check_replaceable() (missing folder, not a folder, a
// folder given as the file, a read-only file), and the folder accepts a new file. That last
// check creates and removes an empty file, because permission bits say nothing to root or on a
// read-only mount.
Status check_output_file(const std::filesystem::path& path);

// check_output_file(), then that an image writer exists for the extension.
Status check_output_image(const std::filesystem::path& path);

// A folder that the run creates if missing: its nearest existing ancestor is a folder that
// accepts a new entry, or the folder exists and accepts a new file.
Status check_output_folder(const std::filesystem::path& folder);

// An output must not be one of the run's inputs (the scene being played, its maps): writing it
// would replace the user's file. kIo naming the output and what it is.
Status check_not_an_input(const std::filesystem::path& output, std::span<const std::filesystem::path> inputs);

}  // namespace sylva
