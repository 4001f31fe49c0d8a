#include <sylva/core/file_transaction.hpp>

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/file_fault.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <system_error>

namespace sylva {

namespace fs = std::filesystem;

namespace {


// Same file for the purpose of staging twice: compare normalised absolute paths.
fs::path identity(const fs::path& p) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(p, ec);
  return (ec ? p : absolute).lexically_normal();
}

}  // namespace

FileTransaction::~FileTransaction() { discard(); }

void FileTransaction::discard() {
  std::error_code ec;
  for (const Staged& s : staged_) {
    if (!s.temp.empty()) fs::remove(s.temp, ec);
    if (!s.backup.empty()) fs::remove(s.backup, ec);
  }
  staged_.clear();
}

Status FileTransaction::stage(const fs::path& target, const Writer& write) {
  const fs::path id = identity(target);
  const bool already = std::any_of(staged_.begin(), staged_.end(), [&](const Staged& s) { return identity(s.target) == id; });
  if (already) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: written twice in one save", target.string()));
  }
  SYLVA_TRY(check_replaceable(target));
  const fs::path temp = temp_path_beside(target);
  std::error_code ec;
  Status written = write(temp, target);
  if (written.ok() && file_fault_hits(target, FileFaultPoint::kWrite)) {
    written = make_error(ErrorCode::kIo, fmt::format("{}: writing failed (No space left on device)", target.string()));
  }
  if (written.ok()) written = sync_file(temp, target);
  if (!written.ok()) {
    fs::remove(temp, ec);
    return make_error(written.error().code,
                      written.error().message + "; nothing was saved, every old file is untouched");
  }
  staged_.push_back({target, temp, {}});
  return ok_status();
}

Status FileTransaction::stage_bytes(const fs::path& target, std::string_view bytes) {
  return stage(target, [bytes](const fs::path& temp, const fs::path& shown) { return write_new_file(temp, bytes, shown); });
}

void FileTransaction::roll_back(std::size_t renamed) {
  std::error_code ec;
  for (std::size_t i = renamed; i-- > 0;) {
    const Staged& s = staged_[i];
    if (s.backup.empty()) {
      fs::remove(s.target, ec);
    } else {
      fs::rename(s.backup, s.target, ec);
    }
  }
  for (std::size_t i = 0; i < renamed; ++i) staged_[i].backup.clear();  // restored: nothing to remove
}

Status FileTransaction::commit() {
  std::error_code ec;
  // Keep every old file reachable under a second name before the first rename, so a failure
  // half way can put the whole old set back.
  for (Staged& s : staged_) {
    if (!fs::exists(s.target, ec)) continue;
    s.backup = temp_path_beside(s.target).replace_extension(".old");
    fs::create_hard_link(s.target, s.backup, ec);
    if (ec) {
      // Copied before discard(): it destroys the element `s` refers to.
      const std::string target = s.target.string(), why = ec.message();
      s.backup.clear();
      discard();
      return make_error(ErrorCode::kIo, fmt::format("{}: cannot keep the old file while saving ({}); nothing was saved",
                                                    target, why));
    }
  }
  for (std::size_t i = 0; i < staged_.size(); ++i) {
    Staged& s = staged_[i];
    if (file_fault_hits(s.target, FileFaultPoint::kRename)) {
      ec = std::make_error_code(std::errc::io_error);
    } else {
      fs::rename(s.temp, s.target, ec);
    }
    if (ec) {
      const std::string target = s.target.string(), why = ec.message();  // discard() destroys `s`
      roll_back(i);
      discard();
      return make_error(ErrorCode::kIo, fmt::format("{}: cannot replace the file ({}); nothing was saved, every old "
                                                    "file is as it was",
                                                    target, why));
    }
    s.temp.clear();
  }
  std::set<fs::path> folders;
  for (const Staged& s : staged_) folders.insert(containing_folder(s.target));
  discard();  // drops the old files' second names
  for (const fs::path& folder : folders) SYLVA_TRY(sync_folder(folder));
  return ok_status();
}

}  // namespace sylva
