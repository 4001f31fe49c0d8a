#include "with_scene/shipped_files.hpp"

#include <fmt/format.h>

#include <system_error>
#include <vector>

namespace sylva::bench {

Result<std::filesystem::path> find_shipped_file(const std::filesystem::path& relative, const std::string& who) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::vector<fs::path> starts = {fs::current_path(ec)};
  if (const fs::path exe = fs::read_symlink("/proc/self/exe", ec); !ec) starts.push_back(exe.parent_path());
  for (fs::path dir : starts) {
    for (int up = 0; up < 6 && !dir.empty(); ++up, dir = dir.parent_path()) {
      if (fs::exists(dir / relative, ec)) return dir / relative;
      if (dir == dir.parent_path()) break;
    }
  }
  return make_error(ErrorCode::kNotFound, fmt::format("{} reads the shipped {}, found neither under the working directory "
                                                      "nor above the executable",
                                                      who, relative.string()));
}

}  // namespace sylva::bench
