// Terrain stability cases for --stability, built from the public chunk-tree and selection API
// (modules/terrain): degenerate and extreme height fields, cameras far away, under the ground
// and with extreme lenses. GL-free.
#include "stability.hpp"

#include <sylva/core/height_field.hpp>
#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/lod_view.hpp>
#include <sylva/terrain/selection.hpp>
#include <sylva/terrain/vertex_position.hpp>

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace sylva::bench {
namespace {

HeightField make_field(int columns, int rows, double spacing, glm::dvec2 origin, float (*h)(int, int)) {
  HeightField f(columns, rows, spacing, origin);
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) f.sample(i, j) = h(i, j);
  }
  f.update_range();
  return f;
}

terrain::LodView view_at(const glm::dvec3& pos, const glm::dvec3& forward, double fov_y) {
  return terrain::LodView::perspective(pos, forward, glm::dvec3(0, 1, 0), fov_y, 256, 144, 0.5,
                                       std::numeric_limits<double>::infinity());
}

// Builds, selects from `view` and places every vertex of every selected chunk; counts non-finite
// coordinates. Returns the build error message when the build fails.
struct TerrainProbe {
  bool built = false;
  std::string error;
  std::uint64_t non_finite = 0;
  std::uint32_t chunks = 0;
  std::uint64_t triangles = 0;
  float root_error = 0.0f;
};

TerrainProbe probe(const HeightField& field, const terrain::LodView& view, terrain::LodSettings lod = {}) {
  TerrainProbe p;
  terrain::ChunkTreeSettings settings;
  settings.leaf_dimension = 17;
  settings.threads = 1;
  auto tree = terrain::ChunkTree::build(field, settings);
  if (!tree.ok()) {
    p.error = tree.error().message;
    return p;
  }
  p.built = true;
  p.root_error = tree->chunk(0).error;
  terrain::LodSelector selector(*tree);
  const terrain::Selection& sel = selector.select(view, lod);
  const terrain::VertexFrame frame = terrain::make_vertex_frame(*tree, view, lod);
  p.chunks = sel.stats.chunks;
  p.triangles = sel.stats.triangles;
  for (const terrain::SelectedChunk& s : sel.chunks) {
    for (const terrain::ChunkVertex& v : tree->chunk(s.index).mesh.vertices) {
      const glm::vec3 q = terrain::vertex_position(frame, v);
      p.non_finite += !std::isfinite(q.x) + !std::isfinite(q.y) + !std::isfinite(q.z);
    }
  }
  return p;
}

StabilityOutcome outcome_of(const TerrainProbe& p, bool must_build, bool must_draw) {
  StabilityOutcome o;
  o.nan_count = p.non_finite;
  o.passed = (p.built == must_build) && (!must_draw || p.chunks > 0);
  o.detail = p.built ? fmt::format("{} chunks, {} triangles drawn, root error {:.3g} m, {} non-finite coordinates",
                                   p.chunks, p.triangles, p.root_error, p.non_finite)
                     : "build refused: " + p.error;
  return o;
}

StabilityOutcome flat_field() {
  const HeightField f = make_field(129, 129, 1.0, {0, 0}, [](int, int) { return 5.0f; });
  const TerrainProbe p = probe(f, view_at({64, 30, -40}, {0, -0.4, 1}, 1.0));
  StabilityOutcome o = outcome_of(p, true, true);
  o.passed = o.passed && p.root_error == 0.0f;
  return o;
}

StabilityOutcome spike_10km() {
  const HeightField f = make_field(129, 129, 1.0, {0, 0}, [](int i, int j) { return (i == 70 && j == 51) ? 10000.0f : 0.0f; });
  const TerrainProbe p = probe(f, view_at({64, 200, -300}, {0, -0.2, 1}, 1.0));
  StabilityOutcome o = outcome_of(p, true, true);
  // The measured root error must see the spike (it cannot be reduced away silently).
  o.passed = o.passed && p.root_error >= 10000.0f * 0.99f;
  return o;
}

StabilityOutcome tiny_and_odd_fields() {
  StabilityOutcome o;
  o.passed = true;
  std::string detail;
  const std::pair<int, int> sizes[] = {{1, 1}, {2, 7}, {33, 17}, {3, 130}};
  for (auto [c, r] : sizes) {
    const HeightField f = make_field(c, r, 2.0, {-10, 5}, [](int i, int j) { return 0.3f * static_cast<float>(i * j % 7); });
    const TerrainProbe p = probe(f, view_at({0, 50, -60}, {0.1, -0.5, 1}, 1.0));
    o.nan_count += p.non_finite;
    // Either a build with finite vertices or a clear refusal; never a crash.
    if (!p.built && p.error.empty()) o.passed = false;
    detail += fmt::format("{}{}x{}: {}", detail.empty() ? "" : "; ", c, r,
                          p.built ? fmt::format("{} chunks", p.chunks) : "refused (" + p.error + ")");
  }
  o.detail = detail;
  return o;
}

StabilityOutcome nan_input_rejected() {
  HeightField f = make_field(65, 65, 1.0, {0, 0}, [](int, int) { return 1.0f; });
  f.sample(10, 20) = std::numeric_limits<float>::quiet_NaN();
  f.sample(11, 20) = std::numeric_limits<float>::infinity();
  const TerrainProbe p = probe(f, view_at({32, 20, -20}, {0, -0.4, 1}, 1.0));
  StabilityOutcome o = outcome_of(p, false, false);
  o.passed = o.passed && p.error.find("2") != std::string::npos;  // the message gives the count
  return o;
}

StabilityOutcome far_from_origin() {
  // The same field at the origin and 1e5 m away, seen from the same relative pose: the
  // camera-relative vertex positions must agree to well under a millimetre.
  auto h = [](int i, int j) { return 20.0f * std::sin(0.11f * static_cast<float>(i)) * std::cos(0.07f * static_cast<float>(j)); };
  const HeightField near_f = make_field(129, 129, 1.0, {0, 0}, h);
  const HeightField far_f = make_field(129, 129, 1.0, {1e5, -1e5}, h);
  terrain::ChunkTreeSettings settings;
  settings.leaf_dimension = 17;
  settings.threads = 1;
  auto a = terrain::ChunkTree::build(near_f, settings);
  auto b = terrain::ChunkTree::build(far_f, settings);
  StabilityOutcome o;
  if (!a.ok() || !b.ok()) {
    o.detail = !a.ok() ? a.error().message : b.error().message;
    return o;
  }
  const glm::dvec3 rel(60.3, 35.0, -25.7);
  const terrain::LodView va = view_at(rel, {0.1, -0.4, 1}, 1.0);
  const terrain::LodView vb = view_at(rel + glm::dvec3(1e5, 0, -1e5), {0.1, -0.4, 1}, 1.0);
  terrain::LodSelector sa(*a), sb(*b);
  const terrain::Selection& sel_a = sa.select(va, {});
  const terrain::Selection& sel_b = sb.select(vb, {});
  const terrain::VertexFrame fa = terrain::make_vertex_frame(*a, va, {});
  const terrain::VertexFrame fb = terrain::make_vertex_frame(*b, vb, {});
  double worst = 0.0;
  std::size_t compared = 0;
  const std::size_t n = std::min(sel_a.chunks.size(), sel_b.chunks.size());
  for (std::size_t c = 0; c < n; ++c) {
    const auto& ma = a->chunk(sel_a.chunks[c].index).mesh.vertices;
    const auto& mb = b->chunk(sel_b.chunks[c].index).mesh.vertices;
    for (std::size_t k = 0; k < std::min(ma.size(), mb.size()); ++k) {
      const glm::vec3 pa = terrain::vertex_position(fa, ma[k]);
      const glm::vec3 pb = terrain::vertex_position(fb, mb[k]);
      o.nan_count += !std::isfinite(pb.x) + !std::isfinite(pb.y) + !std::isfinite(pb.z);
      worst = std::max(worst, static_cast<double>(glm::length(pa - pb)));
      ++compared;
    }
  }
  o.passed = sel_a.chunks.size() == sel_b.chunks.size() && compared > 0 && worst < 1e-3;
  o.detail = fmt::format("{} vertices compared, largest camera-relative difference {:.2e} m ({} vs {} chunks)", compared,
                         worst, sel_a.chunks.size(), sel_b.chunks.size());
  return o;
}

StabilityOutcome camera_below_ground() {
  const HeightField f = make_field(129, 129, 1.0, {0, 0}, [](int i, int) { return 40.0f + 0.1f * static_cast<float>(i); });
  return outcome_of(probe(f, view_at({64, -50, 64}, {0.3, 1.0, 0.2}, 1.0)), true, false);
}

StabilityOutcome extreme_lenses() {
  const HeightField f = make_field(129, 129, 1.0, {0, 0}, [](int i, int j) { return 0.05f * static_cast<float>((i * 7 + j * 13) % 50); });
  StabilityOutcome o;
  o.passed = true;
  std::string detail;
  for (double fov : {1e-3, 0.05, 1.0, 3.0}) {
    const TerrainProbe p = probe(f, view_at({-20, 15, -20}, {1, -0.3, 1}, fov));
    o.nan_count += p.non_finite;
    o.passed = o.passed && p.built;
    detail += fmt::format("{}fov {} rad: {} chunks", detail.empty() ? "" : "; ", fov, p.chunks);
  }
  o.detail = detail;
  return o;
}

}  // namespace

void add_terrain_stability_cases(std::vector<StabilityCase>& cases) {
  cases.push_back({"terrain", "flat_field", "a flat field builds with measured error exactly 0 and draws finite vertices",
                   false, flat_field});
  cases.push_back({"terrain", "spike_10km", "one 10 km spike: the root's measured error keeps it (>= 9.9 km), vertices "
                   "finite", false, spike_10km});
  cases.push_back({"terrain", "tiny_and_non_square_fields", "1x1, 2x7, 33x17, 3x130 fields build with finite vertices "
                   "or are refused with a message; never a crash", false, tiny_and_odd_fields});
  cases.push_back({"terrain", "nan_input_rejected", "NaN/Inf samples are refused with their count, never built into "
                   "geometry", false, nan_input_rejected});
  cases.push_back({"terrain", "far_from_origin_1e5m", "the same field 1e5 m from the origin gives camera-relative "
                   "vertices within 1 mm of the field at the origin (no jitter)", false, far_from_origin});
  cases.push_back({"terrain", "camera_below_ground", "a camera 50 m under the surface looking up: selection runs, "
                   "vertices finite", false, camera_below_ground});
  cases.push_back({"terrain", "extreme_fov", "fov 0.001..3 rad: selection runs, vertices finite", false, extreme_lenses});
}

}  // namespace sylva::bench
