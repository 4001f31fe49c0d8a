#include "undo.hpp"

#include <fmt/format.h>

namespace sylva::editor {

std::size_t UndoEntry::bytes() const {
  std::size_t b = 0;
  for (const Edit& e : edits) {
    if (const auto* m = std::get_if<MapEdit>(&e)) b += (m->before.size() + m->after.size()) * sizeof(float);
  }
  return b;
}

void UndoStack::push(UndoEntry entry) {
  entries_.resize(position_);
  if (saved_valid_ && saved_ > position_) saved_valid_ = false;  // the saved state was undone away
  entries_.push_back(std::move(entry));
  ++position_;
  trim();
}

namespace {

Status apply(EditTarget& target, const Edit& edit, bool forward) {
  return std::visit(
      [&](const auto& e) -> Status {
        using T = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<T, MapEdit>) {
          return target.write_map_rect(e.map_id, e.rect, forward ? e.after : e.before);
        } else if constexpr (std::is_same_v<T, ParamEdit>) {
          return target.write_param(e.path, forward ? e.after : e.before);
        } else if constexpr (std::is_same_v<T, SectionEdit>) {
          return target.write_section(e.module, forward ? e.after : e.before);
        } else {
          return target.write_bookmark(e.name, forward ? e.after : e.before);
        }
      },
      edit);
}

}  // namespace

Status UndoStack::undo(EditTarget& target) {
  if (!can_undo()) return make_error(ErrorCode::kInvalidArgument, "undo: nothing to undo");
  const UndoEntry& entry = entries_[position_ - 1];
  for (auto it = entry.edits.rbegin(); it != entry.edits.rend(); ++it) {
    Status s = apply(target, *it, false);
    if (!s.ok()) return make_error(s.error().code, fmt::format("undo \"{}\": {}", entry.label, s.error().message));
  }
  --position_;
  return {};
}

Status UndoStack::redo(EditTarget& target) {
  if (!can_redo()) return make_error(ErrorCode::kInvalidArgument, "redo: nothing to redo");
  const UndoEntry& entry = entries_[position_];
  for (const Edit& e : entry.edits) {
    Status s = apply(target, e, true);
    if (!s.ok()) return make_error(s.error().code, fmt::format("redo \"{}\": {}", entry.label, s.error().message));
  }
  ++position_;
  return {};
}

UndoEntry* UndoStack::mergeable_top() {
  if (position_ == 0 || position_ != entries_.size()) return nullptr;
  if (saved_valid_ && saved_ == position_) return nullptr;
  return &entries_.back();
}

void UndoStack::clear() {
  entries_.clear();
  position_ = 0;
  saved_ = 0;
  saved_valid_ = false;
}

std::size_t UndoStack::bytes() const {
  std::size_t b = 0;
  for (const UndoEntry& e : entries_) b += e.bytes();
  return b;
}

void UndoStack::trim() {
  while (entries_.size() > 1 && bytes() > max_bytes_) {
    entries_.erase(entries_.begin());
    --position_;
    if (saved_valid_) {
      if (saved_ == 0) saved_valid_ = false;
      else --saved_;
    }
  }
}

void StrokeRecorder::before_dab(const scene::TexelRect& dab) {
  const scene::TexelRect r = dab.intersect(grid_->bounds());
  if (r.empty()) return;
  const scene::TexelRect grown = rect_.unite(r);
  if (grown == rect_) return;
  // New buffer over the grown rectangle: old before-values inside the old rectangle, current
  // (still untouched) map values elsewhere.
  std::vector<float> next;
  next.reserve(static_cast<std::size_t>(grown.width()) * static_cast<std::size_t>(grown.height()));
  for (int j = grown.y0; j < grown.y1; ++j) {
    for (int i = grown.x0; i < grown.x1; ++i) {
      const bool inside = !rect_.empty() && i >= rect_.x0 && i < rect_.x1 && j >= rect_.y0 && j < rect_.y1;
      next.push_back(inside ? before_[static_cast<std::size_t>(j - rect_.y0) * static_cast<std::size_t>(rect_.width()) +
                                      static_cast<std::size_t>(i - rect_.x0)]
                            : grid_->at(i, j));
    }
  }
  before_ = std::move(next);
  rect_ = grown;
}

std::optional<MapEdit> StrokeRecorder::finish() const {
  if (rect_.empty()) return std::nullopt;
  return MapEdit{map_id_, rect_, before_, grid_->copy_rect(rect_)};
}

}  // namespace sylva::editor
