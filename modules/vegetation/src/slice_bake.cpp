#include <sylva/vegetation/slice_bake.hpp>

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/cache_directory.hpp>
#include <sylva/core/log.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/saved_target_state.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/vegetation/animation.hpp>
#include <sylva/vegetation/tree_renderer.hpp>

#include "tree_asset_access.hpp"

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

namespace sylva::render::embedded {
void register_vegetation_shaders();
}  // namespace sylva::render::embedded

namespace sylva::vegetation {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr char kMagic[8] = {'S', 'Y', 'L', 'V', 'S', 'L', 'C', 'E'};
constexpr std::uint32_t kFormatVersion = 2;  // 2: leaves baked with the hashed alpha test

// Writes uncovered texels of one slice from their nearest covered texel.
void propagate_slice(SliceImages& im, int slice, const std::vector<std::int32_t>& nearest) {
  const std::size_t n = static_cast<std::size_t>(im.resolution) * static_cast<std::size_t>(im.resolution);
  const std::size_t base = static_cast<std::size_t>(slice) * n;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t t = base + i;
    if (im.branch[t * 4 + 3] > 0.5f) continue;
    const std::int32_t src = nearest[i];
    if (src < 0) {
      // An empty slice: the first root's motion, transparent.
      im.branch[t * 4 + 0] = -1.0f;
      im.branch[t * 4 + 3] = -1.0f;
      continue;
    }
    const std::size_t s = base + static_cast<std::size_t>(src);
    for (int c = 0; c < 3; ++c) {
      im.color[t * 4 + static_cast<std::size_t>(c)] = im.color[s * 4 + static_cast<std::size_t>(c)];
      im.branch[t * 4 + static_cast<std::size_t>(c)] = im.branch[s * 4 + static_cast<std::size_t>(c)];
    }
    im.color[t * 4 + 3] = 0;
    for (int c = 0; c < 4; ++c) im.normal[t * 4 + static_cast<std::size_t>(c)] = im.normal[s * 4 + static_cast<std::size_t>(c)];
    im.depth[t] = im.depth[s];
    im.branch[t * 4 + 3] = -im.branch[s * 4 + 3];  // the root + 1, negative: propagated
  }
}

template <class T>
void append(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}
template <class T>
void append_vec(std::string& out, const std::vector<T>& v) {
  out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

struct Reader {
  const std::string& bytes;
  std::size_t pos = 0;
  template <class T>
  bool get(T& v) {
    if (pos + sizeof(T) > bytes.size()) return false;
    std::memcpy(&v, bytes.data() + pos, sizeof(T));
    pos += sizeof(T);
    return true;
  }
  template <class T>
  bool get_vec(std::vector<T>& v, std::size_t count) {
    if (count > (bytes.size() - pos) / sizeof(T)) return false;
    v.resize(count);
    std::memcpy(v.data(), bytes.data() + pos, count * sizeof(T));
    pos += count * sizeof(T);
    return true;
  }
};

std::uint64_t hash_image(const Image& img, std::uint64_t h) {
  const int dims[3] = {img.width(), img.height(), img.channels()};
  h = fnv1a64(dims, sizeof(dims), h);
  return fnv1a64(img.data().data(), img.data().size_bytes(), h);
}

}  // namespace

float SliceLayout::angle(int j) const { return static_cast<float>(static_cast<double>(j) * kPi / static_cast<double>(directions)); }
glm::vec3 SliceLayout::axis(int j) const { return {std::cos(angle(j)), 0.0f, -std::sin(angle(j))}; }
glm::vec3 SliceLayout::normal(int j) const { return {std::sin(angle(j)), 0.0f, std::cos(angle(j))}; }
float SliceLayout::layer_offset(int i) const { return -radius + (static_cast<float>(i) + 0.5f) * thickness(); }

glm::mat4 SliceLayout::bake_matrix(int j, int i) const {
  const glm::vec3 a = axis(j);
  const glm::vec3 n = normal(j);
  const float z_lo = -radius + static_cast<float>(i) * thickness();
  const float t = thickness();
  // Rows: x = a.(p - c) / R, y = (p.y - c.y) / h, z = (n.(p - c) - z_lo) / T, w = 1.
  glm::mat4 m(0.0f);
  const glm::vec3 cx(center.x, 0.0f, center.z);
  m[0][0] = a.x / radius;
  m[1][0] = a.y / radius;
  m[2][0] = a.z / radius;
  m[3][0] = -glm::dot(a, cx) / radius;
  m[1][1] = 1.0f / half_height;
  m[3][1] = -center.y / half_height;
  m[0][2] = n.x / t;
  m[1][2] = n.y / t;
  m[2][2] = n.z / t;
  m[3][2] = (-glm::dot(n, cx) - z_lo) / t;
  m[3][3] = 1.0f;
  return m;
}

SliceLayout make_slice_layout(const TreeMesh& mesh, int directions, int layers, float margin_share) {
  SliceLayout l;
  l.directions = directions;
  l.layers = layers;
  const glm::vec3 c = 0.5f * (mesh.bounds_min + mesh.bounds_max);
  l.center = c;
  float r2 = 0.0f;
  const auto grow = [&](const glm::vec3& p) { r2 = std::max(r2, (p.x - c.x) * (p.x - c.x) + (p.z - c.z) * (p.z - c.z)); };
  for (const BranchVertex& v : mesh.branch_vertices) grow(v.position);
  for (const LeafVertex& v : mesh.leaf_vertices) grow(v.position);
  // A small border (2 %) so the outermost texels stay empty and clamp-to-edge never smears.
  l.radius = std::max(std::sqrt(r2) * 1.02f, 1.0e-3f);
  l.half_height = std::max(0.5f * (mesh.bounds_max.y - mesh.bounds_min.y) * 1.02f, 1.0e-3f);
  const float m = std::isfinite(margin_share) ? std::clamp(margin_share, 0.0f, 1.0f) : 0.0f;
  l.margin = m * 2.0f * l.half_height;
  return l;
}

std::vector<std::int32_t> nearest_covered(const std::vector<std::uint8_t>& covered, int res) {
  const std::size_t n = static_cast<std::size_t>(res) * static_cast<std::size_t>(res);
  std::vector<std::int32_t> best(n, -1);
  for (std::size_t i = 0; i < n; ++i)
    if (covered[i] != 0) best[i] = static_cast<std::int32_t>(i);
  const auto dist2 = [res](std::size_t i, std::int32_t s) {
    const int dx = static_cast<int>(i % static_cast<std::size_t>(res)) - s % res;
    const int dy = static_cast<int>(i / static_cast<std::size_t>(res)) - s / res;
    return dx * dx + dy * dy;
  };
  std::vector<std::int32_t> next(n);
  std::vector<int> steps;
  for (int k = std::max(1, res / 2); k >= 1; k /= 2) steps.push_back(k);
  steps.push_back(1);
  for (int k : steps) {
    for (int y = 0; y < res; ++y)
      for (int x = 0; x < res; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(res) + static_cast<std::size_t>(x);
        std::int32_t b = best[i];
        int bd = b < 0 ? std::numeric_limits<int>::max() : dist2(i, b);
        for (int dy = -k; dy <= k; dy += k)
          for (int dx = -k; dx <= k; dx += k) {
            const int nx = x + dx;
            const int ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= res || ny >= res) continue;
            const std::int32_t s = best[static_cast<std::size_t>(ny) * static_cast<std::size_t>(res) + static_cast<std::size_t>(nx)];
            if (s < 0) continue;
            const int d = dist2(i, s);
            if (d < bd) {
              bd = d;
              b = s;
            }
          }
        next[i] = b;
      }
    best.swap(next);
  }
  return best;
}

Result<BakedTree> bake_tree_slices(const TreeAsset& asset, const TreeMesh& mesh, int resolution, float margin_share) {
  if (resolution < 16 || resolution > 1024)
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("forest.lod.slice_resolution: {} is outside [16, 1024]", resolution));
  const auto start = std::chrono::steady_clock::now();
  render::embedded::register_render_shaders();
  render::embedded::register_vegetation_shaders();
  const render::ShaderDefines defines{{"SYLVA_TREE_ANIMATION", "0"}, {"SYLVA_TREE_BAKE", "1"}};
  Result<render::Program> bark = render::Program::create({"vegetation/bark.vert", "vegetation/bake_bark.frag"}, defines);
  if (!bark.ok()) return bark.error();
  Result<render::Program> leaf = render::Program::create({"vegetation/leaf.vert", "vegetation/bake_leaf.frag"}, defines);
  if (!leaf.ok()) return leaf.error();

  render::FramebufferDesc desc;
  desc.width = resolution;
  desc.height = resolution;
  desc.color_formats = {GL_RGBA8, GL_RGBA8, GL_RGBA32F};
  Result<render::Framebuffer> fb = render::Framebuffer::create(desc);
  if (!fb.ok()) return fb.error();

  const render::SavedTargetState saved;  // restored on every exit
  // The identity instance at rest, and calm blocks (the static program reads no animation).
  InstanceGpu identity{};
  identity.translation_scale = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  identity.rotation = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
  const render::Buffer instance = render::Buffer::immutable(sizeof(InstanceGpu), &identity);
  const AnimationGpu rest = rest_animation();
  const render::Buffer anim = render::Buffer::immutable(sizeof(AnimationGpu), &rest);
  const WindGpuParams calm{};
  const render::Buffer wind = render::Buffer::immutable(sizeof(WindGpuParams), &calm);
  instance.bind_base(GL_SHADER_STORAGE_BUFFER, kInstanceBinding);
  anim.bind_base(GL_UNIFORM_BUFFER, kAnimationBinding);
  wind.bind_base(GL_UNIFORM_BUFFER, kWindBinding);
  TreeAssetAccess::branches(asset).bind_base(GL_SHADER_STORAGE_BUFFER, kBranchBinding);
  TreeAssetAccess::leaves(asset).bind_base(GL_SHADER_STORAGE_BUFFER, kLeafBinding);
  TreeAssetAccess::leaf_color(asset).bind(0);
  TreeAssetAccess::leaf_normal(asset).bind(1);
  TreeAssetAccess::leaf_coverage(asset).bind(6);
  TreeAssetAccess::bark_albedo(asset).bind(4);
  TreeAssetAccess::bark_normal(asset).bind(5);

  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
  glClearDepth(0.0);
  glDisable(GL_MULTISAMPLE);
  glDisable(GL_DEPTH_CLAMP);

  BakedTree out;
  const std::size_t n = static_cast<std::size_t>(resolution) * static_cast<std::size_t>(resolution);
  const int configs[2][2] = {{3, 3}, {2, 1}};
  for (int lod = 0; lod < 2; ++lod) {
    BakedLod& b = out.lod[static_cast<std::size_t>(lod)];
    b.layout = make_slice_layout(mesh, configs[lod][0], configs[lod][1], margin_share);
    SliceImages& im = b.images;
    im.resolution = resolution;
    im.count = b.layout.count();
    im.color.resize(im.texels() * 4);
    im.normal.resize(im.texels() * 4);
    im.depth.resize(im.texels());
    im.branch.resize(im.texels() * 4);
    std::vector<float> depth_raw(n);
    std::vector<std::uint8_t> covered(n);
    for (int j = 0; j < b.layout.directions; ++j)
      for (int i = 0; i < b.layout.layers; ++i) {
        const int slice = j * b.layout.layers + i;
        const glm::mat4 m = b.layout.bake_matrix(j, i);
        fb->bind();
        fb->clear(glm::vec4(0.0f), 0.0f);
        for (render::Program* p : {&*bark, &*leaf}) {
          p->set("u_view_proj", m);
          p->set("u_instance_base", 0);
          p->set("u_slice_axis", b.layout.axis(j));
          p->set("u_slice_normal", b.layout.normal(j));
        }
        glDisable(GL_CULL_FACE);  // both sides of thin bark cut by the slab faces
        if (asset.branch_index_count() > 0) {
          bark->use();
          TreeAssetAccess::branch_vao(asset).bind();
          glDrawElementsInstanced(GL_TRIANGLES, static_cast<GLsizei>(asset.branch_index_count()), GL_UNSIGNED_INT, nullptr, 1);
        }
        if (asset.leaf_index_count() > 0) {
          leaf->use();
          TreeAssetAccess::leaf_vao(asset).bind();
          glDrawElementsInstanced(GL_TRIANGLES, static_cast<GLsizei>(asset.leaf_index_count()), GL_UNSIGNED_INT, nullptr, 1);
        }
        const std::size_t off = static_cast<std::size_t>(slice) * n;
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fb->id());
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glReadPixels(0, 0, resolution, resolution, GL_RGBA, GL_UNSIGNED_BYTE, im.color.data() + off * 4);
        glReadBuffer(GL_COLOR_ATTACHMENT1);
        glReadPixels(0, 0, resolution, resolution, GL_RGBA, GL_UNSIGNED_BYTE, im.normal.data() + off * 4);
        glReadBuffer(GL_COLOR_ATTACHMENT2);
        glReadPixels(0, 0, resolution, resolution, GL_RGBA, GL_FLOAT, im.branch.data() + off * 4);
        glReadPixels(0, 0, resolution, resolution, GL_DEPTH_COMPONENT, GL_FLOAT, depth_raw.data());
        const float t = b.layout.thickness();
        for (std::size_t k = 0; k < n; ++k) {
          const bool c = im.branch[(off + k) * 4 + 3] > 0.5f;
          covered[k] = c ? 1 : 0;
          // Depth 1 at the slab face nearest the camera: offset from the slab centre along n.
          im.depth[off + k] = c ? (depth_raw[k] - 0.5f) * t : 0.0f;
          if (c) im.color[(off + k) * 4 + 3] = 255;
        }
        propagate_slice(im, slice, nearest_covered(covered, resolution));
      }
  }
  out.bake_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::uint64_t slice_cache_key(const TreeMesh& mesh, const TreeTextureSet& tex, int resolution, float margin_share) {
  std::uint64_t h = fnv1a64(&kFormatVersion, sizeof(kFormatVersion));
  h = fnv1a64(&resolution, sizeof(resolution), h);
  h = fnv1a64(&margin_share, sizeof(margin_share), h);
  h = fnv1a64(mesh.branch_vertices.data(), mesh.branch_vertices.size() * sizeof(BranchVertex), h);
  h = fnv1a64(mesh.branch_indices.data(), mesh.branch_indices.size() * sizeof(std::uint32_t), h);
  h = fnv1a64(mesh.leaf_vertices.data(), mesh.leaf_vertices.size() * sizeof(LeafVertex), h);
  h = fnv1a64(mesh.leaf_indices.data(), mesh.leaf_indices.size() * sizeof(std::uint32_t), h);
  h = fnv1a64(mesh.data.branches.data(), mesh.data.branches.size() * sizeof(BranchGpu), h);
  h = fnv1a64(mesh.data.leaves.data(), mesh.data.leaves.size() * sizeof(LeafGpu), h);
  for (const Image* img : {&tex.leaves.front.color, &tex.leaves.front.normal, &tex.leaves.back.color,
                           &tex.leaves.back.normal, &tex.bark.albedo, &tex.bark.normal})
    h = hash_image(*img, h);
  return h;
}

std::string serialize_slices(const BakedTree& tree, std::uint64_t key) {
  std::string payload;
  for (const BakedLod& b : tree.lod) {
    const SliceLayout& l = b.layout;
    append(payload, l.directions);
    append(payload, l.layers);
    append(payload, l.center);
    append(payload, l.radius);
    append(payload, l.half_height);
    append(payload, l.margin);
    append(payload, b.images.resolution);
    append(payload, b.images.count);
    append_vec(payload, b.images.color);
    append_vec(payload, b.images.normal);
    append_vec(payload, b.images.depth);
    append_vec(payload, b.images.branch);
  }
  std::string out(kMagic, sizeof(kMagic));
  append(out, kFormatVersion);
  append(out, key);
  append(out, static_cast<std::uint64_t>(payload.size()));
  append(out, fnv1a64(payload.data(), payload.size()));
  out += payload;
  return out;
}

Result<BakedTree> deserialize_slices(const std::string& bytes, std::uint64_t key) {
  const auto corrupt = [](const std::string& what) { return make_error(ErrorCode::kCorrupt, "slice cache: " + what); };
  if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) return corrupt("bad magic");
  Reader r{bytes, sizeof(kMagic)};
  std::uint32_t version = 0;
  std::uint64_t file_key = 0, size = 0, sum = 0;
  if (!r.get(version) || !r.get(file_key) || !r.get(size) || !r.get(sum)) return corrupt("truncated header");
  if (version != kFormatVersion) return corrupt(fmt::format("format version {} (expected {})", version, kFormatVersion));
  if (file_key != key) return corrupt(fmt::format("key {:016x} does not match {:016x}", file_key, key));
  if (size != bytes.size() - r.pos) return corrupt(fmt::format("payload of {} bytes, header says {}", bytes.size() - r.pos, size));
  if (fnv1a64(bytes.data() + r.pos, static_cast<std::size_t>(size)) != sum) return corrupt("checksum mismatch");
  BakedTree tree;
  tree.from_cache = true;
  for (BakedLod& b : tree.lod) {
    SliceLayout& l = b.layout;
    SliceImages& im = b.images;
    if (!r.get(l.directions) || !r.get(l.layers) || !r.get(l.center) || !r.get(l.radius) || !r.get(l.half_height) ||
        !r.get(l.margin) || !r.get(im.resolution) || !r.get(im.count))
      return corrupt("truncated slice header");
    if (l.directions < 1 || l.directions > 8 || l.layers < 1 || l.layers > 8 || im.count != l.count() ||
        im.resolution < 16 || im.resolution > 1024 || !(l.radius > 0.0f) || !(l.half_height > 0.0f))
      return corrupt(fmt::format("bad dimensions ({} x {} slices, {} px)", l.directions, l.layers, im.resolution));
    const std::size_t t = im.texels();
    if (!r.get_vec(im.color, t * 4) || !r.get_vec(im.normal, t * 4) || !r.get_vec(im.depth, t) || !r.get_vec(im.branch, t * 4))
      return corrupt("truncated slice images");
  }
  if (r.pos != bytes.size()) return corrupt("trailing bytes");
  return tree;
}

Status save_slice_cache(const std::filesystem::path& file, const BakedTree& tree, std::uint64_t key) {
  std::error_code ec;
  std::filesystem::create_directories(file.parent_path(), ec);
  return write_file_atomic(file, serialize_slices(tree, key));
}

Result<BakedTree> load_slice_cache(const std::filesystem::path& file, std::uint64_t key) {
  Result<std::string> bytes = read_file(file);
  if (!bytes.ok()) return bytes.error();
  Result<BakedTree> t = deserialize_slices(*bytes, key);
  if (!t.ok()) return make_error(t.error().code, fmt::format("{}: {}", file.string(), t.error().message));
  return t;
}

std::filesystem::path slice_cache_file(const std::filesystem::path& directory, std::uint64_t key) {
  return directory / fmt::format("slices-{:016x}.bin", key);
}

std::filesystem::path resolve_cache_directory(const std::string& setting) {
  return sylva::resolve_cache_directory(setting, "sylva-lod-cache");
}

Result<BakedTree> bake_or_load_slices(const TreeAsset& asset, const TreeMesh& mesh, const TreeTextureSet& textures,
                                      int resolution, float margin_share, const std::filesystem::path& directory) {
  std::uint64_t key = 0;
  std::filesystem::path file;
  if (!directory.empty()) {
    key = slice_cache_key(mesh, textures, resolution, margin_share);
    file = slice_cache_file(directory, key);
    std::error_code ec;
    if (std::filesystem::exists(file, ec)) {
      Result<BakedTree> cached = load_slice_cache(file, key);
      if (cached.ok()) return cached;
      log_warn("vegetation: rejected slice cache, rebaking: {}", cached.error().message);
    }
  }
  Result<BakedTree> baked = bake_tree_slices(asset, mesh, resolution, margin_share);
  if (!baked.ok()) return baked;
  if (!file.empty()) {
    const Status s = save_slice_cache(file, *baked, key);
    if (!s.ok()) log_warn("vegetation: could not write the slice cache: {}", s.error().message);
  }
  return baked;
}

}  // namespace sylva::vegetation
