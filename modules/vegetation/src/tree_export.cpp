#include <sylva/vegetation/tree_export.hpp>

#include <sylva/core/assert.hpp>
#include <sylva/core/file_transaction.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/params.hpp>
#include <sylva/render/tone_mapping.hpp>
#include <sylva/vegetation/objt.hpp>
#include <sylva/vegetation/species_file.hpp>
#include <sylva/vegetation/textures.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <system_error>

namespace sylva::vegetation {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian");

// glTF 2.0 enumerations (specification §5).
constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kLinear = 9729;
constexpr int kLinearMipmapLinear = 9987;
constexpr int kRepeat = 10497;
constexpr int kClampToEdge = 33071;

// glTF base colour textures are sRGB-encoded: render's exact OETF (IEC 61966-2-1), NaN as 0.
float srgb_texel(float linear) { return render::linear_to_srgb_exact(std::isfinite(linear) ? linear : 0.0f); }

// One exported primitive: flat attribute arrays in glTF's conventions.
struct Primitive {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec4> tangents;
  std::vector<glm::vec2> uvs;  // glTF: v = 0 at the image's top row
  std::vector<std::uint32_t> indices;
};

// Per-vertex tangents from positions and texture coordinates (Lengyel 2001): T along +u and
// w = +1 when cross(N, T) points along +v of Sylva's coordinates (v up in the image: the glTF
// normal-texture convention, +Y up). `gl_uvs` are Sylva's (v = 0 at the image's bottom row).
void compute_tangents(Primitive& p, const std::vector<glm::vec2>& gl_uvs) {
  const std::size_t n = p.positions.size();
  std::vector<glm::vec3> tu(n, glm::vec3(0.0f)), tv(n, glm::vec3(0.0f));
  for (std::size_t i = 0; i + 2 < p.indices.size(); i += 3) {
    const std::uint32_t a = p.indices[i], b = p.indices[i + 1], c = p.indices[i + 2];
    const glm::vec3 e1 = p.positions[b] - p.positions[a], e2 = p.positions[c] - p.positions[a];
    const glm::vec2 d1 = gl_uvs[b] - gl_uvs[a], d2 = gl_uvs[c] - gl_uvs[a];
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::abs(det) > 1e-12f)) continue;
    const float r = 1.0f / det;
    const glm::vec3 su = (e1 * d2.y - e2 * d1.y) * r;
    const glm::vec3 sv = (e2 * d1.x - e1 * d2.x) * r;
    for (std::uint32_t k : {a, b, c}) {
      tu[k] += su;
      tv[k] += sv;
    }
  }
  p.tangents.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const glm::vec3 nn = p.normals[k];
    glm::vec3 t = tu[k] - nn * glm::dot(nn, tu[k]);
    if (!(glm::dot(t, t) > 1e-20f)) {  // no usable triangle: any direction across the normal
      t = glm::cross(nn, std::abs(nn.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f));
    }
    t = glm::normalize(t);
    const float w = glm::dot(glm::cross(nn, t), tv[k]) < 0.0f ? -1.0f : 1.0f;
    p.tangents[k] = glm::vec4(t, w);
  }
}

Primitive bark_primitive(const TreeMesh& mesh) {
  Primitive p;
  std::vector<glm::vec2> gl_uvs;
  for (const BranchVertex& v : mesh.branch_vertices) {
    // The builder's normal is in the branch's rest frame (r, s, t); glTF wants object space.
    const BranchGpu& b = mesh.data.branches[v.branch];
    const glm::vec3 n = glm::vec3(b.r_object) * v.normal.x + glm::vec3(b.s_object) * v.normal.y +
                        glm::vec3(b.t_object) * v.normal.z;
    p.positions.push_back(v.position);
    p.normals.push_back(glm::normalize(n));
    p.uvs.emplace_back(v.uv.x, 1.0f - v.uv.y);
    gl_uvs.push_back(v.uv);
  }
  p.indices = mesh.branch_indices;
  compute_tangents(p, gl_uvs);
  return p;
}

Primitive leaf_primitive(const TreeMesh& mesh) {
  Primitive p;
  std::vector<glm::vec2> gl_uvs;
  for (const LeafVertex& v : mesh.leaf_vertices) {
    p.positions.push_back(v.position);
    p.normals.push_back(glm::normalize(v.normal));
    p.uvs.emplace_back(v.uv.x, 1.0f - v.uv.y);
    gl_uvs.push_back(v.uv);
  }
  p.indices = mesh.leaf_indices;
  compute_tangents(p, gl_uvs);
  return p;
}

// Appends a float attribute or the indices to the buffer and describes them (bufferView +
// accessor); returns the accessor index.
class GltfBuffer {
 public:
  template <class T>
  int add(json& doc, const std::vector<T>& values, const char* type, int components, int component_type, int target,
          bool with_bounds) {
    while (bytes_.size() % 4 != 0) bytes_.push_back('\0');
    const std::size_t offset = bytes_.size();
    const std::size_t length = values.size() * sizeof(T);
    bytes_.resize(offset + length);
    std::memcpy(bytes_.data() + offset, values.data(), length);
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}, {"target", target}});
    json acc = {{"bufferView", doc["bufferViews"].size() - 1},
                {"componentType", component_type},
                {"count", values.size()},
                {"type", type}};
    if (with_bounds) {
      std::vector<double> lo(static_cast<std::size_t>(components), std::numeric_limits<double>::max());
      std::vector<double> hi(static_cast<std::size_t>(components), std::numeric_limits<double>::lowest());
      for (const T& v : values) {
        const auto* c = reinterpret_cast<const float*>(&v);
        for (int k = 0; k < components; ++k) {
          lo[static_cast<std::size_t>(k)] = std::min(lo[static_cast<std::size_t>(k)], static_cast<double>(c[k]));
          hi[static_cast<std::size_t>(k)] = std::max(hi[static_cast<std::size_t>(k)], static_cast<double>(c[k]));
        }
      }
      acc["min"] = lo;
      acc["max"] = hi;
    }
    doc["accessors"].push_back(acc);
    return static_cast<int>(doc["accessors"].size()) - 1;
  }
  int add_indices(json& doc, const std::vector<std::uint32_t>& indices, std::size_t vertex_count) {
    const int a = add(doc, indices, "SCALAR", 1, kUnsignedInt, kElementArrayBuffer, false);
    // Index bounds as integers (glTF: min/max have the accessor's component type).
    std::uint32_t lo = std::numeric_limits<std::uint32_t>::max(), hi = 0;
    for (std::uint32_t i : indices) {
      lo = std::min(lo, i);
      hi = std::max(hi, i);
    }
    SYLVA_ASSERT(indices.empty() || static_cast<std::size_t>(hi) < vertex_count, "index {} vertices {}", hi, vertex_count);
    doc["accessors"][static_cast<std::size_t>(a)]["min"] = {lo};
    doc["accessors"][static_cast<std::size_t>(a)]["max"] = {hi};
    return a;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

Image srgb_rgb(const Image& linear, bool keep_alpha) {
  Image out(linear.width(), linear.height(), keep_alpha ? 4 : 3);
  for (int y = 0; y < linear.height(); ++y)
    for (int x = 0; x < linear.width(); ++x) {
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = srgb_texel(linear.at(x, y, std::min(c, linear.channels() - 1)));
      if (keep_alpha) out.at(x, y, 3) = linear.channels() == 4 ? linear.at(x, y, 3) : 1.0f;
    }
  return out;
}

Image rgb_only(const Image& image) {
  Image out(image.width(), image.height(), 3);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = image.at(x, y, std::min(c, image.channels() - 1));
  return out;
}

// The leaves' glTF base colour: c_v + c_s (seed eq. 3.34; textures.hpp stores 0.5 + c_v), sRGB,
// alpha the outline.
Image leaf_base_color(const TreeTextureSet& textures, float season) {
  const Image& dev = textures.leaves.front.color;
  const glm::vec3 cs = glm::vec3(sample_season(textures.season, season));
  Image lin(dev.width(), dev.height(), 4);
  for (int y = 0; y < dev.height(); ++y)
    for (int x = 0; x < dev.width(); ++x) {
      for (int c = 0; c < 3; ++c) lin.at(x, y, c) = dev.at(x, y, c) - 0.5f + cs[c];
      lin.at(x, y, 3) = dev.at(x, y, 3);
    }
  return srgb_rgb(lin, true);
}

Status stage_image(FileTransaction& save, const fs::path& target, const Image& image) {
  return save.stage(target, [&image](const fs::path& temp, const fs::path& display) {
    return write_image_file(temp, image, PixelFormat::kU8, display);
  });
}

std::string dump(const json& doc) { return doc.dump(1, ' ', false, json::error_handler_t::replace) + "\n"; }

json vec_json(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// Slice layer k of a baked level as two top-row-first images: colour (sRGB, leaf texels with the
// season colour added as the slice shader does, slice.frag) and the normal texture as baked.
void slice_images(const SliceImages& im, int k, const glm::vec3& season_rgb, Image& color, Image& normal) {
  const int res = im.resolution;
  color = Image(res, res, 4);
  normal = Image(res, res, 4);
  const std::size_t base = static_cast<std::size_t>(k) * static_cast<std::size_t>(res) * static_cast<std::size_t>(res);
  for (int row = 0; row < res; ++row) {
    const int y = res - 1 - row;  // baked rows are bottom-up (GL)
    for (int x = 0; x < res; ++x) {
      const std::size_t t = (base + static_cast<std::size_t>(row) * static_cast<std::size_t>(res) + static_cast<std::size_t>(x)) * 4;
      const bool leaf = im.normal[t + 3] > 32;  // alpha 0 bark, 0.25 + 0.75 number on leaves
      for (int c = 0; c < 3; ++c) {
        float v = static_cast<float>(im.color[t + static_cast<std::size_t>(c)]) / 255.0f;
        if (leaf) v = v - 0.5f + season_rgb[c];
        color.at(x, y, c) = srgb_texel(v);
      }
      color.at(x, y, 3) = static_cast<float>(im.color[t + 3]) / 255.0f;
      for (int c = 0; c < 4; ++c) normal.at(x, y, c) = static_cast<float>(im.normal[t + static_cast<std::size_t>(c)]) / 255.0f;
    }
  }
}

Result<fs::path> make_folder(const fs::path& folder) {
  std::error_code ec;
  if (fs::is_directory(folder, ec)) return folder;
  fs::create_directories(folder, ec);
  if (ec || !fs::is_directory(folder))
    return make_error(ErrorCode::kIo, fmt::format("{}: cannot create the export folder ({})", folder.string(),
                                                  ec ? ec.message() : std::string("not a folder")));
  return folder;
}

}  // namespace

std::string export_file_stem(std::string_view name) {
  std::string stem;
  for (const char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
    const char out = keep ? ch : '_';
    if (out == '_' && !stem.empty() && stem.back() == '_') continue;
    stem.push_back(out);
    if (stem.size() >= 64) break;
  }
  while (!stem.empty() && stem.back() == '_') stem.pop_back();
  while (!stem.empty() && stem.front() == '_') stem.erase(stem.begin());
  return stem.empty() ? std::string("tree") : stem;
}

Result<ExportTree> export_tree_from_species_file(const fs::path& file, int texture_size,
                                                 std::vector<std::string>& warnings) {
  Result<SpeciesFile> species = load_species_file(file, warnings);
  if (!species.ok()) return species.error();
  Result<TreeTextureSet> textures = make_species_textures(*species, texture_size);
  if (!textures.ok()) return textures.error();
  return ExportTree{species->name, std::move(species->model), std::move(textures).value()};
}

Result<ExportTree> export_tree_from_preset(SpeciesPreset preset, std::uint32_t seed, int texture_size) {
  Result<TreeModel> model = generate_tree(species_preset(preset, seed));
  if (!model.ok()) return model.error();
  Result<TreeTextureSet> textures = make_texture_set(preset, seed, texture_size, texture_size);
  if (!textures.ok()) return textures.error();
  std::string name = "tree";
  for (const auto& e : enum_names(preset))
    if (e.value == preset) name = e.name;
  if (seed != 1) name += fmt::format("_{}", seed);
  return ExportTree{std::move(name), std::move(model).value(), std::move(textures).value()};
}

Result<TreeExportReport> export_tree(const ExportTree& tree, const fs::path& folder, const TreeExportOptions& options,
                                     const BakedTree* slices) {
  if (Status s = validate(tree.model); !s.ok()) return s.error();
  SYLVA_TRY(validate_params(options.mesh, "export.mesh"));
  if (!std::isfinite(options.season))
    return make_error(ErrorCode::kInvalidArgument, fmt::format("export: season {} is not finite", options.season));
  if (!options.objt && !options.gltf && slices == nullptr)
    return make_error(ErrorCode::kInvalidArgument, "export: nothing to write (no OBJT, glTF or slices asked for)");
  if (folder.empty()) return make_error(ErrorCode::kInvalidArgument, "export: no output folder given");
  SYLVA_TRY(make_folder(folder));

  const std::string stem = export_file_stem(tree.name);
  const glm::vec3 season_rgb = glm::vec3(sample_season(tree.textures.season, options.season));
  TreeExportReport report;
  FileTransaction save;
  const auto stage_file = [&](const fs::path& target, const auto& write) -> Status {
    SYLVA_TRY(write(target));
    report.files.push_back(target);
    return ok_status();
  };

  if (options.objt) {
    SYLVA_TRY(stage_file(folder / (stem + ".objt"),
                         [&](const fs::path& p) { return save.stage_bytes(p, format_objt(tree.model)); }));
  }

  if (slices != nullptr) {
    const fs::path dir = folder / (stem + "_slices");
    SYLVA_TRY(make_folder(dir));
    json manifest = {{"format", "sylva-tree-slices"},
                     {"version", 1},
                     {"name", tree.name},
                     {"units", "metres"},
                     {"up", "+y"},
                     {"season", options.season},
                     {"color", "sRGB RGB, alpha coverage (0.5 = the alpha test); leaf texels carry the season colour"},
                     {"normal", "RGB = slice-space normal (axis, +y, slice normal) * 0.5 + 0.5; "
                                "alpha 0 on bark, 0.25 + 0.75 leaf number on leaves"},
                     {"image_rows", "top row = the rectangle's top edge (y = center.y + half_height)"},
                     {"levels", json::array()}};
    for (int level = 0; level < 2; ++level) {
      const BakedLod& lod = slices->lod[static_cast<std::size_t>(level)];
      const SliceLayout& l = lod.layout;
      json lj = {{"level", level + 1},
                 {"directions", l.directions},
                 {"layers", l.layers},
                 {"resolution", lod.images.resolution},
                 {"center", vec_json(l.center)},
                 {"radius", l.radius},
                 {"half_height", l.half_height},
                 {"thickness", l.thickness()},
                 {"margin", l.margin},
                 {"slices", json::array()}};
      for (int j = 0; j < l.directions; ++j)
        for (int i = 0; i < l.layers; ++i) {
          const int k = j * l.layers + i;  // the texture-array layer order of slice_bake.hpp
          Image color, normal;
          slice_images(lod.images, k, season_rgb, color, normal);
          const std::string base = fmt::format("lod{}_{:02}", level + 1, k);
          SYLVA_TRY(stage_file(dir / (base + "_color.png"), [&](const fs::path& p) { return stage_image(save, p, color); }));
          SYLVA_TRY(stage_file(dir / (base + "_normal.png"), [&](const fs::path& p) { return stage_image(save, p, normal); }));
          ++report.slice_layers;
          const glm::vec3 n = l.normal(j);
          lj["slices"].push_back({{"layer", k},
                                  {"direction", j},
                                  {"index_in_direction", i},
                                  {"normal", vec_json(n)},
                                  {"axis", vec_json(l.axis(j))},
                                  {"plane_point", vec_json(l.center + n * l.layer_offset(i))},
                                  {"slab", {l.layer_offset(i) - 0.5f * l.thickness(), l.layer_offset(i) + 0.5f * l.thickness()}},
                                  {"width", 2.0f * l.radius},
                                  {"height", 2.0f * l.half_height},
                                  {"color", base + "_color.png"},
                                  {"normal_map", base + "_normal.png"}});
        }
      manifest["levels"].push_back(lj);
    }
    SYLVA_TRY(stage_file(dir / "slices.json", [&](const fs::path& p) { return save.stage_bytes(p, dump(manifest)); }));
  }

  const TreeMesh mesh = build_tree_mesh(tree.model, options.mesh);
  const Primitive bark = bark_primitive(mesh);
  const Primitive leaves = leaf_primitive(mesh);
  report.bark_vertices = bark.positions.size();
  report.bark_triangles = bark.indices.size() / 3;
  report.leaf_vertices = leaves.positions.size();
  report.leaf_triangles = leaves.indices.size() / 3;
  report.bounds_min = glm::vec3(std::numeric_limits<float>::max());
  report.bounds_max = glm::vec3(std::numeric_limits<float>::lowest());
  for (const Primitive* p : {&bark, &leaves})
    for (const glm::vec3& v : p->positions) {
      report.bounds_min = glm::min(report.bounds_min, v);
      report.bounds_max = glm::max(report.bounds_max, v);
    }

  if (options.gltf) {
    json doc = {{"asset", {{"version", "2.0"}, {"generator", "Sylva tree export (modules/vegetation)"}}},
                {"scene", 0},
                {"scenes", json::array({{{"name", tree.name}, {"nodes", {0}}}})},
                {"nodes", json::array({{{"name", tree.name}, {"children", json::array()}}})},
                {"meshes", json::array()},
                {"materials", json::array()},
                {"textures", json::array()},
                {"images", json::array()},
                {"samplers", json::array({{{"magFilter", kLinear}, {"minFilter", kLinearMipmapLinear}, {"wrapS", kRepeat}, {"wrapT", kRepeat}},
                                          {{"magFilter", kLinear}, {"minFilter", kLinearMipmapLinear}, {"wrapS", kClampToEdge}, {"wrapT", kClampToEdge}}})},
                {"bufferViews", json::array()},
                {"accessors", json::array()},
                {"extras", {{"units", "metres"}, {"season", options.season}}}};
    GltfBuffer buffer;
    const auto add_texture = [&](const std::string& file, int sampler) {
      doc["images"].push_back({{"uri", file}, {"name", file}});
      doc["textures"].push_back({{"sampler", sampler}, {"source", doc["images"].size() - 1}});
      return static_cast<int>(doc["textures"].size()) - 1;
    };
    const auto add_primitive = [&](const char* name, const Primitive& p, json material) {
      const int pos = buffer.add(doc, p.positions, "VEC3", 3, kFloat, kArrayBuffer, true);
      const int nrm = buffer.add(doc, p.normals, "VEC3", 3, kFloat, kArrayBuffer, false);
      const int tan = buffer.add(doc, p.tangents, "VEC4", 4, kFloat, kArrayBuffer, false);
      const int uv = buffer.add(doc, p.uvs, "VEC2", 2, kFloat, kArrayBuffer, false);
      const int idx = buffer.add_indices(doc, p.indices, p.positions.size());
      doc["materials"].push_back(std::move(material));
      doc["meshes"].push_back({{"name", name},
                               {"primitives", json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TANGENT", tan}, {"TEXCOORD_0", uv}}},
                                                            {"indices", idx},
                                                            {"material", doc["materials"].size() - 1},
                                                            {"mode", 4}}})}});
      doc["nodes"].push_back({{"name", name}, {"mesh", doc["meshes"].size() - 1}});
      doc["nodes"][0]["children"].push_back(doc["nodes"].size() - 1);
    };
    const std::string bark_color = stem + "_bark_color.png", bark_normal = stem + "_bark_normal.png";
    const std::string leaf_color = stem + "_leaf_color.png", leaf_normal = stem + "_leaf_normal.png";
    if (!bark.indices.empty()) {
      SYLVA_TRY(stage_file(folder / bark_color, [&](const fs::path& p) { return stage_image(save, p, srgb_rgb(tree.textures.bark.albedo, false)); }));
      SYLVA_TRY(stage_file(folder / bark_normal, [&](const fs::path& p) { return stage_image(save, p, rgb_only(tree.textures.bark.normal)); }));
      const int bc = add_texture(bark_color, 0), bn = add_texture(bark_normal, 0);
      add_primitive("bark", bark,
                    {{"name", "bark"},
                     {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", bc}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.9}}},
                     {"normalTexture", {{"index", bn}}}});
    }
    if (!leaves.indices.empty()) {
      SYLVA_TRY(stage_file(folder / leaf_color, [&](const fs::path& p) { return stage_image(save, p, leaf_base_color(tree.textures, options.season)); }));
      SYLVA_TRY(stage_file(folder / leaf_normal, [&](const fs::path& p) { return stage_image(save, p, rgb_only(tree.textures.leaves.front.normal)); }));
      const int lc = add_texture(leaf_color, 1), ln = add_texture(leaf_normal, 1);
      add_primitive("leaves", leaves,
                    {{"name", "leaves"},
                     {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", lc}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.6}}},
                     {"normalTexture", {{"index", ln}}},
                     {"alphaMode", "MASK"},
                     {"alphaCutoff", 0.5},
                     {"doubleSided", true}});
    }
    const std::string bin = stem + ".bin";
    doc["buffers"] = json::array({{{"uri", bin}, {"byteLength", buffer.bytes().size()}}});
    SYLVA_TRY(stage_file(folder / bin, [&](const fs::path& p) { return save.stage_bytes(p, buffer.bytes()); }));
    // Staged last: renamed last, so a .gltf never names files that are not in place.
    SYLVA_TRY(stage_file(folder / (stem + ".gltf"), [&](const fs::path& p) { return save.stage_bytes(p, dump(doc)); }));
  }
  SYLVA_TRY(save.commit());
  return report;
}

Result<BakedTree> bake_export_slices(const ExportTree& tree, const TreeExportOptions& options, int resolution,
                                     float margin_share) {
  if (Status s = validate(tree.model); !s.ok()) return s.error();
  SYLVA_TRY(validate_params(options.mesh, "export.mesh"));
  const TreeMesh mesh = build_tree_mesh(tree.model, options.mesh);
  Result<TreeAsset> asset = TreeAsset::create(mesh, tree.textures);
  if (!asset.ok()) return asset.error();
  return bake_tree_slices(*asset, mesh, resolution, margin_share);
}

}  // namespace sylva::vegetation
