// glTF 2.0 (.gltf with its buffers, or .glb) for the general-model terrain through Debian's
// libtinygltf (a shared library: no TINYGLTF_IMPLEMENTATION here). Every triangle primitive of
// every mesh a node of the default scene (or of every scene root when there is none) reaches,
// with the node's world transform; images are not decoded. Accessors are checked against their
// buffer views and buffers before anything is read: errors name the file and the JSON path.
#include <sylva/terrain/mesh.hpp>

#include <sylva/core/log.hpp>

#include <fmt/format.h>

#include <limits>

#if SYLVA_HAVE_TINYGLTF
#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstring>
#endif

namespace sylva::terrain {

#if SYLVA_HAVE_TINYGLTF
namespace {

// Nodes may form a graph only as a forest; deeper chains are refused rather than recursed into.
constexpr int kMaxNodeDepth = 64;

class GltfReader {
 public:
  GltfReader(const tinygltf::Model& model, std::string source) : model_(model), source_(std::move(source)) {}

  Result<PolygonMesh> run() {
    std::vector<int> roots;
    const int scene = model_.defaultScene >= 0 ? model_.defaultScene : (model_.scenes.empty() ? -1 : 0);
    if (scene >= static_cast<int>(model_.scenes.size())) return fail("scene", "the default scene does not exist");
    if (scene >= 0) {
      roots = model_.scenes[static_cast<std::size_t>(scene)].nodes;
    } else {
      // No scene: every node that is nobody's child.
      std::vector<bool> child(model_.nodes.size(), false);
      for (const tinygltf::Node& n : model_.nodes)
        for (int c : n.children)
          if (c >= 0 && static_cast<std::size_t>(c) < child.size()) child[static_cast<std::size_t>(c)] = true;
      for (std::size_t i = 0; i < child.size(); ++i)
        if (!child[i]) roots.push_back(static_cast<int>(i));
    }
    for (int r : roots) SYLVA_TRY(node(r, glm::dmat4(1.0), 0));
    if (mesh_.face_sizes.empty()) return fail("meshes", "no triangle primitives in the scene");
    if (!mesh_.colors.empty()) mesh_.colors.resize(mesh_.positions.size(), glm::vec3(1.0f));
    if (!uvs_complete_ && !mesh_.corner_uvs.empty()) {
      log_warn("{}: only some triangle primitives have TEXCOORD_0: texture coordinates ignored", source_);
    }
    if (!uvs_complete_) mesh_.corner_uvs.clear();
    return std::move(mesh_);
  }

 private:
  Error fail(const std::string& path, const std::string& what) const {
    return Error{ErrorCode::kParse, fmt::format("{}: {}: {}", source_, path, what)};
  }

  Status node(int index, const glm::dmat4& parent, int depth) {
    const std::string path = fmt::format("nodes[{}]", index);
    if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size()) return fail(path, "no such node");
    if (depth > kMaxNodeDepth) return fail(path, fmt::format("nodes nested deeper than {} (a cycle?)", kMaxNodeDepth));
    const tinygltf::Node& n = model_.nodes[static_cast<std::size_t>(index)];
    glm::dmat4 local(1.0);
    if (n.matrix.size() == 16) {
      local = glm::make_mat4(n.matrix.data());  // column-major, as glTF stores it
    } else {
      if (n.translation.size() == 3) local = glm::translate(local, glm::make_vec3(n.translation.data()));
      if (n.rotation.size() == 4) {
        local *= glm::mat4_cast(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
      }
      if (n.scale.size() == 3) local = glm::scale(local, glm::make_vec3(n.scale.data()));
    }
    const glm::dmat4 world = parent * local;
    if (n.mesh >= 0) SYLVA_TRY(mesh(n.mesh, world));
    for (int c : n.children) SYLVA_TRY(node(c, world, depth + 1));
    return {};
  }

  Status mesh(int index, const glm::dmat4& world) {
    if (static_cast<std::size_t>(index) >= model_.meshes.size()) return fail(fmt::format("meshes[{}]", index), "no such mesh");
    const tinygltf::Mesh& m = model_.meshes[static_cast<std::size_t>(index)];
    for (std::size_t p = 0; p < m.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = m.primitives[p];
      const std::string path = fmt::format("meshes[{}].primitives[{}]", index, p);
      if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) continue;  // points, lines, strips: not a surface
      const auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end()) return fail(path, "a triangle primitive without POSITION");
      const std::size_t base = mesh_.positions.size();
      SYLVA_TRY(positions(pos->second, path + ".attributes.POSITION", world));
      const std::size_t count = mesh_.positions.size() - base;
      if (const auto col = prim.attributes.find("COLOR_0"); col != prim.attributes.end()) {
        SYLVA_TRY(colors(col->second, path + ".attributes.COLOR_0", base, count));
      }
      std::vector<glm::vec2> uv;
      if (const auto tex = prim.attributes.find("TEXCOORD_0"); tex != prim.attributes.end()) {
        SYLVA_TRY(texcoords(tex->second, path + ".attributes.TEXCOORD_0", count, uv));
      } else {
        uvs_complete_ = false;
      }
      std::vector<std::uint32_t> idx;
      if (prim.indices >= 0) {
        SYLVA_TRY(indices(prim.indices, path + ".indices", idx));
      } else {
        idx.resize(count);
        for (std::size_t i = 0; i < count; ++i) idx[i] = static_cast<std::uint32_t>(i);
      }
      if (idx.size() % 3 != 0) return fail(path, fmt::format("{} indices is not a whole number of triangles", idx.size()));
      for (std::uint32_t i : idx) {
        if (i >= count) return fail(path + ".indices", fmt::format("index {} is outside the {} vertices", i, count));
        mesh_.face_indices.push_back(static_cast<std::uint32_t>(base + i));
        if (!uv.empty()) mesh_.corner_uvs.push_back(uv[i]);
      }
      mesh_.face_sizes.insert(mesh_.face_sizes.end(), idx.size() / 3, 3u);
    }
    return {};
  }

  // The bytes of accessor `index`: element size `elem`, checked against its view and buffer.
  Result<std::pair<const unsigned char*, std::size_t>> bytes(int index, const std::string& path, std::size_t elem,
                                                             std::size_t& count) {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size()) return fail(path, "no such accessor");
    const tinygltf::Accessor& a = model_.accessors[static_cast<std::size_t>(index)];
    const std::string apath = fmt::format("accessors[{}]", index);
    if (a.sparse.isSparse) return Error{ErrorCode::kUnsupported, fmt::format("{}: {}: sparse accessors are not read", source_, apath)};
    if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model_.bufferViews.size()) {
      return fail(apath + ".bufferView", "no such buffer view");
    }
    const tinygltf::BufferView& v = model_.bufferViews[static_cast<std::size_t>(a.bufferView)];
    const std::string vpath = fmt::format("bufferViews[{}]", a.bufferView);
    if (v.buffer < 0 || static_cast<std::size_t>(v.buffer) >= model_.buffers.size()) return fail(vpath + ".buffer", "no such buffer");
    const tinygltf::Buffer& b = model_.buffers[static_cast<std::size_t>(v.buffer)];
    const std::size_t stride = v.byteStride != 0 ? v.byteStride : elem;
    count = a.count;
    if (stride < elem) return fail(vpath + ".byteStride", fmt::format("stride {} is below the element size {}", stride, elem));
    // Sizes are checked in 64 bits before any element is read.
    const unsigned long long view_end = static_cast<unsigned long long>(v.byteOffset) + v.byteLength;
    if (view_end > b.data.size()) {
      return fail(vpath, fmt::format("bytes {}..{} lie outside buffer {} of {} bytes", v.byteOffset, view_end, v.buffer,
                                     b.data.size()));
    }
    if (count > 0) {
      const unsigned long long need = static_cast<unsigned long long>(a.byteOffset) +
                                      static_cast<unsigned long long>(stride) * (count - 1) + elem;
      if (count > std::numeric_limits<std::uint32_t>::max() || need > v.byteLength) {
        return fail(apath, fmt::format("{} elements from byte {} need {} bytes, the buffer view has {}", count, a.byteOffset,
                                       need, v.byteLength));
      }
    }
    return std::make_pair(b.data.data() + v.byteOffset + a.byteOffset, stride);
  }

  Status positions(int index, const std::string& path, const glm::dmat4& world) {
    if (index >= 0 && static_cast<std::size_t>(index) < model_.accessors.size()) {
      const tinygltf::Accessor& a = model_.accessors[static_cast<std::size_t>(index)];
      if (a.type != TINYGLTF_TYPE_VEC3 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
        return fail(fmt::format("accessors[{}]", index), "POSITION must be VEC3 of FLOAT");
      }
    }
    std::size_t count = 0;
    auto src = bytes(index, path, 12, count);
    if (!src.ok()) return src.error();
    mesh_.positions.reserve(mesh_.positions.size() + count);
    for (std::size_t i = 0; i < count; ++i) {
      float f[3];
      std::memcpy(f, src->first + i * src->second, sizeof f);
      const glm::dvec3 p = glm::dvec3(world * glm::dvec4(f[0], f[1], f[2], 1.0));
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        return fail(fmt::format("accessors[{}]", index), fmt::format("vertex {} is not finite", i));
      }
      mesh_.positions.emplace_back(p);
    }
    return {};
  }

  // COLOR_0 of the primitive whose vertices start at `base` into PolygonMesh::colors (RGB, alpha
  // dropped); vertices of primitives without one are white once any primitive has colours.
  Status colors(int index, const std::string& path, std::size_t base, std::size_t vertices) {
    std::size_t comps = 0, size = 0;
    if (index >= 0 && static_cast<std::size_t>(index) < model_.accessors.size()) {
      const tinygltf::Accessor& a = model_.accessors[static_cast<std::size_t>(index)];
      comps = a.type == TINYGLTF_TYPE_VEC3 ? 3 : a.type == TINYGLTF_TYPE_VEC4 ? 4 : 0;
      if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) size = 4;
      if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && a.normalized) size = 1;
      if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && a.normalized) size = 2;
      if (comps == 0 || size == 0) {
        return fail(fmt::format("accessors[{}]", index),
                    "COLOR_0 must be VEC3 or VEC4 of FLOAT or of normalized unsigned byte or short");
      }
    }
    std::size_t count = 0;
    auto src = bytes(index, path, comps * size, count);
    if (!src.ok()) return src.error();
    if (count != vertices) return fail(path, fmt::format("{} colours for {} vertices", count, vertices));
    mesh_.colors.resize(base, glm::vec3(1.0f));
    for (std::size_t i = 0; i < count; ++i) {
      const unsigned char* at = src->first + i * src->second;
      glm::vec3 c;
      for (std::size_t k = 0; k < 3; ++k) {
        if (size == 4) {
          std::memcpy(&c[static_cast<int>(k)], at + 4 * k, 4);
        } else if (size == 2) {
          std::uint16_t v;
          std::memcpy(&v, at + 2 * k, 2);
          c[static_cast<int>(k)] = static_cast<float>(v) / 65535.0f;
        } else {
          c[static_cast<int>(k)] = static_cast<float>(at[k]) / 255.0f;
        }
        if (!(c[static_cast<int>(k)] >= 0.0f && c[static_cast<int>(k)] <= 1.0f)) {
          return fail(path, fmt::format("colour {} of vertex {} is {}, outside [0, 1]", k, i, c[static_cast<int>(k)]));
        }
      }
      mesh_.colors.push_back(c);
    }
    return {};
  }

  // TEXCOORD_0 of a primitive of `vertices` vertices (glTF's convention is already the image's).
  Status texcoords(int index, const std::string& path, std::size_t vertices, std::vector<glm::vec2>& out) {
    std::size_t size = 0;
    if (index >= 0 && static_cast<std::size_t>(index) < model_.accessors.size()) {
      const tinygltf::Accessor& a = model_.accessors[static_cast<std::size_t>(index)];
      if (a.type == TINYGLTF_TYPE_VEC2) {
        if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) size = 4;
        if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && a.normalized) size = 1;
        if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && a.normalized) size = 2;
      }
      if (size == 0) {
        return fail(fmt::format("accessors[{}]", index),
                    "TEXCOORD_0 must be VEC2 of FLOAT or of normalized unsigned byte or short");
      }
    }
    std::size_t count = 0;
    auto src = bytes(index, path, 2 * (size == 0 ? 4 : size), count);
    if (!src.ok()) return src.error();
    if (count != vertices) return fail(path, fmt::format("{} texture coordinates for {} vertices", count, vertices));
    out.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const unsigned char* at = src->first + i * src->second;
      for (int k = 0; k < 2; ++k) {
        float& c = out[i][k];
        if (size == 4) {
          std::memcpy(&c, at + 4 * k, 4);
        } else if (size == 2) {
          std::uint16_t v;
          std::memcpy(&v, at + 2 * k, 2);
          c = static_cast<float>(v) / 65535.0f;
        } else {
          c = static_cast<float>(at[k]) / 255.0f;
        }
        if (!std::isfinite(c)) return fail(path, fmt::format("texture coordinate {} of vertex {} is not finite", k, i));
      }
    }
    return {};
  }

  Status indices(int index, const std::string& path, std::vector<std::uint32_t>& out) {
    std::size_t elem = 0;
    if (index >= 0 && static_cast<std::size_t>(index) < model_.accessors.size()) {
      const tinygltf::Accessor& a = model_.accessors[static_cast<std::size_t>(index)];
      if (a.type == TINYGLTF_TYPE_SCALAR) {
        if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) elem = 1;
        if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) elem = 2;
        if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) elem = 4;
      }
      if (elem == 0) return fail(fmt::format("accessors[{}]", index), "indices must be SCALAR unsigned byte, short or int");
    }
    std::size_t count = 0;
    auto src = bytes(index, path, elem == 0 ? 4 : elem, count);
    if (!src.ok()) return src.error();
    out.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const unsigned char* at = src->first + i * src->second;
      if (elem == 1) {
        out[i] = at[0];
      } else if (elem == 2) {
        std::uint16_t v;
        std::memcpy(&v, at, 2);
        out[i] = v;
      } else {
        std::memcpy(&out[i], at, 4);
      }
    }
    return {};
  }

  const tinygltf::Model& model_;
  std::string source_;
  PolygonMesh mesh_;
  bool uvs_complete_ = true;  // every triangle primitive so far had TEXCOORD_0
};

// Images are not needed for geometry: accepted undecoded.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

}  // namespace

bool gltf_supported() { return true; }

Result<PolygonMesh> load_gltf(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) return make_error(ErrorCode::kNotFound, fmt::format("{}: no such file", path.string()));
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&skip_image, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const bool binary = path.extension() == ".glb";
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path.string())
                         : loader.LoadASCIIFromFile(&model, &err, &warn, path.string());
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    return make_error(ErrorCode::kParse, fmt::format("{}: {}", path.string(), err.empty() ? std::string("not a glTF file") : err));
  }
  return GltfReader(model, path.string()).run();
}

#else

bool gltf_supported() { return false; }

Result<PolygonMesh> load_gltf(const std::filesystem::path& path) {
  return make_error(ErrorCode::kUnsupported,
                    fmt::format("{}: glTF needs libtinygltf-dev, which this build was configured without", path.string()));
}

#endif

}  // namespace sylva::terrain
