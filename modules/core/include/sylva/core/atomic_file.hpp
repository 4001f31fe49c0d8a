#pragma once
// Writing a user's file without ever leaving it half-written or lost (DESIGN.md §2 "Errors"):
// write a temporary file in the same folder (same file system, so the rename is atomic), flush
// it to the disk (fsync), rename it over the target, then fsync the folder so the rename itself
// survives a power cut. On any failure the temporary file is removed and the old file is
// untouched. A target whose permission bits say read-only is refused, never replaced (a rename
// would silently drop the user's protection, and root ignores the bits otherwise).
//
// Several files that must change together (a scene and its maps) go through FileTransaction
// (file_transaction.hpp), built on the same pieces.

#include <sylva/core/result.hpp>

#include <filesystem>
#include <string_view>

namespace sylva {

// The folder holding `file`: its parent path, or "." for a bare file name.
std::filesystem::path containing_folder(const std::filesystem::path& file);

// A unique temporary path beside `target` that keeps its extension (so format writers that
// pick a plugin by extension still work): "<folder>/.<stem>.<pid>-<n>.tmp<ext>".
std::filesystem::path temp_path_beside(const std::filesystem::path& target);

// Whether `target` may be replaced: kIo naming it when it is a folder, when it exists with no
// write permission bit (read-only), or when its folder is missing or is not a folder. A missing
// target in an existing folder is fine.
Status check_replaceable(const std::filesystem::path& target);

// Flushes a written file's data to the disk (fsync). kIo naming `display` on failure.
Status sync_file(const std::filesystem::path& file, const std::filesystem::path& display);
// Flushes a folder's entries (new names from renames) to the disk. kIo naming the folder.
Status sync_folder(const std::filesystem::path& folder);

// Makes `temp` (fully written) the new `target`: checks the target is replaceable, fsyncs the
// temporary file, renames it, fsyncs the folder. On failure removes `temp` and returns kIo naming
// `target`; the old file is untouched.
Status replace_with_temp(const std::filesystem::path& temp, const std::filesystem::path& target);

// Writes `bytes` to a new (temporary) file `file`, not atomically: for writers of a temporary
// that is renamed later. Errors name `display` (the user's target); a failed write removes `file`.
Status write_new_file(const std::filesystem::path& file, std::string_view bytes, const std::filesystem::path& display);

// Writes `bytes` to `target` atomically and durably. Errors (kIo) name the file and the reason.
Status write_file_atomic(const std::filesystem::path& target, std::string_view bytes);

// Reads a whole file. Errors: kNotFound (missing), kIo (unreadable or a folder).
Result<std::string> read_file(const std::filesystem::path& path);

}  // namespace sylva
