// Tree export (issue #16): the glTF 2.0 file parsed back and checked structurally against the
// mesh builder's own mesh (accessor counts, min/max, every index below the vertex count, buffer
// views inside the .bin, images present, the two materials as stated), the OBJT read back, a
// species file in other units exported in metres, odd names, and failures that leave the old
// files whole (no gltf_validator or tinygltf on these machines: this is the check).
#include <sylva/vegetation/tree_export.hpp>

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>
#include <sylva/vegetation/objt.hpp>

#include "support/models.hpp"
#include "support/temp_path.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>

#if SYLVA_HAVE_TINYGLTF
#include <tiny_gltf.h>
#endif

namespace sylva::vegetation {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path fresh(const std::string& name) {
  const fs::path d = testing::unique_temp(name);
  fs::remove_all(d);
  return d;
}

int component_count(const std::string& type) {
  return type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : 0;
}

// A parsed .gltf with its .bin, and typed access to accessors after checking their ranges.
struct Gltf {
  json doc;
  std::string bin;

  // Checks the accessor's bufferView and byte range; returns its bytes.
  const char* data(int accessor, std::size_t& count, int& components) const {
    const json& a = doc["accessors"].at(static_cast<std::size_t>(accessor));
    const json& v = doc["bufferViews"].at(a["bufferView"].get<std::size_t>());
    count = a["count"].get<std::size_t>();
    components = component_count(a["type"].get<std::string>());
    EXPECT_GT(components, 0);
    EXPECT_TRUE(a["componentType"] == 5126 || a["componentType"] == 5125);
    const std::size_t offset = v["byteOffset"].get<std::size_t>();
    const std::size_t length = v["byteLength"].get<std::size_t>();
    EXPECT_EQ(v["buffer"], 0);
    EXPECT_LE(offset + length, bin.size()) << "bufferView outside the .bin";
    EXPECT_EQ(offset % 4, 0u);
    EXPECT_LE(count * static_cast<std::size_t>(components) * 4, length) << "accessor " << accessor;
    return bin.data() + offset + a.value("byteOffset", std::size_t{0});
  }
  std::vector<float> floats(int accessor, int& components) const {
    std::size_t count = 0;
    const char* p = data(accessor, count, components);
    std::vector<float> out(count * static_cast<std::size_t>(components));
    std::memcpy(out.data(), p, out.size() * 4);
    return out;
  }
  std::vector<std::uint32_t> indices(int accessor) const {
    std::size_t count = 0;
    int components = 0;
    const char* p = data(accessor, count, components);
    EXPECT_EQ(components, 1);
    std::vector<std::uint32_t> out(count);
    std::memcpy(out.data(), p, out.size() * 4);
    return out;
  }
};

Gltf read_gltf(const fs::path& file) {
  Gltf g;
  Result<std::string> text = read_file(file);
  EXPECT_TRUE(text.ok()) << file;
  if (!text.ok()) return g;
  g.doc = json::parse(*text);
  const json& buffers = g.doc["buffers"];
  EXPECT_EQ(buffers.size(), 1u);
  Result<std::string> bin = read_file(file.parent_path() / buffers[0]["uri"].get<std::string>());
  EXPECT_TRUE(bin.ok());
  if (bin.ok()) g.bin = *bin;
  EXPECT_EQ(buffers[0]["byteLength"].get<std::size_t>(), g.bin.size());
  return g;
}

struct Checked {
  std::size_t vertices = 0, triangles = 0;
  glm::vec3 lo{0.0f}, hi{0.0f};
};

// Checks one mesh's primitive: attribute counts agree, POSITION min/max are the data's, normals
// unit, tangents across the normal with w = +-1, UVs finite, every index below the vertex count.
Checked check_primitive(const Gltf& g, const json& prim) {
  Checked c;
  EXPECT_EQ(prim.value("mode", 4), 4);
  const json& at = prim["attributes"];
  int pc = 0, nc = 0, tc = 0, uc = 0;
  const std::vector<float> pos = g.floats(at["POSITION"].get<int>(), pc);
  const std::vector<float> nrm = g.floats(at["NORMAL"].get<int>(), nc);
  const std::vector<float> tan = g.floats(at["TANGENT"].get<int>(), tc);
  const std::vector<float> uv = g.floats(at["TEXCOORD_0"].get<int>(), uc);
  EXPECT_EQ(pc, 3);
  EXPECT_EQ(nc, 3);
  EXPECT_EQ(tc, 4);
  EXPECT_EQ(uc, 2);
  c.vertices = pos.size() / 3;
  EXPECT_EQ(nrm.size() / 3, c.vertices);
  EXPECT_EQ(tan.size() / 4, c.vertices);
  EXPECT_EQ(uv.size() / 2, c.vertices);
  c.lo = glm::vec3(INFINITY);
  c.hi = glm::vec3(-INFINITY);
  for (std::size_t v = 0; v < c.vertices; ++v) {
    const glm::vec3 p(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);
    c.lo = glm::min(c.lo, p);
    c.hi = glm::max(c.hi, p);
    const glm::vec3 n(nrm[3 * v], nrm[3 * v + 1], nrm[3 * v + 2]);
    const glm::vec3 t(tan[4 * v], tan[4 * v + 1], tan[4 * v + 2]);
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f) << v;
    EXPECT_NEAR(glm::length(t), 1.0f, 1e-4f) << v;
    EXPECT_NEAR(glm::dot(n, t), 0.0f, 1e-4f) << v;
    EXPECT_EQ(std::abs(tan[4 * v + 3]), 1.0f) << v;
    EXPECT_TRUE(std::isfinite(uv[2 * v]) && std::isfinite(uv[2 * v + 1])) << v;
  }
  const json& pa = g.doc["accessors"][at["POSITION"].get<std::size_t>()];
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(pa["min"][static_cast<std::size_t>(k)].get<float>(), c.lo[k]) << "POSITION min " << k;
    EXPECT_EQ(pa["max"][static_cast<std::size_t>(k)].get<float>(), c.hi[k]) << "POSITION max " << k;
  }
  const std::vector<std::uint32_t> idx = g.indices(prim["indices"].get<int>());
  EXPECT_EQ(idx.size() % 3, 0u);
  c.triangles = idx.size() / 3;
  std::size_t outside = 0;
  for (std::uint32_t i : idx) outside += i >= c.vertices ? 1 : 0;
  EXPECT_EQ(outside, 0u) << "indices at or above the vertex count " << c.vertices;
  return c;
}

const json& material_of(const Gltf& g, const std::string& mesh_name) {
  for (const json& m : g.doc["meshes"])
    if (m["name"] == mesh_name) return g.doc["materials"][m["primitives"][0]["material"].get<std::size_t>()];
  ADD_FAILURE() << "no mesh " << mesh_name;
  return g.doc["materials"][0];
}

fs::path texture_file(const Gltf& g, const fs::path& folder, const json& texture_info) {
  const json& tex = g.doc["textures"][texture_info["index"].get<std::size_t>()];
  return folder / g.doc["images"][tex["source"].get<std::size_t>()]["uri"].get<std::string>();
}

ExportTree small_export(const std::string& name) {
  Result<TreeTextureSet> tex = make_texture_set(SpeciesPreset::kBroadleaf, 1, 32, 32);
  EXPECT_TRUE(tex.ok());
  return ExportTree{name, testing::small_tree(), std::move(tex).value()};
}

TEST(TreeExport, PresetGltfMatchesTheMeshAndIsWellFormed) {
  Result<ExportTree> tree = export_tree_from_preset(SpeciesPreset::kShrub, 3, 64);
  ASSERT_TRUE(tree.ok()) << tree.error().message;
  EXPECT_EQ(tree->name, "shrub_3");
  const fs::path dir = fresh("export_preset");
  Result<TreeExportReport> r = export_tree(*tree, dir, {});
  ASSERT_TRUE(r.ok()) << r.error().message;
  const TreeMesh mesh = build_tree_mesh(tree->model);  // built independently of the exporter
  ASSERT_GT(mesh.leaf_indices.size(), 0u);

  const Gltf g = read_gltf(dir / "shrub_3.gltf");
  EXPECT_EQ(g.doc["asset"]["version"], "2.0");
  ASSERT_EQ(g.doc["meshes"].size(), 2u);
  EXPECT_EQ(g.doc["nodes"][0]["children"].size(), 2u);
  std::size_t triangles = 0;
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const json& m : g.doc["meshes"]) {
    ASSERT_EQ(m["primitives"].size(), 1u);
    const Checked c = check_primitive(g, m["primitives"][0]);
    const bool bark = m["name"] == "bark";
    EXPECT_EQ(c.vertices, bark ? mesh.branch_vertices.size() : mesh.leaf_vertices.size()) << m["name"];
    EXPECT_EQ(c.triangles * 3, bark ? mesh.branch_indices.size() : mesh.leaf_indices.size()) << m["name"];
    triangles += c.triangles;
    lo = glm::min(lo, c.lo);
    hi = glm::max(hi, c.hi);
  }
  EXPECT_EQ(triangles, (mesh.branch_indices.size() + mesh.leaf_indices.size()) / 3);
  EXPECT_EQ(triangles, r->bark_triangles + r->leaf_triangles);
  // Metres, +Y up: the model's own frame (the mesh's rest bounds).
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(lo[k], mesh.bounds_min[k], 1e-5f) << k;
    EXPECT_NEAR(hi[k], mesh.bounds_max[k], 1e-5f) << k;
  }
  EXPECT_GT(hi.y - lo.y, 1.0f);
  std::printf("shrub_3: %zu bark + %zu leaf vertices, %zu triangles, bounds (%.3f %.3f %.3f)-(%.3f %.3f %.3f), %zu bytes\n",
              r->bark_vertices, r->leaf_vertices, triangles, lo.x, lo.y, lo.z, hi.x, hi.y, hi.z, g.bin.size());

  // Bark normals in object space point away from the branch axis (the builder's are in the
  // branch frame): tested against the builder's axis offsets, rotated here.
  {
    int comps = 0;
    const json& bark_prim = g.doc["meshes"][0]["primitives"][0];
    ASSERT_EQ(g.doc["meshes"][0]["name"], "bark");
    const std::vector<float> nrm = g.floats(bark_prim["attributes"]["NORMAL"].get<int>(), comps);
    std::size_t inward = 0, side = 0;
    for (std::size_t v = 0; v < mesh.branch_vertices.size(); ++v) {
      const BranchVertex& bv = mesh.branch_vertices[v];
      if (bv.local.x == 0.0f && bv.local.y == 0.0f) continue;  // tip cap points
      const BranchGpu& b = mesh.data.branches[bv.branch];
      const glm::vec3 off = glm::vec3(b.r_object) * bv.local.x + glm::vec3(b.s_object) * bv.local.y;
      if (glm::length(off) < 1e-6f) continue;
      ++side;
      if (glm::dot(glm::vec3(nrm[3 * v], nrm[3 * v + 1], nrm[3 * v + 2]), glm::normalize(off)) < 0.5f) ++inward;
    }
    EXPECT_GT(side, 100u);
    EXPECT_EQ(inward, 0u) << "bark normals not pointing away from the axis";
  }

  // Materials as stated; their images exist at the texture size.
  const json& leaf = material_of(g, "leaves");
  EXPECT_EQ(leaf["alphaMode"], "MASK");
  EXPECT_EQ(leaf["alphaCutoff"], 0.5);
  EXPECT_EQ(leaf["doubleSided"], true);
  const json& bark = material_of(g, "bark");
  EXPECT_EQ(bark.value("alphaMode", std::string("OPAQUE")), "OPAQUE");
  for (const json* m : {&leaf, &bark}) {
    const fs::path color = texture_file(g, dir, (*m)["pbrMetallicRoughness"]["baseColorTexture"]);
    const fs::path normal = texture_file(g, dir, (*m)["normalTexture"]);
    Result<Image> ci = read_image(color), ni = read_image(normal);
    ASSERT_TRUE(ci.ok()) << color;
    ASSERT_TRUE(ni.ok()) << normal;
    EXPECT_EQ(ci->width(), 64);
    EXPECT_EQ(ni->width(), 64);
    EXPECT_EQ(ni->channels(), 3);
    EXPECT_EQ(ci->channels(), m == &leaf ? 4 : 3) << color;
  }
  // The leaf colour keeps the outline: some texels pass the cutoff, some do not.
  Result<Image> lc = read_image(texture_file(g, dir, leaf["pbrMetallicRoughness"]["baseColorTexture"]));
  std::size_t inside = 0;
  for (int y = 0; y < lc->height(); ++y)
    for (int x = 0; x < lc->width(); ++x) inside += lc->at(x, y, 3) > 0.5f ? 1 : 0;
  EXPECT_GT(inside, 0u);
  EXPECT_LT(inside, lc->pixel_count());

  // The OBJT next to it reads back as the same tree.
  Result<TreeModel> back = load_objt(dir / "shrub_3.objt");
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(back->branches.size(), tree->model.branches.size());
  EXPECT_EQ(back->leaves.size(), tree->model.leaves.size());
  EXPECT_EQ(r->files.size(), 7u);  // objt, 4 images, bin, gltf
  EXPECT_EQ(r->files.back(), dir / "shrub_3.gltf");
  fs::remove_all(dir);
}

TEST(TreeExport, SpeciesFileInOtherUnitsIsWrittenInMetres) {
  const fs::path src = fresh("export_species_src");
  fs::create_directories(src);
  const TreeModel model = testing::small_tree();
  ASSERT_TRUE(save_objt(src / "t.objt", model).ok());
  ASSERT_TRUE(write_file_atomic(src / "odd.json",
                                R"({"name": "Tree: \u00fcber/../\"x\"", "model": {"objt": "t.objt"}, "units": 0.5})")
                  .ok());
  std::vector<std::string> warnings;
  Result<ExportTree> tree = export_tree_from_species_file(src / "odd.json", 32, warnings);
  ASSERT_TRUE(tree.ok()) << tree.error().message;
  const fs::path dir = fresh("export_species_out");
  TreeExportOptions options;
  options.objt = false;
  Result<TreeExportReport> r = export_tree(*tree, dir, options);
  ASSERT_TRUE(r.ok()) << r.error().message;
  // The odd name becomes a plain stem; the name itself stays in the JSON.
  const Gltf g = read_gltf(dir / "Tree_ber_x.gltf");
  EXPECT_EQ(g.doc["nodes"][0]["name"], "Tree: \u00fcber/../\"x\"");
  EXPECT_FALSE(fs::exists(dir / "Tree_ber_x.objt"));
  const TreeMesh unscaled = build_tree_mesh(model);
  const float height = r->bounds_max.y - r->bounds_min.y;
  EXPECT_NEAR(height, 0.5f * (unscaled.bounds_max.y - unscaled.bounds_min.y), 1e-4f);
  fs::remove_all(src);
  fs::remove_all(dir);
}

#if SYLVA_HAVE_TINYGLTF
// The issue's check: another glTF reader (tinygltf 2.7, Debian libtinygltf-dev) loads the file,
// its buffers and images, and finds the tree's triangle count and bounds.
TEST(TreeExport, TinyGltfReadsItBack) {
  Result<ExportTree> tree = export_tree_from_preset(SpeciesPreset::kBirch, 5, 64);
  ASSERT_TRUE(tree.ok()) << tree.error().message;
  const fs::path dir = fresh("export_tinygltf");
  ASSERT_TRUE(export_tree(*tree, dir, {}).ok());
  const TreeMesh mesh = build_tree_mesh(tree->model);

  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadASCIIFromFile(&m, &err, &warn, (dir / "birch_5.gltf").string())) << err;
  EXPECT_TRUE(err.empty()) << err;
  EXPECT_TRUE(warn.empty()) << warn;
  std::size_t triangles = 0, bad_indices = 0;
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const tinygltf::Mesh& me : m.meshes)
    for (const tinygltf::Primitive& p : me.primitives) {
      EXPECT_EQ(p.mode, TINYGLTF_MODE_TRIANGLES);
      const tinygltf::Accessor& pos = m.accessors[static_cast<std::size_t>(p.attributes.at("POSITION"))];
      const tinygltf::Accessor& idx = m.accessors[static_cast<std::size_t>(p.indices)];
      ASSERT_EQ(idx.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
      triangles += idx.count / 3;
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], static_cast<float>(pos.minValues[static_cast<std::size_t>(k)]));
        hi[k] = std::max(hi[k], static_cast<float>(pos.maxValues[static_cast<std::size_t>(k)]));
      }
      const tinygltf::BufferView& view = m.bufferViews[static_cast<std::size_t>(idx.bufferView)];
      const tinygltf::Buffer& buffer = m.buffers[static_cast<std::size_t>(view.buffer)];
      ASSERT_LE(view.byteOffset + idx.byteOffset + idx.count * 4, buffer.data.size());
      const auto* data = reinterpret_cast<const std::uint32_t*>(buffer.data.data() + view.byteOffset + idx.byteOffset);
      for (std::size_t i = 0; i < idx.count; ++i) bad_indices += data[i] >= pos.count ? 1 : 0;
    }
  EXPECT_EQ(triangles, (mesh.branch_indices.size() + mesh.leaf_indices.size()) / 3);
  EXPECT_EQ(bad_indices, 0u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(lo[k], mesh.bounds_min[k], 1e-5f) << k;
    EXPECT_NEAR(hi[k], mesh.bounds_max[k], 1e-5f) << k;
  }
  ASSERT_EQ(m.images.size(), 4u);
  for (const tinygltf::Image& im : m.images) EXPECT_EQ(im.width, 64) << im.uri;
  int masked = 0;
  for (const tinygltf::Material& mat : m.materials)
    if (mat.alphaMode == "MASK" && mat.alphaCutoff == 0.5 && mat.doubleSided) ++masked;
  EXPECT_EQ(masked, 1);
  std::printf("tinygltf: birch_5 %zu triangles, bounds (%.3f %.3f %.3f)-(%.3f %.3f %.3f)\n", triangles, lo.x, lo.y, lo.z,
              hi.x, hi.y, hi.z);
  fs::remove_all(dir);
}
#endif

TEST(TreeExport, FileStems) {
  EXPECT_EQ(export_file_stem("seed example"), "seed_example");
  EXPECT_EQ(export_file_stem("../../etc/passwd"), "etc_passwd");
  EXPECT_EQ(export_file_stem(""), "tree");
  EXPECT_EQ(export_file_stem("///"), "tree");
  EXPECT_EQ(export_file_stem("a\xff\xfe" "b"), "a_b");
  EXPECT_EQ(export_file_stem(std::string(300, 'x')).size(), 64u);
}

TEST(TreeExport, FailuresLeaveTheOldFilesWhole) {
  const ExportTree tree = small_export("old tree");
  // A folder that cannot be created: under a regular file.
  const fs::path base = fresh("export_fail");
  fs::create_directories(base);
  ASSERT_TRUE(write_file_atomic(base / "plain", "x").ok());
  Result<TreeExportReport> r = export_tree(tree, base / "plain" / "out", {});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kIo);
  EXPECT_NE(r.error().message.find("plain/out"), std::string::npos) << r.error().message;

  // A read-only target among the files: nothing is replaced, the old .gltf stays, no temporaries.
  const fs::path dir = base / "out";
  fs::create_directories(dir);
  ASSERT_TRUE(write_file_atomic(dir / "old_tree.gltf", "OLD").ok());
  ASSERT_TRUE(write_file_atomic(dir / "old_tree.objt", "OLD OBJT").ok());
  ASSERT_TRUE(write_file_atomic(dir / "old_tree_leaf_color.png", "PNG").ok());
  fs::permissions(dir / "old_tree_leaf_color.png", fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  r = export_tree(tree, dir, {});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("old_tree_leaf_color.png"), std::string::npos) << r.error().message;
  EXPECT_EQ(read_file(dir / "old_tree.gltf").value_or(""), "OLD");
  EXPECT_EQ(read_file(dir / "old_tree.objt").value_or(""), "OLD OBJT");
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  EXPECT_EQ(names.size(), 3u) << "left behind: " << ::testing::PrintToString(names);

  // Made writable again, the export replaces all three.
  fs::permissions(dir / "old_tree_leaf_color.png", fs::perms::owner_write, fs::perm_options::add);
  r = export_tree(tree, dir, {});
  ASSERT_TRUE(r.ok()) << r.error().message;
  const Gltf g = read_gltf(dir / "old_tree.gltf");
  EXPECT_EQ(g.doc["asset"]["version"], "2.0");
  EXPECT_TRUE(read_image(dir / "old_tree_leaf_color.png").ok());

  // Bad options are named.
  TreeExportOptions none;
  none.objt = none.gltf = false;
  EXPECT_EQ(export_tree(tree, dir, none).error().code, ErrorCode::kInvalidArgument);
  TreeExportOptions nan;
  nan.season = NAN;
  EXPECT_NE(export_tree(tree, dir, nan).error().message.find("season"), std::string::npos);
  fs::remove_all(base);
}

}  // namespace
}  // namespace sylva::vegetation
