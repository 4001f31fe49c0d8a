#include <sylva/terrain/chunk_tree.hpp>

#include "chunk_build.hpp"
#include "grid_tessellation.hpp"
#include "parallel.hpp"
#include "rtin.hpp"

#include <sylva/core/assert.hpp>
#include <sylva/core/log.hpp>
#include <sylva/core/timer.hpp>

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

namespace sylva::terrain {

using detail::ActiveRule;
using detail::ErrorGrid;
using detail::HeightGrid;
using detail::Pt;
using detail::Tri;

std::uint64_t BuildReport::triangles() const {
  std::uint64_t total = 0;
  for (const LevelReport& l : levels) total += l.triangles;
  return total;
}

std::string BuildReport::describe() const {
  std::string out = fmt::format("chunk tree built in {:.0f} ms on {} thread(s) (error grid {:.0f} ms, meshes {:.0f} ms), "
                                "{} triangles over {} levels",
                                total_ms, threads, error_grid_ms, meshes_ms, triangles(), levels.size());
  for (const LevelReport& l : levels) {
    out += fmt::format("\n  level {}: {} chunks, {} triangles ({:.1f} % of its grid), max error {:.3f} m", l.level,
                       l.chunks, l.triangles,
                       100.0 * static_cast<double>(l.triangles) / std::max<double>(1.0, static_cast<double>(l.grid_triangles)),
                       l.max_error);
  }
  return out;
}

std::uint32_t ChunkTree::index(int level, std::uint32_t x, std::uint32_t z) const {
  SYLVA_ASSERT(level >= 0 && level < levels_, "level={} levels={}", level, levels_);
  const std::uint32_t side = chunks_per_side(level);
  SYLVA_ASSERT(x < side && z < side, "chunk ({}, {}) outside level {} ({} per side)", x, z, level, side);
  return level_offset_[static_cast<std::size_t>(level)] + z * side + x;
}

const Chunk* ChunkTree::find(int level, std::int64_t x, std::int64_t z) const {
  if (level < 0 || level >= levels_) return nullptr;
  const std::int64_t side = chunks_per_side(level);
  if (x < 0 || z < 0 || x >= side || z >= side) return nullptr;
  const Chunk& c = chunks_[index(level, static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(z))];
  return c.present ? &c : nullptr;
}

std::uint32_t ChunkTree::parent_index(std::uint32_t idx) const {
  const ChunkKey& k = chunks_[idx].key;
  SYLVA_ASSERT(k.level > 0, "the root chunk has no parent");
  return index(k.level - 1, k.x / 2, k.z / 2);
}

std::array<std::uint32_t, 4> ChunkTree::child_indices(std::uint32_t idx) const {
  const ChunkKey& k = chunks_[idx].key;
  SYLVA_ASSERT(k.level + 1 < levels_, "chunk at level {} of {} has no children", k.level, levels_);
  const std::uint32_t x = k.x * 2, z = k.z * 2;
  return {index(k.level + 1, x, z), index(k.level + 1, x + 1, z), index(k.level + 1, x, z + 1),
          index(k.level + 1, x + 1, z + 1)};
}

void ChunkTree::compute_nodes() {
  nodes_.assign(chunks_.size(), ChunkNode{});
  for (std::uint32_t idx = 0; idx < chunks_.size(); ++idx) {
    const Chunk& c = chunks_[idx];
    ChunkNode& n = nodes_[idx];
    const std::uint32_t size = chunk_size(c.key.level);
    const double x0 = static_cast<double>(c.key.x) * size, z0 = static_cast<double>(c.key.z) * size;
    const double x1 = std::min(x0 + size, static_cast<double>(std::max(columns_ - 1, 0)));
    const double z1 = std::min(z0 + size, static_cast<double>(std::max(rows_ - 1, 0)));
    n.lo = glm::dvec3(origin_.x + x0 * spacing_, static_cast<double>(c.min_y), origin_.y + z0 * spacing_);
    n.hi = glm::dvec3(origin_.x + std::max(x1, x0) * spacing_, static_cast<double>(c.max_y),
                      origin_.y + std::max(z1, z0) * spacing_);
    n.error_bound = c.error_bound;
    n.parent_bound = c.key.level > 0 ? chunks_[parent_index(idx)].error_bound : c.error_bound;
    n.x = c.key.x;
    n.z = c.key.z;
    n.level = static_cast<std::uint8_t>(c.key.level);
    n.present = c.present ? 1 : 0;
  }
}

namespace {

bool is_pow2(std::uint32_t v) { return v != 0 && (v & (v - 1)) == 0; }

// Upper bound in float of a double (so a measured error stored as float never understates).
float round_up(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// The root grid's heights: the field with clamped padding.
HeightGrid padded_heights(const HeightField& field, std::uint32_t root_n, int threads) {
  HeightGrid hg;
  hg.n = static_cast<std::int32_t>(root_n);
  const std::size_t side = static_cast<std::size_t>(root_n) + 1;
  hg.h.resize(side * side);
  detail::parallel_for(side, threads, [&](std::size_t z) {
    const int fz = std::min(static_cast<int>(z), field.rows() - 1);
    for (std::size_t x = 0; x < side; ++x) {
      const int fx = std::min(static_cast<int>(x), field.columns() - 1);
      hg.h[z * side + x] = field.sample(fx, fz);
    }
  }, nullptr, 64);
  return hg;
}

// The padded grid from a field the caller gave up: the field is released as soon as its samples
// are in the grid (moved when it is exactly the root grid, as a 2^k+1 square is), so the error
// grid is allocated without a third full-size array alive (bake.hpp; 16k^2 fields).
HeightGrid take_padded_heights(HeightField&& field, std::uint32_t root_n, int threads) {
  HeightGrid hg;
  if (field.columns() == field.rows() && static_cast<std::uint32_t>(field.columns()) == root_n + 1) {
    hg.n = static_cast<std::int32_t>(root_n);
    hg.h = std::move(field.samples());
  } else {
    hg = padded_heights(field, root_n, threads);
  }
  field = HeightField{};
  return hg;
}

ActiveRule make_rule(const ErrorGrid& errors, int levels, std::uint32_t n, const ChunkTreeSettings& settings,
                     double spacing) {
  ActiveRule rule;
  rule.errors = &errors;
  rule.levels = levels;
  rule.leaf_n = static_cast<std::int32_t>(n);
  rule.eps.resize(static_cast<std::size_t>(levels));
  // Leaves keep every vertex that is not exactly interpolated (eps 0): nothing finer can be
  // selected when a leaf's projected error passes tau, so a reduced leaf would break the bound
  // for a camera close to the ground (README, "Meshes").
  for (int l = 0; l < levels; ++l) {
    const bool leaf = l + 1 == levels;
    rule.eps[static_cast<std::size_t>(l)] =
        leaf ? 0.0f : static_cast<float>(settings.flat_tolerance * spacing * static_cast<double>(rule.step(l)));
  }
  return rule;
}

struct ChunkBuildContext {
  const ChunkTree* tree;
  const HeightGrid* heights;
  const ActiveRule* rule;
  std::int32_t columns, rows;  // field samples
  bool keep_mesh;
  bool optimize;
};

void finish_chunk(const ChunkBuildContext& ctx, Chunk& chunk, ChunkMesh mesh, double max_err);

// Triangulates one chunk at its level, measures its error and fills its vertex data (except
// morph_error, which needs every chunk's error bound first).
void build_chunk(const ChunkBuildContext& ctx, Chunk& chunk) {
  const ChunkTree& tree = *ctx.tree;
  const ActiveRule& rule = *ctx.rule;
  const HeightGrid& hg = *ctx.heights;
  const int level = chunk.key.level;
  const std::int32_t size = static_cast<std::int32_t>(tree.chunk_size(level));
  const std::int32_t s = static_cast<std::int32_t>(tree.step(level));
  const std::int32_t n = static_cast<std::int32_t>(tree.leaf_intervals());
  const std::int32_t x0 = static_cast<std::int32_t>(chunk.key.x) * size;
  const std::int32_t z0 = static_cast<std::int32_t>(chunk.key.z) * size;
  const Tessellation tessellation = tree.settings().tessellation;
  if (tessellation != Tessellation::kRtin) {
    // The seed's full grids (seed 002 §3.3, hq 0/1/2).
    ChunkMesh mesh;
    const double err = detail::build_grid_chunk(
        {&hg, tessellation, level, tree.levels(), x0, z0, size, ctx.columns, ctx.rows}, mesh);
    finish_chunk(ctx, chunk, std::move(mesh), err);
    return;
  }

  thread_local std::vector<std::int32_t> local;
  thread_local std::vector<Tri> stack;
  local.assign(static_cast<std::size_t>((n + 1) * (n + 1)), -1);
  stack.clear();

  ChunkMesh mesh;
  auto vertex_of = [&](Pt p) -> std::uint32_t {
    const std::size_t li = static_cast<std::size_t>(((p.z - z0) / s) * (n + 1) + (p.x - x0) / s);
    if (local[li] < 0) {
      local[li] = static_cast<std::int32_t>(mesh.vertices.size());
      ChunkVertex v;
      v.gx = static_cast<std::uint32_t>(p.x);
      v.gz = static_cast<std::uint32_t>(p.z);
      v.height = hg.at(p);
      v.outside = (p.x > ctx.columns - 1 || p.z > ctx.rows - 1) ? 1 : 0;
      const int intro = rule.intro_level(p);
      SYLVA_ASSERT(intro <= level, "point ({}, {}) in a level-{} mesh is introduced at level {}", p.x, p.z,
                   level, intro);
      v.intro_level = static_cast<std::uint8_t>(intro);
      v.morph_target = intro == 0 ? v.height
                                  : static_cast<float>(detail::level_surface_height(rule, hg, intro - 1, p));
      mesh.vertices.push_back(v);
    }
    return static_cast<std::uint32_t>(local[li]);
  };

  double max_err = 0.0;
  const std::int32_t fx1 = ctx.columns - 1, fz1 = ctx.rows - 1;
  auto measure = [&](Pt p0, Pt p1, Pt p2) {
    const std::int32_t bx0 = std::max(std::min({p0.x, p1.x, p2.x}), 0);
    const std::int32_t bx1 = std::min(std::max({p0.x, p1.x, p2.x}), fx1);
    const std::int32_t bz0 = std::max(std::min({p0.z, p1.z, p2.z}), 0);
    const std::int32_t bz1 = std::min(std::max({p0.z, p1.z, p2.z}), fz1);
    if (bx0 > bx1 || bz0 > bz1) return;
    const double total = static_cast<double>(detail::area2(p0, p1, p2));
    const double h0 = hg.at(p0), h1 = hg.at(p1), h2 = hg.at(p2);
    for (std::int32_t z = bz0; z <= bz1; ++z) {
      for (std::int32_t x = bx0; x <= bx1; ++x) {
        const Pt q{x, z};
        const std::int64_t w0 = detail::area2(q, p1, p2);
        const std::int64_t w1 = detail::area2(p0, q, p2);
        const std::int64_t w2 = detail::area2(p0, p1, q);
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const double v = (static_cast<double>(w0) * h0 + static_cast<double>(w1) * h1 +
                          static_cast<double>(w2) * h2) / total;
        max_err = std::max(max_err, std::fabs(v - static_cast<double>(hg.at(q))));
      }
    }
  };

  Tri roots[2];
  detail::square_triangles(x0, z0, size, chunk.key.x, chunk.key.z, roots);
  stack.push_back(roots[0]);
  stack.push_back(roots[1]);
  while (!stack.empty()) {
    const Tri t = stack.back();
    stack.pop_back();
    const bool even = ((t.a.x - t.b.x) % 2 == 0) && ((t.a.z - t.b.z) % 2 == 0);
    if (even) {
      const Pt m = detail::midpoint(t.a, t.b);
      if (rule.active(m, level)) {
        stack.push_back(Tri{t.c, t.a, m});
        stack.push_back(Tri{t.b, t.c, m});
        continue;
      }
    }
    Pt p0 = t.a, p1 = t.b, p2 = t.c;
    if (detail::area2(p0, p1, p2) < 0) std::swap(p1, p2);
    mesh.indices.push_back(vertex_of(p0));
    mesh.indices.push_back(vertex_of(p1));
    mesh.indices.push_back(vertex_of(p2));
    measure(p0, p1, p2);
  }
  finish_chunk(ctx, chunk, std::move(mesh), max_err);
}

// Error, counts, height range and (kept meshes) vertex-cache order and edge lists of a chunk whose
// triangles and vertices are made.
void finish_chunk(const ChunkBuildContext& ctx, Chunk& chunk, ChunkMesh mesh, double max_err) {
  const ChunkTree& tree = *ctx.tree;
  const std::int32_t size = static_cast<std::int32_t>(tree.chunk_size(chunk.key.level));
  const std::int32_t x0 = static_cast<std::int32_t>(chunk.key.x) * size;
  const std::int32_t z0 = static_cast<std::int32_t>(chunk.key.z) * size;
  chunk.error = round_up(max_err);
  chunk.triangle_count = static_cast<std::uint32_t>(mesh.indices.size() / 3);
  chunk.vertex_count = static_cast<std::uint32_t>(mesh.vertices.size());
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (const ChunkVertex& v : mesh.vertices) {
    lo = std::min({lo, v.height, v.morph_target});
    hi = std::max({hi, v.height, v.morph_target});
  }
  chunk.min_y = lo;
  chunk.max_y = hi;
  if (!ctx.keep_mesh) return;

  if (ctx.optimize) {
    std::vector<std::uint32_t> optimized(mesh.indices.size());
    meshopt_optimizeVertexCache(optimized.data(), mesh.indices.data(), mesh.indices.size(), mesh.vertices.size());
    std::vector<std::uint32_t> remap(mesh.vertices.size());
    const std::size_t unique = meshopt_optimizeVertexFetchRemap(remap.data(), optimized.data(), optimized.size(),
                                                                 mesh.vertices.size());
    SYLVA_ASSERT(unique == mesh.vertices.size(), "every chunk vertex is referenced ({} of {})", unique,
                 mesh.vertices.size());
    std::vector<ChunkVertex> vertices(unique);
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) vertices[remap[i]] = mesh.vertices[i];
    for (std::uint32_t& i : optimized) i = remap[i];
    mesh.vertices = std::move(vertices);
    mesh.indices = std::move(optimized);
  }

  const std::int32_t x1 = x0 + size, z1 = z0 + size;
  for (std::uint32_t i = 0; i < mesh.vertices.size(); ++i) {
    const ChunkVertex& v = mesh.vertices[i];
    if (v.centre != 0) continue;  // inside a leaf square (hq2), never on an edge
    const std::int32_t x = static_cast<std::int32_t>(v.gx), z = static_cast<std::int32_t>(v.gz);
    if (x == x0) mesh.edges[kWest].push_back(i);
    if (x == x1) mesh.edges[kEast].push_back(i);
    if (z == z0) mesh.edges[kSouth].push_back(i);
    if (z == z1) mesh.edges[kNorth].push_back(i);
  }
  auto by_z = [&](std::uint32_t a, std::uint32_t b) { return mesh.vertices[a].gz < mesh.vertices[b].gz; };
  auto by_x = [&](std::uint32_t a, std::uint32_t b) { return mesh.vertices[a].gx < mesh.vertices[b].gx; };
  std::sort(mesh.edges[kWest].begin(), mesh.edges[kWest].end(), by_z);
  std::sort(mesh.edges[kEast].begin(), mesh.edges[kEast].end(), by_z);
  std::sort(mesh.edges[kSouth].begin(), mesh.edges[kSouth].end(), by_x);
  std::sort(mesh.edges[kNorth].begin(), mesh.edges[kNorth].end(), by_x);
  chunk.mesh = std::move(mesh);
}

}  // namespace

Result<ChunkTree> ChunkTree::build(const HeightField& field, const ChunkTreeSettings& settings,
                                   const BuildControl& control) {
  return ChunkTreeBuilder::build(field, settings, control);
}

Result<ChunkTree> ChunkTreeBuilder::layout(int columns, int rows, double spacing, glm::dvec2 origin,
                                           const ChunkTreeSettings& settings) {
  SYLVA_TRY(validate_params(settings, "terrain.tree"));
  const std::uint32_t n = static_cast<std::uint32_t>(settings.leaf_dimension - 1);
  if (!is_pow2(n)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("terrain.tree.leaf_dimension: {} is not 2^k+1 (e.g. 17, 33, 65)",
                                  settings.leaf_dimension));
  }
  ChunkTree tree;
  tree.settings_ = settings;
  tree.n_ = n;
  tree.columns_ = columns;
  tree.rows_ = rows;
  tree.spacing_ = spacing;
  tree.origin_ = origin;
  const std::uint32_t need = static_cast<std::uint32_t>(std::max(columns, rows) - 1);
  int levels = 1;
  while ((static_cast<std::uint64_t>(n) << (levels - 1)) < need) ++levels;
  tree.levels_ = levels;
  tree.root_n_ = n << (levels - 1);
  const double grid_points = std::pow(static_cast<double>(tree.root_n_) + 1.0, 2.0);
  if (grid_points * 8.0 > settings.max_build_bytes || tree.root_n_ > (1u << 20)) {
    return make_error(ErrorCode::kLimit,
                      fmt::format("terrain: a {}x{} field needs a {}^2 build grid ({:.2f} GB), above "
                                  "terrain.tree.max_build_bytes = {:.2f} GB",
                                  columns, rows, tree.root_n_ + 1, grid_points * 8.0 / 1e9,
                                  settings.max_build_bytes / 1e9));
  }
  // Chunk slots for every level; presence: the chunk's low corner lies inside the field extent
  // (or on the field's first row/column, so a 1-sample-wide field still has its chunks).
  std::uint32_t offset = 0;
  for (int l = 0; l < levels; ++l) {
    tree.level_offset_.push_back(offset);
    offset += (1u << l) * (1u << l);
  }
  tree.chunks_.resize(offset);
  for (int l = 0; l < levels; ++l) {
    const std::uint32_t side_chunks = 1u << l, size = tree.chunk_size(l);
    for (std::uint32_t z = 0; z < side_chunks; ++z) {
      for (std::uint32_t x = 0; x < side_chunks; ++x) {
        Chunk& c = tree.chunks_[tree.index(l, x, z)];
        c.key = ChunkKey{l, x, z};
        const std::int64_t x0 = static_cast<std::int64_t>(x) * size, z0 = static_cast<std::int64_t>(z) * size;
        c.present = (x0 == 0 || x0 < columns - 1) && (z0 == 0 || z0 < rows - 1);
      }
    }
  }
  return tree;
}

Result<std::unique_ptr<detail::TreeGrids>> ChunkTreeBuilder::prepare(HeightField&& field,
                                                                     const ChunkTreeSettings& settings,
                                                                     const BuildControl& control) {
  SYLVA_TRY(validate_params(settings, "terrain.tree"));
  if (field.columns() < 1 || field.rows() < 1 ||
      field.samples().size() != static_cast<std::size_t>(field.columns()) * static_cast<std::size_t>(field.rows())) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("terrain: the height field is empty ({}x{} samples)", field.columns(), field.rows()));
  }
  if (!(field.spacing() > 0.0) || !std::isfinite(field.spacing())) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("terrain: height field spacing {} m is not a positive finite number", field.spacing()));
  }
  {
    std::size_t bad = 0, first = 0;
    const auto& s = field.samples();
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (!std::isfinite(s[i])) {
        if (bad == 0) first = i;
        ++bad;
      }
    }
    if (bad > 0) {
      const std::size_t cols = static_cast<std::size_t>(field.columns());
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("terrain: the height field has {} NaN/Inf sample(s), the first at column {} row {} "
                                    "(load with non_finite = repair to replace them)",
                                    bad, first % cols, first / cols));
    }
  }
  auto grids = std::make_unique<detail::TreeGrids>();
  {
    Result<ChunkTree> tree = layout(field.columns(), field.rows(), field.spacing(), field.origin(), settings);
    if (!tree) return tree.error();
    grids->tree = std::move(tree.value());
  }
  ChunkTree& tree = grids->tree;
  const int threads = detail::resolve_threads(settings.threads);
  tree.report_.threads = threads;

  // Padded height grid.
  Stopwatch watch;
  const double spacing = field.spacing();
  grids->heights = take_padded_heights(std::move(field), tree.root_n_, threads);
  grids->errors = detail::compute_errors(grids->heights, threads);
  tree.report_.error_grid_ms = watch.lap_ms();
  if (control.cancel != nullptr && control.cancel->load()) {
    return make_error(ErrorCode::kCancelled, "terrain: chunk tree build cancelled");
  }
  grids->rule = make_rule(grids->errors, tree.levels_, tree.n_, settings, spacing);
  for (std::uint32_t i = 0; i < tree.chunks_.size(); ++i)
    if (tree.chunks_[i].present) grids->present.push_back(i);
  return grids;
}

void ChunkTreeBuilder::build_chunk(const detail::TreeGrids& grids, Chunk& chunk) {
  const ChunkTree& tree = grids.tree;
  const ChunkBuildContext ctx{&tree, &grids.heights, &grids.rule, tree.columns_, tree.rows_,
                              tree.settings_.keep_meshes, tree.settings_.optimize_vertex_cache};
  sylva::terrain::build_chunk(ctx, chunk);
}

void ChunkTreeBuilder::finish(ChunkTree& tree) {
  tree.compute_error_bounds();
  tree.fill_level_report();
  tree.compute_nodes();
}

Result<ChunkTree> ChunkTreeBuilder::build(const HeightField& field, const ChunkTreeSettings& settings,
                                          const BuildControl& control) {
  Stopwatch total_watch;
  // A copy for prepare to consume: the caller keeps its field (memory as before: the copy becomes
  // the padded grid, or is released before the error grid is allocated).
  Result<std::unique_ptr<detail::TreeGrids>> prepared = prepare(HeightField(field), settings, control);
  if (!prepared) return prepared.error();
  std::unique_ptr<detail::TreeGrids>& grids = prepared.value();
  // Chunks are built in place: each call writes only its own slot and reads the tree's geometry.
  ChunkTree& tree = grids->tree;
  const int threads = tree.report_.threads;
  const std::vector<std::uint32_t>& present = grids->present;
  Stopwatch watch;

  std::atomic<std::size_t> done{0};
  std::mutex progress_mutex;
  const bool finished = detail::parallel_for(present.size(), threads, [&](std::size_t i) {
    build_chunk(*grids, tree.chunks_[present[i]]);
    const std::size_t d = ++done;
    if (control.progress && (d % 64 == 0 || d == present.size())) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      control.progress(0.05f + 0.9f * static_cast<float>(d) / static_cast<float>(present.size()));
    }
  }, control.cancel);
  if (!finished) return make_error(ErrorCode::kCancelled, "terrain: chunk tree build cancelled");

  tree.compute_error_bounds();

  // Morph error of each vertex: the smallest error bound among the coarser chunks containing it,
  // so the vertex has reached the coarser surface whichever of them is selected first.
  if (settings.keep_meshes) {
    detail::parallel_for(present.size(), threads, [&](std::size_t i) {
      Chunk& c = tree.chunks_[present[i]];
      for (ChunkVertex& v : c.mesh.vertices) v.morph_error = tree.morph_error_of(v);
    }, control.cancel);
  }
  tree.report_.meshes_ms = watch.lap_ms();

  tree.fill_level_report();
  tree.compute_nodes();
  tree.report_.total_ms = total_watch.elapsed_ms();
  if (control.progress) control.progress(1.0f);
  return std::move(tree);
}


void ChunkTree::compute_error_bounds() {
  // Monotone error bounds, finest level first.
  const double growth = 1.0 / (1.0 - static_cast<double>(settings_.max_morph_fraction));
  for (int l = levels_ - 1; l >= 0; --l) {
    for (std::uint32_t i = level_offset_[static_cast<std::size_t>(l)];
         i < level_offset_[static_cast<std::size_t>(l)] + (1u << l) * (1u << l); ++i) {
      Chunk& c = chunks_[i];
      if (!c.present) continue;
      double bound = c.error;
      if (l + 1 < levels_) {
        for (std::uint32_t ci : child_indices(i)) {
          const Chunk& child = chunks_[ci];
          if (child.present) bound = std::max(bound, growth * child.error_bound);
        }
      }
      c.error_bound = round_up(bound);
    }
  }
}

// Morph error of a vertex: the smallest error bound among the coarser chunks containing it, so
// the vertex has reached the coarser surface whichever of them is selected first.
float ChunkTree::morph_error_of(const ChunkVertex& v) const {
  if (v.intro_level == 0) return 0.0f;
  const int pl = v.intro_level - 1;
  const std::uint32_t size = chunk_size(pl);
  float best = std::numeric_limits<float>::infinity();
  for (int dz = 0; dz < 2; ++dz) {
    for (int dx = 0; dx < 2; ++dx) {
      if (dx == 1 && (v.gx % size != 0)) continue;
      if (dz == 1 && (v.gz % size != 0)) continue;
      std::int64_t cx = v.gx / size - dx, cz = v.gz / size - dz;
      const std::int64_t side_chunks = chunks_per_side(pl);
      if (cx == side_chunks) continue;  // on the root's far edge: only the chunk below counts
      if (cz == side_chunks) continue;
      if (const Chunk* pc = find(pl, cx, cz)) best = std::min(best, pc->error_bound);
    }
  }
  SYLVA_ASSERT(std::isfinite(best), "vertex ({}, {}) of level {} has no coarser chunk", v.gx, v.gz, pl + 1);
  return best;
}

void ChunkTree::fill_level_report() {
  report_.levels.assign(static_cast<std::size_t>(levels_), LevelReport{});
  for (int l = 0; l < levels_; ++l) report_.levels[static_cast<std::size_t>(l)].level = l;
  for (const Chunk& c : chunks_) {
    if (!c.present) continue;
    LevelReport& r = report_.levels[static_cast<std::size_t>(c.key.level)];
    ++r.chunks;
    r.triangles += c.triangle_count;
    // The level's full grid: 2 triangles per square, 4 with the seed's hq2 centres.
    r.grid_triangles += (settings_.tessellation == Tessellation::kHq2 ? 4ull : 2ull) * n_ * n_;
    r.max_error = std::max(r.max_error, c.error);
  }
}

Result<RegionRebuild> ChunkTree::rebuild_region(const HeightField& field, int x0, int z0, int x1, int z1) {
  Stopwatch watch;
  RegionRebuild out;
  if (!settings_.keep_meshes) {
    return make_error(ErrorCode::kInvalidArgument,
                      "terrain.tree.keep_meshes: rebuild_region needs the chunk meshes (keep_meshes = true)");
  }
  if (settings_.tessellation != Tessellation::kRtin) {
    return make_error(ErrorCode::kInvalidArgument,
                      "terrain.tree.tessellation: rebuild_region updates RTIN trees only; rebuild the whole tree");
  }
  if (field.columns() != columns_ || field.rows() != rows_ || field.spacing() != spacing_ ||
      field.origin() != origin_ ||
      field.samples().size() != static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("terrain: rebuild_region got a {}x{} field (spacing {} m), the tree was built from "
                                  "{}x{} (spacing {} m); rebuild the whole tree instead",
                                  field.columns(), field.rows(), field.spacing(), columns_, rows_, spacing_));
  }
  x0 = std::max(x0, 0);
  z0 = std::max(z0, 0);
  x1 = std::min(x1, columns_);
  z1 = std::min(z1, rows_);
  if (x0 >= x1 || z0 >= z1) return out;
  for (std::size_t i = static_cast<std::size_t>(z0) * static_cast<std::size_t>(columns_);
       i < static_cast<std::size_t>(z1) * static_cast<std::size_t>(columns_); ++i) {
    if (!std::isfinite(field.samples()[i])) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("terrain: the edited height field has a NaN/Inf sample at column {} row {}",
                                    i % static_cast<std::size_t>(columns_), i / static_cast<std::size_t>(columns_)));
    }
  }
  // The edited rectangle in root-grid points (inclusive). Padding points copy the nearest field
  // sample, so an edit touching the last column/row also changes the padding beyond it.
  const std::int64_t rn = root_n_;
  const std::int64_t ex0 = x0, ez0 = z0;
  const std::int64_t ex1 = (x1 == columns_) ? rn : x1 - 1;
  const std::int64_t ez1 = (z1 == rows_) ? rn : z1 - 1;
  auto dist = [&](std::int64_t gx, std::int64_t gz) {  // Chebyshev distance from a point to the edit
    const std::int64_t dx = gx < ex0 ? ex0 - gx : (gx > ex1 ? gx - ex1 : 0);
    const std::int64_t dz = gz < ez0 ? ez0 - gz : (gz > ez1 ? gz - ez1 : 0);
    return std::max(dx, dz);
  };

  const int threads = detail::resolve_threads(settings_.threads);
  HeightGrid hg = padded_heights(field, root_n_, threads);
  // The whole error grid is recomputed (O(N^2), a few ms for 257^2) rather than kept: keeping
  // it would double the tree's memory for every terrain that is never edited.
  const ErrorGrid errors = detail::compute_errors(hg, threads);
  const ActiveRule rule = make_rule(errors, levels_, n_, settings_, spacing_);

  // Chunks whose mesh, heights or measured error can change: a chunk's mesh is decided by the
  // errors of the points in its square, and a point on the square's edge has a diamond reaching
  // half a chunk into the neighbour (rtin.hpp), so the square grown by size / 2 must meet the edit.
  std::vector<std::uint32_t> rebuild;
  std::vector<std::uint8_t> rebuilt_flag(chunks_.size(), 0);
  for (std::uint32_t i = 0; i < chunks_.size(); ++i) {
    const Chunk& c = chunks_[i];
    if (!c.present) continue;
    const std::int64_t size = chunk_size(c.key.level), half = size / 2;
    const std::int64_t cx0 = static_cast<std::int64_t>(c.key.x) * size - half, cx1 = cx0 + size + 2 * half;
    const std::int64_t cz0 = static_cast<std::int64_t>(c.key.z) * size - half, cz1 = cz0 + size + 2 * half;
    if (cx0 <= ex1 && ex0 <= cx1 && cz0 <= ez1 && ez0 <= cz1) {
      rebuild.push_back(i);
      rebuilt_flag[i] = 1;
    }
  }
  ChunkBuildContext ctx{this, &hg, &rule, columns_, rows_, settings_.keep_meshes, settings_.optimize_vertex_cache};
  detail::parallel_for(rebuild.size(), threads, [&](std::size_t i) {
    Chunk& c = chunks_[rebuild[i]];
    c.mesh = ChunkMesh{};
    build_chunk(ctx, c);
  });
  out.rebuilt = rebuild;

  // Monotone bounds over the whole tree (O(chunks)): an edit may raise or lower any ancestor's.
  compute_error_bounds();

  // Morph data of the chunks not rebuilt: morph_target is the coarser level's surface, which
  // depends on points within chunk_size(intro - 1) of the vertex (the level's quadrant grown by
  // half a quadrant); morph_error follows the coarser chunks' bounds, which may change anywhere.
  // The intro level itself follows the point's RTIN error, which gathers the point's whole
  // triangle and so can change by an edit far beyond the chunk's reach: it is taken again for
  // every vertex (as the streamed edit's patch does), and with it the morph target.
  std::vector<std::uint8_t> updated_flag(chunks_.size(), 0);
  std::vector<std::uint32_t> present;
  for (std::uint32_t i = 0; i < chunks_.size(); ++i)
    if (chunks_[i].present) present.push_back(i);
  detail::parallel_for(present.size(), threads, [&](std::size_t k) {
    const std::uint32_t i = present[k];
    Chunk& c = chunks_[i];
    bool changed = false;
    for (ChunkVertex& v : c.mesh.vertices) {
      const Pt p{static_cast<std::int32_t>(v.gx), static_cast<std::int32_t>(v.gz)};
      const auto intro = static_cast<std::uint8_t>(std::min(rule.intro_level(p), static_cast<int>(c.key.level)));
      if (!rebuilt_flag[i] && intro != v.intro_level) {
        v.intro_level = intro;
        v.morph_target =
            intro == 0 ? v.height : static_cast<float>(detail::level_surface_height(rule, hg, intro - 1, p));
        changed = true;
      } else if (!rebuilt_flag[i] && v.intro_level > 0 &&
                 dist(v.gx, v.gz) <= static_cast<std::int64_t>(chunk_size(v.intro_level - 1))) {
        const float t = static_cast<float>(detail::level_surface_height(
            rule, hg, v.intro_level - 1, Pt{static_cast<std::int32_t>(v.gx), static_cast<std::int32_t>(v.gz)}));
        if (t != v.morph_target) {
          v.morph_target = t;
          changed = true;
        }
      }
      const float e = morph_error_of(v);
      if (e != v.morph_error) {
        v.morph_error = e;
        changed = true;
      }
    }
    if (changed && !rebuilt_flag[i]) {
      float lo = std::numeric_limits<float>::infinity(), hi = -lo;
      for (const ChunkVertex& v : c.mesh.vertices) {
        lo = std::min({lo, v.height, v.morph_target});
        hi = std::max({hi, v.height, v.morph_target});
      }
      c.min_y = lo;
      c.max_y = hi;
      updated_flag[i] = 1;
    }
  });
  for (std::uint32_t i : present)
    if (updated_flag[i]) out.updated.push_back(i);
  for (std::uint32_t i = 0; i < chunks_.size(); ++i)
    if (!rebuilt_flag[i] && !updated_flag[i] && nodes_[i].error_bound != chunks_[i].error_bound) out.bounds_only.push_back(i);
  fill_level_report();
  compute_nodes();
  out.ms = watch.elapsed_ms();
  return out;
}

}  // namespace sylva::terrain
