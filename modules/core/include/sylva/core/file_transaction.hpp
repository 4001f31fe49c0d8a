#pragma once
// A save made of several files that succeeds or fails as a whole (a scene and its maps).
//
//   FileTransaction save;
//   SYLVA_TRY(save.stage("maps/height.exr", [&](const fs::path& temp) { return write_to(temp); }));
//   SYLVA_TRY(save.stage_bytes("scene.json", text));   // staged last: renamed last
//   SYLVA_TRY(save.commit());
//
// stage() writes each file to a temporary file beside its target and fsyncs it; nothing the user
// has is touched yet, so a folder that cannot be written, a full disk or a read-only target fails
// here with every old file as it was. commit() then keeps a hard link to each old file, renames
// the temporary files into place in staging order (stage the file that refers to the others
// last), fsyncs the folders and drops the old links. If a rename fails half way, the files
// already renamed are put back from their links (or removed when they are new), so the old set
// is restored whole. A transaction that is destroyed without commit() removes its temporaries.
//
// Failure messages name the user's target path, never a temporary name. Not thread-safe; one
// transaction per save.

#include <sylva/core/result.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace sylva {

class FileTransaction {
 public:
  // Fills the temporary file at the given path (it keeps the target's extension). Errors from
  // the writer should name the target (the writer is given it as its second argument).
  using Writer = std::function<Status(const std::filesystem::path& temp, const std::filesystem::path& target)>;

  FileTransaction() = default;
  ~FileTransaction();
  FileTransaction(const FileTransaction&) = delete;
  FileTransaction& operator=(const FileTransaction&) = delete;

  // Writes and fsyncs the new content of `target`. The target's folder must exist. kIo names
  // the target when it is read-only or a folder, when its folder is missing or unwritable, or
  // when writing fails; kInvalidArgument when the target is already staged.
  Status stage(const std::filesystem::path& target, const Writer& write);
  Status stage_bytes(const std::filesystem::path& target, std::string_view bytes);

  // Renames every staged file into place (see above). On failure every target is as it was
  // before and the error names the file that failed. After commit(), success or not, the
  // transaction is empty.
  Status commit();

  std::size_t staged_count() const { return staged_.size(); }

 private:
  struct Staged {
    std::filesystem::path target;
    std::filesystem::path temp;
    std::filesystem::path backup;  // hard link to the old target during commit(); empty if none
  };
  void discard();
  void roll_back(std::size_t renamed);

  std::vector<Staged> staged_;
};

}  // namespace sylva
