#include <sylva/core/atomic_file.hpp>

#include <sylva/core/file_fault.hpp>

#include <fmt/format.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace sylva {

namespace fs = std::filesystem;

namespace {


Error io_error(const fs::path& target, std::string_view what) {
  return make_error(ErrorCode::kIo, fmt::format("{}: {}", target.string(), what));
}

// Writes all of `bytes` to `fd`; a fault injected for `target` stops half way with ENOSPC.
bool write_all(int fd, std::string_view bytes, const fs::path& target) {
  if (file_fault_hits(target, FileFaultPoint::kWrite)) {
    [[maybe_unused]] const ssize_t half = ::write(fd, bytes.data(), bytes.size() / 2);
    errno = ENOSPC;
    return false;
  }
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

// fsync, rename, fsync of the folder; `temp` is removed on failure.
Status finish_temp(const fs::path& temp, const fs::path& target) {
  std::error_code ec;
  Status synced = sync_file(temp, target);
  if (!synced.ok()) {
    fs::remove(temp, ec);
    return synced;
  }
  if (file_fault_hits(target, FileFaultPoint::kRename)) {
    ec = std::make_error_code(std::errc::io_error);
  } else {
    fs::rename(temp, target, ec);
  }
  if (ec) {
    const std::string why = ec.message();
    fs::remove(temp, ec);
    return io_error(target, fmt::format("cannot replace the file ({}); the old file is untouched", why));
  }
  return sync_folder(containing_folder(target));
}

}  // namespace

fs::path containing_folder(const fs::path& file) { return file.has_parent_path() ? file.parent_path() : fs::path("."); }

fs::path temp_path_beside(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  return containing_folder(target) / fmt::format(".{}.{}-{}.tmp{}", target.stem().string(), ::getpid(), counter++,
                                         target.extension().string());
}

Status check_replaceable(const fs::path& target) {
  std::error_code ec;
  const fs::path folder = containing_folder(target);
  const fs::file_status folder_status = fs::status(folder, ec);
  if (!fs::exists(folder_status)) return io_error(target, fmt::format("the folder {} does not exist", folder.string()));
  if (!fs::is_directory(folder_status)) return io_error(target, fmt::format("{} is not a folder", folder.string()));
  const fs::file_status status = fs::status(target, ec);
  if (!fs::exists(status)) return ok_status();
  if (fs::is_directory(status)) return io_error(target, "is a folder, not a file");
  constexpr fs::perms kAnyWrite = fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write;
  if ((status.permissions() & kAnyWrite) == fs::perms::none) {
    return io_error(target, "the file is read-only and was not replaced; save under another name or make it writable");
  }
  return ok_status();
}

Status sync_file(const fs::path& file, const fs::path& display) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return io_error(display, fmt::format("cannot open the written file to flush it ({})", std::strerror(errno)));
  const bool synced = ::fsync(fd) == 0;
  const int err = errno;
  ::close(fd);
  if (!synced) return io_error(display, fmt::format("flushing to the disk failed ({})", std::strerror(err)));
  return ok_status();
}

Status sync_folder(const fs::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return io_error(folder, fmt::format("cannot open the folder to flush it ({})", std::strerror(errno)));
  const bool synced = ::fsync(fd) == 0 || errno == EINVAL;  // some file systems cannot sync folders
  const int err = errno;
  ::close(fd);
  if (!synced) return io_error(folder, fmt::format("flushing the folder to the disk failed ({})", std::strerror(err)));
  return ok_status();
}

Status replace_with_temp(const fs::path& temp, const fs::path& target) {
  std::error_code ec;
  Status replaceable = check_replaceable(target);
  if (!replaceable.ok()) {
    fs::remove(temp, ec);
    return replaceable;
  }
  if (file_fault_hits(target, FileFaultPoint::kWrite)) {
    fs::remove(temp, ec);
    return io_error(target, fmt::format("writing failed ({}); the old file is untouched", std::strerror(ENOSPC)));
  }
  return finish_temp(temp, target);
}

Status write_new_file(const fs::path& file, std::string_view bytes, const fs::path& display) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return io_error(display, fmt::format("cannot create a file in this folder ({})", std::strerror(errno)));
  const bool written = write_all(fd, bytes, display);
  const int write_errno = errno;
  const bool closed = ::close(fd) == 0;
  if (!written || !closed) {
    const int err = written ? errno : write_errno;
    std::error_code ec;
    fs::remove(file, ec);
    return io_error(display, fmt::format("writing failed ({}); the old file is untouched", std::strerror(err)));
  }
  return ok_status();
}

Status write_file_atomic(const fs::path& target, std::string_view bytes) {
  SYLVA_TRY(check_replaceable(target));
  const fs::path temp = temp_path_beside(target);
  SYLVA_TRY(write_new_file(temp, bytes, target));
  return finish_temp(temp, target);
}

Result<std::string> read_file(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return make_error(ErrorCode::kNotFound, fmt::format("{}: no such file", path.string()));
  if (fs::is_directory(path, ec)) {
    return make_error(ErrorCode::kIo, fmt::format("{}: is a folder, not a file", path.string()));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::kIo, fmt::format("{}: cannot open ({})", path.string(), std::strerror(errno)));
  std::stringstream text;
  text << in.rdbuf();
  if (in.bad()) return make_error(ErrorCode::kIo, fmt::format("{}: read failed", path.string()));
  return text.str();
}

}  // namespace sylva
