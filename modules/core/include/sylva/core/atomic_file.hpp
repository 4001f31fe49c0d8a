#pragma once
// Writing a user's file without ever leaving it half-written (DESIGN.md §2 "Errors"): write a
// temporary file in the same folder (same file system, so the rename is atomic), then rename it
// over the target. On any failure the temporary file is removed and the old file is untouched.

#include <sylva/core/result.hpp>

#include <filesystem>
#include <string_view>

namespace sylva {

// A unique temporary path beside `target` that keeps its extension (so format writers that
// pick a plugin by extension still work): "<folder>/.<stem>.<pid>-<n>.tmp<ext>".
std::filesystem::path temp_path_beside(const std::filesystem::path& target);

// Renames `temp` over `target`; on failure removes `temp` and returns kIo naming `target`.
Status replace_with_temp(const std::filesystem::path& temp, const std::filesystem::path& target);

// Writes `bytes` to `target` atomically. Errors (kIo) name the file and the reason.
Status write_file_atomic(const std::filesystem::path& target, std::string_view bytes);

// Reads a whole file. Errors: kNotFound (missing), kIo (unreadable or a folder).
Result<std::string> read_file(const std::filesystem::path& path);

}  // namespace sylva
