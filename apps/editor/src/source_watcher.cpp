#include "source_watcher.hpp"

#include <sylva/core/atomic_file.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <system_error>

namespace sylva::editor {
namespace {

namespace fs = std::filesystem;

// Largest JSON file searched for the files it names (a species table is at most 4 MiB).
constexpr std::uintmax_t kMaxJsonBytes = std::uintmax_t{4} << 20;

fs::path absolute_normal(const fs::path& p) {
  std::error_code ec;
  const fs::path a = fs::absolute(p, ec);
  return (ec ? p : a).lexically_normal();
}

void named_files(const nlohmann::json& j, const fs::path& folder, std::vector<fs::path>& out) {
  if (j.is_string()) {
    const std::string& s = j.get_ref<const std::string&>();
    if (s.empty() || s.size() > 4096 || s.find('\0') != std::string::npos) return;
    std::error_code ec;
    const fs::path p = absolute_normal(fs::path(s).is_absolute() ? fs::path(s) : folder / s);
    if (fs::is_regular_file(p, ec)) out.push_back(p);
  } else if (j.is_structured()) {
    for (const auto& v : j) named_files(v, folder, out);
  }
}

// The files a JSON file names; nothing when it is not readable JSON (the module reports that).
std::vector<fs::path> files_named_by(const fs::path& json_file) {
  std::vector<fs::path> out;
  std::error_code ec;
  if (json_file.extension() != ".json" || !fs::is_regular_file(json_file, ec) || fs::file_size(json_file, ec) > kMaxJsonBytes) {
    return out;
  }
  auto text = read_file(json_file);
  if (!text.ok()) return out;
  const nlohmann::json j = nlohmann::json::parse(*text, nullptr, false);
  if (!j.is_discarded()) named_files(j, json_file.parent_path(), out);
  return out;
}

}  // namespace

std::vector<WatchedSource> scene_sources(const scene::SceneDocument& document) {
  std::vector<WatchedSource> out;
  auto add = [&](const std::string& param, const fs::path& file) {
    const WatchedSource w{param, file};
    if (std::find(out.begin(), out.end(), w) == out.end()) out.push_back(w);
  };
  for (const scene::ModuleSection& section : document.modules()) {
    for (const ParamDescriptor& p : describe_params(*section.settings)) {
      if (!scene::names_scene_file(p.path) || p.ref.type != ParamType::kString) continue;
      const std::string value = p.get_string();
      if (value.empty()) continue;
      const std::string param = section.name + "." + p.path;
      const fs::path file = absolute_normal(document.resolve(value));
      add(param, file);
      for (const fs::path& named : files_named_by(file)) add(param, named);
    }
  }
  return out;
}

SourceWatcher::Stamp SourceWatcher::stamp(const fs::path& file) {
  std::error_code ec;
  Stamp s;
  const auto status = fs::status(file, ec);
  if (ec || !fs::is_regular_file(status)) return s;
  s.exists = true;
  s.size = fs::file_size(file, ec);
  const auto time = fs::last_write_time(file, ec);
  if (!ec) s.mtime = static_cast<std::int64_t>(time.time_since_epoch().count());
  return s;
}

void SourceWatcher::watch(const std::vector<WatchedSource>& sources) {
  sources_ = sources;
  std::map<fs::path, Stamp> kept;
  for (const WatchedSource& w : sources_) {
    if (kept.contains(w.file)) continue;
    auto it = seen_.find(w.file);
    kept[w.file] = it != seen_.end() ? it->second : stamp(w.file);
  }
  seen_ = std::move(kept);
}

std::vector<WatchedSource> SourceWatcher::poll() {
  std::vector<WatchedSource> changed;
  std::map<fs::path, bool> checked;  // a file named by two settings is reported for both
  for (const WatchedSource& w : sources_) {
    auto done = checked.find(w.file);
    if (done == checked.end()) {
      const Stamp now = stamp(w.file);
      Stamp& before = seen_[w.file];
      done = checked.emplace(w.file, !(now == before)).first;
      before = now;
    }
    if (done->second) changed.push_back(w);
  }
  return changed;
}

}  // namespace sylva::editor
