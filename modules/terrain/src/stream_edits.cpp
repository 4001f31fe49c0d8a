// Height edits of a streamed terrain (stream_edits.hpp).
#include "stream_edits.hpp"

#include "parallel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace sylva::terrain::detail {

ChunkMesh RebuildSource::build(std::uint32_t index) const {
  Chunk chunk = grids->tree.chunk(index);
  ChunkTreeBuilder::build_chunk(*grids, chunk);
  return std::move(chunk.mesh);
}

namespace {

// The previous edit's grids brought up to `field` (issue 15 (a)): copied (streaming threads may
// still build from the old ones), the padded heights rewritten in the edits' root-grid rectangles
// (padding clamps to the last sample, as prepare's padded_heights does) and the RTIN errors near
// them recomputed (update_errors), so the result equals prepare(field) bit for bit at a cost of
// one copy plus the strokes' own work, not prepare's whole-field error passes.
Result<std::unique_ptr<TreeGrids>> updated_grids(const TreeGrids& old, const HeightField& field,
                                                 const std::vector<std::array<std::int64_t, 4>>& edits) {
  auto g = std::make_unique<TreeGrids>(old);
  g->errors.heights = &g->heights;
  g->rule.errors = &g->errors;
  const std::size_t side = static_cast<std::size_t>(g->heights.n) + 1;
  for (const auto& e : edits) {
    for (std::int64_t z = e[1]; z <= e[3]; ++z) {
      const int fz = std::min(static_cast<int>(z), field.rows() - 1);
      for (std::int64_t x = e[0]; x <= e[2]; ++x) {
        const int fx = std::min(static_cast<int>(x), field.columns() - 1);
        const float h = field.sample(fx, fz);
        if (!std::isfinite(h)) {
          return make_error(ErrorCode::kInvalidArgument,
                            fmt::format("terrain: the height field has a NaN/Inf sample at column {} row {} "
                                        "(load with non_finite = repair to replace them)",
                                        fx, fz));
        }
        g->heights.h[static_cast<std::size_t>(z) * side + static_cast<std::size_t>(x)] = h;
      }
    }
  }
  for (const auto& e : edits) {
    update_errors(g->errors, static_cast<std::int32_t>(e[0]), static_cast<std::int32_t>(e[1]),
                  static_cast<std::int32_t>(e[2]), static_cast<std::int32_t>(e[3]));
  }
  return g;
}

}  // namespace

StreamEdits::StreamEdits(const ChunkTree& file_tree) : tree_(file_tree) {}

Result<RegionRebuild> StreamEdits::apply(const HeightField& field, const std::vector<SampleRect>& rects,
                                         RebuiltMeshes& meshes) {
  RegionRebuild out;
  if (tree_.settings().tessellation != Tessellation::kRtin) {
    return make_error(ErrorCode::kInvalidArgument,
                      "terrain.tree.tessellation: only RTIN chunk files can be painted (re-bake with the default)");
  }
  if (field.columns() != tree_.field_columns() || field.rows() != tree_.field_rows() ||
      field.spacing() != tree_.spacing() || field.origin() != tree_.origin()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("terrain: the edited ground is {}x{} samples {} m apart from ({}, {}), the baked file "
                                  "{}x{} samples {} m apart from ({}, {}): it cannot be painted",
                                  field.columns(), field.rows(), field.spacing(), field.origin().x, field.origin().y,
                                  tree_.field_columns(), tree_.field_rows(), tree_.spacing(), tree_.origin().x,
                                  tree_.origin().y));
  }
  // Each rectangle in root-grid points (inclusive). Padding points copy the nearest sample, so an
  // edit on the last column/row reaches the padding beyond it.
  const std::int64_t rn = tree_.root_intervals();
  std::vector<std::array<std::int64_t, 4>> edits;
  for (const SampleRect& r : rects) {
    const int x0 = std::max(r.x0, 0), z0 = std::max(r.z0, 0);
    const int x1 = std::min(r.x1, field.columns()), z1 = std::min(r.z1, field.rows());
    if (x0 >= x1 || z0 >= z1) continue;
    edits.push_back({x0, z0, x1 == field.columns() ? rn : x1 - 1, z1 == field.rows() ? rn : z1 - 1});
  }
  if (edits.empty()) return out;

  // The bake's own grids of the edited field (chunk_build.hpp); validates NaN/Inf.
  ChunkTreeSettings settings = tree_.settings();
  settings.keep_meshes = true;  // the rebuilt meshes are what the overlay is for
  auto grids = source_ ? updated_grids(*source_->grids, field, edits)
                       : ChunkTreeBuilder::prepare(HeightField(field), settings, {});
  if (!grids.ok()) return grids.error();

  // The chunks rebuild_region re-triangulates: the square grown by half a chunk meets an edit (a
  // point on a chunk edge has an error diamond reaching half a chunk into the neighbour, rtin.hpp).
  std::vector<std::uint32_t>& rebuild = out.rebuilt;
  for (std::uint32_t i = 0; i < tree_.chunk_count(); ++i) {
    const Chunk& c = tree_.chunk(i);
    if (!c.present) continue;
    const std::int64_t size = tree_.chunk_size(c.key.level), half = size / 2;
    const std::int64_t cx0 = static_cast<std::int64_t>(c.key.x) * size - half, cx1 = cx0 + size + 2 * half;
    const std::int64_t cz0 = static_cast<std::int64_t>(c.key.z) * size - half, cz1 = cz0 + size + 2 * half;
    for (const auto& e : edits) {
      if (cx0 <= e[2] && e[0] <= cx1 && cz0 <= e[3] && e[1] <= cz1) {
        rebuild.push_back(i);
        break;
      }
    }
  }
  std::vector<Chunk> built(rebuild.size());
  const TreeGrids& g = **grids;
  parallel_for(rebuild.size(), resolve_threads(settings.threads), [&](std::size_t k) {
    built[k] = g.tree.chunk(rebuild[k]);
    ChunkTreeBuilder::build_chunk(g, built[k]);
  });

  // Committed: metadata of the rebuilt chunks, then bounds, report and nodes of the whole tree.
  auto source = std::make_shared<RebuildSource>();
  source->grids = std::move(*grids);
  source->rebuilt = source_ ? source_->rebuilt : std::vector<std::uint8_t>(tree_.chunk_count(), 0);
  source->generation = generation() + 1;
  std::vector<std::shared_ptr<ChunkMesh>> fresh(rebuild.size());
  for (std::size_t k = 0; k < rebuild.size(); ++k) {
    fresh[k] = std::make_shared<ChunkMesh>(std::move(built[k].mesh));
    built[k].mesh = ChunkMesh{};
    ChunkTreeBuilder::chunk(tree_, rebuild[k]) = std::move(built[k]);
    rebuilt_count_ += source->rebuilt[rebuild[k]] ? 0 : 1;
    source->rebuilt[rebuild[k]] = 1;
  }
  source_ = std::move(source);
  ChunkTreeBuilder::finish(tree_);
  // A chunk read from the file later gets its exact height range when it is resolved; until then
  // its range must still hold its geometry, or the selection could cull it while it shows. Its
  // heights are the file's; its morph targets lie on coarser levels' surfaces, i.e. within the
  // range of the ancestor whose mesh is that surface there, which changed only if that ancestor
  // was rebuilt: widen by the rebuilt ancestors' ranges.
  std::vector<std::uint8_t> was_rebuilt(tree_.chunk_count(), 0);
  for (std::uint32_t i : rebuild) was_rebuilt[i] = 1;
  for (std::uint32_t i = 1; i < tree_.chunk_count(); ++i) {
    Chunk& c = ChunkTreeBuilder::chunk(tree_, i);
    if (!c.present || was_rebuilt[i]) continue;
    for (std::uint32_t a = tree_.parent_index(i);; a = tree_.parent_index(a)) {
      if (was_rebuilt[a]) {
        c.min_y = std::min(c.min_y, tree_.chunk(a).min_y);
        c.max_y = std::max(c.max_y, tree_.chunk(a).max_y);
      }
      if (a == 0) break;
    }
  }
  // This edit's meshes take their morph data (from the new grids and bounds); the caller
  // re-resolves the chunks it holds from earlier edits.
  for (std::size_t k = 0; k < rebuild.size(); ++k) {
    patch(rebuild[k], *fresh[k]);
    meshes[rebuild[k]] = std::move(fresh[k]);
  }
  ChunkTreeBuilder::finish(tree_);
  return out;
}

void StreamEdits::patch(std::uint32_t index, ChunkMesh& mesh) {
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  const TreeGrids& g = *source_->grids;
  for (ChunkVertex& v : mesh.vertices) {
    // The coarsest level holding the point follows the point's RTIN error, which an edit beyond
    // the chunk's reach can change (a coarse-grid corner's error gathers a wide diamond): taken
    // again, as the bake's build_chunk takes it (a chunk's own vertex set is unchanged: the points
    // a coarser level may drop lie within its reach).
    const Pt p{static_cast<std::int32_t>(v.gx), static_cast<std::int32_t>(v.gz)};
    v.intro_level = static_cast<std::uint8_t>(std::min(g.rule.intro_level(p), static_cast<int>(tree_.chunk(index).key.level)));
    v.morph_target = v.intro_level == 0 ? v.height
                                        : static_cast<float>(level_surface_height(g.rule, g.heights, v.intro_level - 1, p));
    v.morph_error = ChunkTreeBuilder::morph_error(tree_, v);
    lo = std::min({lo, v.height, v.morph_target});
    hi = std::max({hi, v.height, v.morph_target});
  }
  Chunk& c = ChunkTreeBuilder::chunk(tree_, index);
  if (!mesh.vertices.empty()) {
    c.min_y = lo;
    c.max_y = hi;
  }
}

std::shared_ptr<const ChunkMesh> StreamEdits::resolve(std::uint32_t index, std::shared_ptr<const ChunkMesh> mesh) {
  if (!source_ || !mesh) return mesh;
  auto copy = std::make_shared<ChunkMesh>(*mesh);
  patch(index, *copy);
  return copy;
}

void StreamEdits::refresh_nodes() { ChunkTreeBuilder::finish(tree_); }

}  // namespace sylva::terrain::detail
