#include <sylva/core/cache_directory.hpp>

namespace sylva {

std::filesystem::path resolve_cache_directory(const std::string& setting, const std::string& auto_name,
                                              const std::filesystem::path& base) {
  if (setting.empty()) return {};
  if (setting == "auto") {
    std::error_code ec;
    const std::filesystem::path tmp = std::filesystem::temp_directory_path(ec);
    if (ec) return {};
    return tmp / auto_name;
  }
  const std::filesystem::path p(setting);
  return p.is_absolute() || base.empty() ? p : base / p;
}

}  // namespace sylva
