// Undo/redo: strokes are restored bit-exactly from their dirty rectangle, parameter edits by
// text, the saved state is tracked across undo/redo, memory is capped.
#include "brush.hpp"
#include "undo.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <map>

using namespace sylva;
using namespace sylva::editor;

namespace {

// An in-memory EditTarget: maps and parameters, no GL.
struct FakeTarget : EditTarget {
  std::map<std::string, scene::MapGrid> maps;
  std::map<std::string, std::string> params;
  std::map<std::string, nlohmann::json> sections;
  std::map<std::string, scene::CameraView> bookmarks;
  Status write_map_rect(const std::string& id, const scene::TexelRect& rect, const std::vector<float>& values) override {
    auto it = maps.find(id);
    if (it == maps.end()) return make_error(ErrorCode::kNotFound, id);
    it->second.paste_rect(rect, values);
    return {};
  }
  Status write_param(const std::string& path, const std::string& text) override {
    params[path] = text;
    return {};
  }
  Status write_section(const std::string& module, const nlohmann::json& s) override {
    if (s.is_null()) sections.erase(module);
    else sections[module] = s;
    return {};
  }
  Status write_bookmark(const std::string& name, const std::optional<scene::CameraView>& v) override {
    if (v) bookmarks[name] = *v;
    else bookmarks.erase(name);
    return {};
  }
};

scene::MapGrid noisy(int w, int h) {
  scene::MapGrid g(w, h, 0.0f, {0.0, 0.0}, {1.0, 1.0});
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) g.at(i, j) = std::sin(i * 0.37f + j * 0.11f) * 3.0f + 1e-7f * static_cast<float>(i * j);
  return g;
}

// Paints a stroke through `points` like the editor does, returning its undo entry.
UndoEntry paint(scene::MapGrid& g, const std::string& id, const BrushSettings& b, std::vector<glm::dvec2> points) {
  StrokeRecorder rec(id, g);
  const std::vector<glm::dvec2> dabs = stroke_dabs(points, b.spacing * b.radius);
  const float target = resolve_target(g, b, dabs.front());
  for (const glm::dvec2& d : dabs) {
    rec.before_dab(dab_rect(g, d, b.radius));
    apply_dab(g, scene::MapKind::kHeight, b, d, target);
  }
  UndoEntry e{"paint " + id, {}};
  if (auto edit = rec.finish()) e.edits.push_back(*edit);
  return e;
}

bool same_bits(const scene::MapGrid& a, const scene::MapGrid& b) {
  return a.values.size() == b.values.size() &&
         std::memcmp(a.values.data(), b.values.data(), a.values.size() * sizeof(float)) == 0;
}

}  // namespace

TEST(Undo, StrokesUndoAndRedoBitExactly) {
  FakeTarget t;
  t.maps["ground.height"] = noisy(64, 48);
  const scene::MapGrid original = t.maps["ground.height"];
  scene::MapGrid& g = t.maps["ground.height"];
  UndoStack stack;
  BrushSettings b;
  b.radius = 5.0f;
  b.strength = 0.7f;
  std::vector<scene::MapGrid> states = {g};
  const BrushOp ops[] = {BrushOp::kRaise, BrushOp::kSmooth, BrushOp::kFlatten, BrushOp::kNoise, BrushOp::kLower};
  int k = 0;
  for (BrushOp op : ops) {
    b.op = op;
    UndoEntry e = paint(g, "ground.height", b, {{5.0 + 7 * k, 4.0}, {30.0, 20.0 + 3 * k}, {60.0, 44.0}});
    ASSERT_EQ(e.edits.size(), 1u);
    const auto& edit = std::get<MapEdit>(e.edits[0]);
    // The dirty rectangle holds every changed texel; outside it nothing changed.
    for (int j = 0; j < g.height; ++j)
      for (int i = 0; i < g.width; ++i)
        if (!(i >= edit.rect.x0 && i < edit.rect.x1 && j >= edit.rect.y0 && j < edit.rect.y1)) {
          ASSERT_EQ(g.at(i, j), states.back().at(i, j));
        }
    EXPECT_LT(edit.rect.width() * edit.rect.height(), g.width * g.height) << "only the dirty rectangle is stored";
    stack.push(std::move(e));
    states.push_back(g);
    ++k;
  }
  for (int n = static_cast<int>(states.size()) - 2; n >= 0; --n) {
    ASSERT_TRUE(stack.undo(t).ok());
    EXPECT_TRUE(same_bits(g, states[static_cast<std::size_t>(n)])) << "undo to state " << n;
  }
  EXPECT_TRUE(same_bits(g, original));
  EXPECT_FALSE(stack.undo(t).ok());
  for (std::size_t n = 1; n < states.size(); ++n) {
    ASSERT_TRUE(stack.redo(t).ok());
    EXPECT_TRUE(same_bits(g, states[n])) << "redo to state " << n;
  }
  EXPECT_FALSE(stack.redo(t).ok());
}

TEST(Undo, ParametersSectionsBookmarksAndSavedState) {
  FakeTarget t;
  UndoStack stack;
  EXPECT_FALSE(stack.unsaved());
  stack.push({"set a", {ParamEdit{"grass.field.density", "100", "120"}}});
  EXPECT_TRUE(stack.unsaved());
  stack.mark_saved();
  EXPECT_FALSE(stack.unsaved());
  scene::CameraView view;
  view.position = {1, 2, 3};
  stack.push({"bookmark", {BookmarkEdit{"home", std::nullopt, view}}});
  stack.push({"add grass", {SectionEdit{"grass", nullptr, {{"field", {{"density", 5}}}}}}});
  EXPECT_TRUE(stack.unsaved());
  ASSERT_TRUE(stack.undo(t).ok());
  EXPECT_EQ(t.sections.count("grass"), 0u);
  ASSERT_TRUE(stack.undo(t).ok());
  EXPECT_EQ(t.bookmarks.count("home"), 0u);
  EXPECT_FALSE(stack.unsaved()) << "undone back to the saved state";
  ASSERT_TRUE(stack.undo(t).ok());
  EXPECT_EQ(t.params["grass.field.density"], "100");
  EXPECT_TRUE(stack.unsaved());
  ASSERT_TRUE(stack.redo(t).ok());
  EXPECT_EQ(t.params["grass.field.density"], "120");
  EXPECT_FALSE(stack.unsaved());
  ASSERT_TRUE(stack.redo(t).ok());
  EXPECT_EQ(t.bookmarks.at("home").position, view.position);
  // A new edit after undo drops the redo entries; the saved state can no longer be reached.
  ASSERT_TRUE(stack.undo(t).ok());
  ASSERT_TRUE(stack.undo(t).ok());
  stack.push({"set b", {ParamEdit{"sun.intensity", "3", "2"}}});
  EXPECT_FALSE(stack.can_redo());
  EXPECT_TRUE(stack.unsaved());
  ASSERT_TRUE(stack.undo(t).ok());
  EXPECT_TRUE(stack.unsaved());
}

TEST(Undo, FailedUndoKeepsThePositionAndNamesTheEntry) {
  FakeTarget t;  // no maps: writing one fails
  UndoStack stack;
  stack.push({"paint lost.map", {MapEdit{"lost.map", {0, 0, 1, 1}, {1.0f}, {2.0f}}}});
  auto s = stack.undo(t);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("paint lost.map"), std::string::npos);
  EXPECT_TRUE(stack.can_undo());
}

TEST(Undo, MemoryIsCappedByDroppingTheOldest) {
  UndoStack stack(1000);
  for (int i = 0; i < 10; ++i) stack.push({"big", {MapEdit{"m", {0, 0, 10, 10}, std::vector<float>(100), std::vector<float>(100)}}});
  EXPECT_EQ(stack.size(), 1u) << "800 bytes per entry, cap 1000";
  EXPECT_LE(stack.bytes(), 1000u);
  EXPECT_TRUE(stack.can_undo());
}

TEST(Undo, RecorderGrowsItsRectangleWithoutLosingBeforeValues) {
  scene::MapGrid g = noisy(20, 20);
  const scene::MapGrid original = g;
  StrokeRecorder rec("m", g);
  rec.before_dab({2, 2, 5, 5});
  for (int j = 2; j < 5; ++j)
    for (int i = 2; i < 5; ++i) g.at(i, j) = 99.0f;
  rec.before_dab({4, 4, 9, 7});  // overlaps the already painted texels
  for (int j = 4; j < 7; ++j)
    for (int i = 4; i < 9; ++i) g.at(i, j) = -5.0f;
  rec.before_dab({-3, -3, 1, 1});  // clipped at the border
  g.at(0, 0) = 7.0f;
  auto edit = rec.finish();
  ASSERT_TRUE(edit.has_value());
  EXPECT_EQ(edit->rect, (scene::TexelRect{0, 0, 9, 7}));
  g.paste_rect(edit->rect, edit->before);
  EXPECT_TRUE(same_bits(g, original));
  EXPECT_FALSE(StrokeRecorder("m", g).finish().has_value());
}
