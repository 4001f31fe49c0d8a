#pragma once
// The editor's source-file watcher (issue #16 "Your own plants"): the files a scene's settings
// name are polled (modification time and size; no inotify) and a changed file is reported with
// the setting that names it, so the editor can rebuild that module in place (EditorSession
// polls twice a second and calls Scene::reload_module).
//
// Which files: every non-empty string setting named `file` or `*_file` (the scenes' convention,
// scene::names_scene_file), resolved against the scene's folder; and, for a JSON file among
// them (a voxel species table, a block palette, a tree species file), every string value in it
// that names an existing file relative to the JSON's folder (the table's .lsys grammars, the
// palette's images, the tree's OBJT model and images), watched under the same setting. GL-free.

#include <sylva/scene/scene_document.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace sylva::editor {

struct WatchedSource {
  std::string param;           // "voxel.flora.species_file"
  std::filesystem::path file;  // absolute, normalised

  bool operator==(const WatchedSource&) const = default;
};

// Every file `document`'s settings name, with the files a named JSON file names (see above).
std::vector<WatchedSource> scene_sources(const scene::SceneDocument& document);

class SourceWatcher {
 public:
  // Replaces the watched set. A file watched before keeps its last seen state (a change made
  // between two calls is still reported); a new one is taken as it is now.
  void watch(const std::vector<WatchedSource>& sources);
  // The watched files whose size, modification time or existence changed since they were last
  // seen, in watch order.
  std::vector<WatchedSource> poll();
  const std::vector<WatchedSource>& sources() const { return sources_; }

 private:
  struct Stamp {
    bool exists = false;
    std::uintmax_t size = 0;
    std::int64_t mtime = 0;
    bool operator==(const Stamp&) const = default;
  };
  static Stamp stamp(const std::filesystem::path& file);

  std::vector<WatchedSource> sources_;
  std::map<std::filesystem::path, Stamp> seen_;
};

}  // namespace sylva::editor
