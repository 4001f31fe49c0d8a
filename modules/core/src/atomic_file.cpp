#include <sylva/core/atomic_file.hpp>

#include <fmt/format.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace sylva {

namespace fs = std::filesystem;

fs::path temp_path_beside(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  return folder / fmt::format(".{}.{}-{}.tmp{}", target.stem().string(), ::getpid(), counter++,
                              target.extension().string());
}

Status replace_with_temp(const fs::path& temp, const fs::path& target) {
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec) {
    const std::string why = ec.message();
    fs::remove(temp, ec);
    return make_error(ErrorCode::kIo, fmt::format("{}: cannot replace the file ({}); the old file is untouched",
                                                  target.string(), why));
  }
  return ok_status();
}

Status write_file_atomic(const fs::path& target, std::string_view bytes) {
  const fs::path temp = temp_path_beside(target);
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) {
      return make_error(ErrorCode::kIo, fmt::format("{}: cannot create a file in this folder ({})", target.string(),
                                                    std::strerror(errno)));
    }
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      std::error_code ec;
      fs::remove(temp, ec);
      return make_error(ErrorCode::kIo,
                        fmt::format("{}: writing failed (disk full?); the old file is untouched", target.string()));
    }
  }
  return replace_with_temp(temp, target);
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
