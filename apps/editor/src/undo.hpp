#pragma once
// Undo/redo for every edit of the editor (GL-free, unit-tested in tests/undo_test.cpp).
//
// An entry is one user action (a whole brush stroke, one parameter change, adding a module...)
// made of edits. Map edits keep the before- and after-values of the stroke's dirty rectangle
// only, so undo and redo restore the map bit-exactly without copying whole maps; parameter edits
// keep the before/after text, which core params round-trip bit-exactly.
//
// StrokeRecorder builds a map edit while a stroke is painted: before each dab it is told the
// dab's rectangle and saves the before-values of texels not yet covered by the stroke (the
// union rectangle grows; texels outside the old union are still untouched, so reading them from
// the map gives their before-values).
//
// The stack knows the entry the document was saved at, so "unsaved changes" survives undo back
// to the saved state (and redo away from it).

#include <sylva/core/result.hpp>
#include <sylva/scene/camera_path.hpp>
#include <sylva/scene/map_grid.hpp>

#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace sylva::editor {

struct MapEdit {
  std::string map_id;           // "ground.height"
  scene::TexelRect rect;
  std::vector<float> before;    // rect's values before / after, row by row
  std::vector<float> after;
};

struct ParamEdit {
  std::string path;             // "grass.field.density"
  std::string before;           // values as ParamDescriptor::get_string text
  std::string after;
};

// A module section added (before = null), removed (after = null) or replaced, as section JSON.
struct SectionEdit {
  std::string module;
  nlohmann::json before;
  nlohmann::json after;
};

struct BookmarkEdit {
  std::string name;
  std::optional<scene::CameraView> before;  // none: the bookmark did not exist
  std::optional<scene::CameraView> after;
};

using Edit = std::variant<MapEdit, ParamEdit, SectionEdit, BookmarkEdit>;

struct UndoEntry {
  std::string label;  // "paint ground.height", "set grass.field.density"
  std::vector<Edit> edits;
  std::size_t bytes() const;
};

// What undo/redo write into (the editor session; a plain map store in tests).
class EditTarget {
 public:
  virtual ~EditTarget() = default;
  virtual Status write_map_rect(const std::string& map_id, const scene::TexelRect& rect, const std::vector<float>& values) = 0;
  virtual Status write_param(const std::string& path, const std::string& text) = 0;
  virtual Status write_section(const std::string& module, const nlohmann::json& section) = 0;  // null = remove
  virtual Status write_bookmark(const std::string& name, const std::optional<scene::CameraView>& view) = 0;
};

class UndoStack {
 public:
  // Oldest entries are dropped when the stored map values exceed this many bytes.
  explicit UndoStack(std::size_t max_bytes = std::size_t{512} << 20) : max_bytes_(max_bytes) {}

  // Adds an entry and drops every redo entry.
  void push(UndoEntry entry);
  bool can_undo() const { return position_ > 0; }
  bool can_redo() const { return position_ < entries_.size(); }
  // Applies the before-state of the newest entry (its edits in reverse order). On failure the
  // position does not move and the error names the edit.
  Status undo(EditTarget& target);
  Status redo(EditTarget& target);
  const UndoEntry* next_undo() const { return can_undo() ? &entries_[position_ - 1] : nullptr; }
  // The newest entry when it may still be extended in place (no redo entries after it and it is
  // not the saved state): slider drags merge their steps into it. Null otherwise.
  UndoEntry* mergeable_top();
  const UndoEntry* next_redo() const { return can_redo() ? &entries_[position_] : nullptr; }

  void clear();
  void mark_saved() { saved_ = position_; saved_valid_ = true; }
  // True when the current state differs from the last save (or was never saved and has edits).
  bool unsaved() const { return !saved_valid_ || saved_ != position_; }
  // For a document just loaded: the current (empty) state is the saved one.
  void reset_saved() { clear(); mark_saved(); }

  std::size_t size() const { return entries_.size(); }
  std::size_t position() const { return position_; }
  std::size_t bytes() const;

 private:
  void trim();
  std::vector<UndoEntry> entries_;
  std::size_t position_ = 0;  // entries_[0, position_) are applied
  std::size_t saved_ = 0;
  bool saved_valid_ = true;
  std::size_t max_bytes_;
};

// Records the dirty rectangle of one stroke on one map.
class StrokeRecorder {
 public:
  StrokeRecorder(std::string map_id, const scene::MapGrid& grid) : map_id_(std::move(map_id)), grid_(&grid) {}
  // Call before a dab changes `rect` (clipped to the grid).
  void before_dab(const scene::TexelRect& rect);
  // The edit, reading the after-values from the grid; nullopt when nothing was touched.
  std::optional<MapEdit> finish() const;
  const scene::TexelRect& rect() const { return rect_; }

 private:
  std::string map_id_;
  const scene::MapGrid* grid_;
  scene::TexelRect rect_;
  std::vector<float> before_;
};

}  // namespace sylva::editor
