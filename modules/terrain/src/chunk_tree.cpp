#include <sylva/terrain/chunk_tree.hpp>

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

// Builds a ChunkTree; a friend so it can fill the private members.
class ChunkTreeBuilder {
 public:
  static Result<ChunkTree> build(const HeightField& field, const ChunkTreeSettings& settings,
                                 const BuildControl& control);
};

namespace {

bool is_pow2(std::uint32_t v) { return v != 0 && (v & (v - 1)) == 0; }

// Upper bound in float of a double (so a measured error stored as float never understates).
float round_up(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

struct ChunkBuildContext {
  const ChunkTree* tree;
  const HeightGrid* heights;
  const ActiveRule* rule;
  std::int32_t columns, rows;  // field samples
  bool keep_mesh;
  bool optimize;
};

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

Result<ChunkTree> ChunkTreeBuilder::build(const HeightField& field, const ChunkTreeSettings& settings,
                                          const BuildControl& control) {
  Stopwatch total_watch;
  SYLVA_TRY(validate_params(settings, "terrain.tree"));
  const std::uint32_t n = static_cast<std::uint32_t>(settings.leaf_dimension - 1);
  if (!is_pow2(n)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("terrain.tree.leaf_dimension: {} is not 2^k+1 (e.g. 17, 33, 65)",
                                  settings.leaf_dimension));
  }
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

  ChunkTree tree;
  tree.settings_ = settings;
  tree.n_ = n;
  tree.columns_ = field.columns();
  tree.rows_ = field.rows();
  tree.spacing_ = field.spacing();
  tree.origin_ = field.origin();
  const std::uint32_t need = static_cast<std::uint32_t>(std::max(field.columns(), field.rows()) - 1);
  int levels = 1;
  while ((static_cast<std::uint64_t>(n) << (levels - 1)) < need) ++levels;
  tree.levels_ = levels;
  tree.root_n_ = n << (levels - 1);
  const double grid_points = std::pow(static_cast<double>(tree.root_n_) + 1.0, 2.0);
  if (grid_points * 8.0 > settings.max_build_bytes || tree.root_n_ > (1u << 20)) {
    return make_error(ErrorCode::kLimit,
                      fmt::format("terrain: a {}x{} field needs a {}^2 build grid ({:.2f} GB), above "
                                  "terrain.tree.max_build_bytes = {:.2f} GB",
                                  field.columns(), field.rows(), tree.root_n_ + 1, grid_points * 8.0 / 1e9,
                                  settings.max_build_bytes / 1e9));
  }
  const int threads = detail::resolve_threads(settings.threads);
  tree.report_.threads = threads;

  // Padded height grid.
  Stopwatch watch;
  HeightGrid hg;
  hg.n = static_cast<std::int32_t>(tree.root_n_);
  const std::size_t side = static_cast<std::size_t>(tree.root_n_) + 1;
  hg.h.resize(side * side);
  detail::parallel_for(side, threads, [&](std::size_t z) {
    const int fz = std::min(static_cast<int>(z), field.rows() - 1);
    for (std::size_t x = 0; x < side; ++x) {
      const int fx = std::min(static_cast<int>(x), field.columns() - 1);
      hg.h[z * side + x] = field.sample(fx, fz);
    }
  }, nullptr, 64);
  const ErrorGrid errors = detail::compute_errors(hg, threads);
  tree.report_.error_grid_ms = watch.lap_ms();
  if (control.cancel != nullptr && control.cancel->load()) {
    return make_error(ErrorCode::kCancelled, "terrain: chunk tree build cancelled");
  }

  ActiveRule rule;
  rule.errors = &errors;
  rule.levels = levels;
  rule.leaf_n = static_cast<std::int32_t>(n);
  rule.eps.resize(static_cast<std::size_t>(levels));
  for (int l = 0; l < levels; ++l) {
    rule.eps[static_cast<std::size_t>(l)] =
        static_cast<float>(settings.flat_tolerance * field.spacing() * static_cast<double>(rule.step(l)));
  }

  // Chunk slots for every level; presence: the chunk's low corner lies inside the field extent
  // (or on the field's first row/column, so a 1-sample-wide field still has its chunks).
  std::uint32_t offset = 0;
  for (int l = 0; l < levels; ++l) {
    tree.level_offset_.push_back(offset);
    offset += (1u << l) * (1u << l);
  }
  tree.chunks_.resize(offset);
  std::vector<std::uint32_t> present;
  for (int l = 0; l < levels; ++l) {
    const std::uint32_t side_chunks = 1u << l, size = tree.chunk_size(l);
    for (std::uint32_t z = 0; z < side_chunks; ++z) {
      for (std::uint32_t x = 0; x < side_chunks; ++x) {
        Chunk& c = tree.chunks_[tree.index(l, x, z)];
        c.key = ChunkKey{l, x, z};
        const std::int64_t x0 = static_cast<std::int64_t>(x) * size, z0 = static_cast<std::int64_t>(z) * size;
        c.present = (x0 == 0 || x0 < field.columns() - 1) && (z0 == 0 || z0 < field.rows() - 1);
        if (c.present) present.push_back(tree.index(l, x, z));
      }
    }
  }

  ChunkBuildContext ctx{&tree, &hg, &rule, field.columns(), field.rows(), settings.keep_meshes,
                        settings.optimize_vertex_cache};
  std::atomic<std::size_t> done{0};
  std::mutex progress_mutex;
  const bool finished = detail::parallel_for(present.size(), threads, [&](std::size_t i) {
    build_chunk(ctx, tree.chunks_[present[i]]);
    const std::size_t d = ++done;
    if (control.progress && (d % 64 == 0 || d == present.size())) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      control.progress(0.05f + 0.9f * static_cast<float>(d) / static_cast<float>(present.size()));
    }
  }, control.cancel);
  if (!finished) return make_error(ErrorCode::kCancelled, "terrain: chunk tree build cancelled");

  // Monotone error bounds, finest level first.
  const double growth = 1.0 / (1.0 - static_cast<double>(settings.max_morph_fraction));
  for (int l = levels - 1; l >= 0; --l) {
    for (std::uint32_t i = tree.level_offset_[static_cast<std::size_t>(l)];
         i < tree.level_offset_[static_cast<std::size_t>(l)] + (1u << l) * (1u << l); ++i) {
      Chunk& c = tree.chunks_[i];
      if (!c.present) continue;
      double bound = c.error;
      if (l + 1 < levels) {
        for (std::uint32_t ci : tree.child_indices(i)) {
          const Chunk& child = tree.chunks_[ci];
          if (child.present) bound = std::max(bound, growth * child.error_bound);
        }
      }
      c.error_bound = round_up(bound);
    }
  }

  // Morph error of each vertex: the smallest error bound among the coarser chunks containing it,
  // so the vertex has reached the coarser surface whichever of them is selected first.
  if (settings.keep_meshes) {
    detail::parallel_for(present.size(), threads, [&](std::size_t i) {
      Chunk& c = tree.chunks_[present[i]];
      for (ChunkVertex& v : c.mesh.vertices) {
        if (v.intro_level == 0) {
          v.morph_error = 0.0f;
          continue;
        }
        const int pl = v.intro_level - 1;
        const std::uint32_t size = tree.chunk_size(pl);
        float best = std::numeric_limits<float>::infinity();
        for (int dz = 0; dz < 2; ++dz) {
          for (int dx = 0; dx < 2; ++dx) {
            if (dx == 1 && (v.gx % size != 0)) continue;
            if (dz == 1 && (v.gz % size != 0)) continue;
            std::int64_t cx = v.gx / size - dx, cz = v.gz / size - dz;
            const std::int64_t side_chunks = tree.chunks_per_side(pl);
            if (cx == side_chunks) continue;  // on the root's far edge: only the chunk below counts
            if (cz == side_chunks) continue;
            if (const Chunk* pc = tree.find(pl, cx, cz)) best = std::min(best, pc->error_bound);
          }
        }
        SYLVA_ASSERT(std::isfinite(best), "vertex ({}, {}) of level {} has no coarser chunk", v.gx, v.gz, pl + 1);
        v.morph_error = best;
      }
    }, control.cancel);
  }
  tree.report_.meshes_ms = watch.lap_ms();

  tree.report_.levels.resize(static_cast<std::size_t>(levels));
  for (int l = 0; l < levels; ++l) tree.report_.levels[static_cast<std::size_t>(l)].level = l;
  for (std::uint32_t i : present) {
    const Chunk& c = tree.chunks_[i];
    LevelReport& r = tree.report_.levels[static_cast<std::size_t>(c.key.level)];
    ++r.chunks;
    r.triangles += c.triangle_count;
    r.grid_triangles += 2ull * n * n;
    r.max_error = std::max(r.max_error, c.error);
  }
  tree.compute_nodes();
  tree.report_.total_ms = total_watch.elapsed_ms();
  if (control.progress) control.progress(1.0f);
  return tree;
}

}  // namespace sylva::terrain
