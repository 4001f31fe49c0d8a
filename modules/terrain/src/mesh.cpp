#include <sylva/terrain/mesh.hpp>

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/log.hpp>

#include "mesh_text.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <unordered_map>

namespace sylva::terrain {

bool PolygonMesh::all_triangles() const {
  return std::all_of(face_sizes.begin(), face_sizes.end(), [](std::uint32_t s) { return s == 3; });
}

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// Splits at spaces/tabs.
std::vector<std::string_view> tokens(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
    const std::size_t b = i;
    while (i < s.size() && s[i] != ' ' && s[i] != '\t') ++i;
    if (i > b) out.push_back(s.substr(b, i - b));
  }
  return out;
}

bool parse_float(std::string_view s, float& out) {
  // std::from_chars for float is available in g++ 12.
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

bool parse_int(std::string_view s, long long& out) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

}  // namespace

Result<PolygonMesh> parse_obj(std::string_view text, std::string_view source) {
  PolygonMesh mesh;
  std::vector<glm::vec2> texcoords;  // vt, v already flipped to the image convention
  bool uvs_complete = true;          // every face corner so far named a vt
  std::size_t line_no = 0;
  std::size_t pos = 0;
  std::size_t warned = 0;
  auto fail = [&](const std::string& what) {
    return make_error(ErrorCode::kParse, fmt::format("{}:{}: {}", source, line_no, what));
  };
  while (pos <= text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    line = trim(line);
    if (line.empty()) {
      if (end == text.size()) break;
      continue;
    }
    const std::vector<std::string_view> t = tokens(line);
    const std::string_view kw = t[0];
    if (kw == "v") {
      if (t.size() < 4 || t.size() == 6 || t.size() > 7) {
        return fail(fmt::format("a vertex needs 3 coordinates (and optionally w, or r g b), got {}", t.size() - 1));
      }
      const bool colored = t.size() == 7;
      if (!mesh.positions.empty() && colored != (mesh.colors.size() == mesh.positions.size())) {
        return fail(colored ? fmt::format("a vertex colour after {} vertices without one", mesh.positions.size())
                            : "a vertex without a colour after vertices with one");
      }
      float v[6];
      for (std::size_t k = 0; k + 1 < std::min<std::size_t>(t.size(), colored ? 7 : 4); ++k) {
        if (!parse_float(t[k + 1], v[k])) return fail(fmt::format("'{}' is not a number", detail::printable(t[k + 1])));
        if (!std::isfinite(v[k])) return fail(fmt::format("coordinate '{}' is not finite", detail::printable(t[k + 1])));
        if (k >= 3 && (v[k] < 0.0f || v[k] > 1.0f)) return fail(fmt::format("colour '{}' is outside [0, 1]", detail::printable(t[k + 1])));
      }
      mesh.positions.emplace_back(v[0], v[1], v[2]);
      if (colored) mesh.colors.emplace_back(v[3], v[4], v[5]);
    } else if (kw == "f") {
      if (t.size() < 4) return fail(fmt::format("a face needs at least 3 vertices, got {}", t.size() - 1));
      for (std::size_t k = 1; k < t.size(); ++k) {
        std::string_view ref = t[k], tex;
        if (const std::size_t slash = ref.find('/'); slash != std::string_view::npos) {
          tex = ref.substr(slash + 1);
          tex = tex.substr(0, tex.find('/'));
          ref = ref.substr(0, slash);
        }
        if (tex.empty()) {
          uvs_complete = false;
        } else {
          long long ti = 0;
          if (!parse_int(tex, ti)) return fail(fmt::format("'{}' is not a texture index", detail::printable(t[k])));
          const long long tcount = static_cast<long long>(texcoords.size());
          if (ti < 0) ti = tcount + ti + 1;
          if (ti < 1 || ti > tcount) {
            return fail(fmt::format("texture index in {} is outside the {} vt defined so far", t[k], tcount));
          }
          mesh.corner_uvs.push_back(texcoords[static_cast<std::size_t>(ti - 1)]);
        }
        long long idx = 0;
        if (!parse_int(ref, idx)) return fail(fmt::format("'{}' is not a vertex index", detail::printable(t[k])));
        const long long count = static_cast<long long>(mesh.positions.size());
        if (idx < 0) idx = count + idx + 1;  // relative to the vertices read so far
        if (idx < 1 || idx > count) {
          return fail(fmt::format("vertex index {} is outside the {} vertices defined so far", t[k], count));
        }
        mesh.face_indices.push_back(static_cast<std::uint32_t>(idx - 1));
      }
      mesh.face_sizes.push_back(static_cast<std::uint32_t>(t.size() - 1));
    } else if (kw == "vt") {
      if (t.size() < 2 || t.size() > 4) return fail(fmt::format("vt needs 1 to 3 numbers, got {}", t.size() - 1));
      float uv[2] = {0.0f, 0.0f};
      for (std::size_t k = 1; k < std::min<std::size_t>(t.size(), 3); ++k) {
        if (!parse_float(t[k], uv[k - 1]) || !std::isfinite(uv[k - 1])) {
          return fail(fmt::format("'{}' is not a finite number", detail::printable(t[k])));
        }
      }
      texcoords.emplace_back(uv[0], 1.0f - uv[1]);  // OBJ's v grows upwards
    } else if (kw == "vn" || kw == "o" || kw == "g" || kw == "s" || kw == "usemtl" ||
               kw == "mtllib" || kw == "l" || kw == "vp") {
      // Not needed for terrain geometry.
    } else {
      if (warned++ < 5) log_warn("{}:{}: unknown OBJ statement '{}' skipped", source, line_no, detail::printable(kw));
    }
    if (end == text.size()) break;
  }
  if (!uvs_complete && !mesh.corner_uvs.empty()) {
    log_warn("{}: {} of {} face corners name a texture coordinate: texture coordinates ignored", source,
             mesh.corner_uvs.size(), mesh.face_indices.size());
  }
  if (!uvs_complete) mesh.corner_uvs.clear();
  if (mesh.face_sizes.empty()) {
    return make_error(ErrorCode::kParse, fmt::format("{}: no faces (read {} lines, {} vertices)", source, line_no,
                                                     mesh.positions.size()));
  }
  return mesh;
}

Result<PolygonMesh> load_obj(const std::filesystem::path& path) {
  auto text = read_file(path);
  if (!text.ok()) return text.error();
  return parse_obj(*text, path.string());
}

Result<PolygonMesh> load_mesh(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  std::error_code size_error;
  if (const std::uintmax_t bytes = std::filesystem::file_size(path, size_error); !size_error && bytes > kMeshFileByteLimit) {
    return make_error(ErrorCode::kLimit, fmt::format("{}: {} MiB, above the {} MiB limit of a mesh file (read whole)",
                                                     path.string(), bytes >> 20, kMeshFileByteLimit >> 20));
  }
  if (ext == ".obj") return load_obj(path);
  if (ext == ".iv") return load_iv(path);
  if (ext == ".gltf" || ext == ".glb") return load_gltf(path);
  return make_error(ErrorCode::kUnsupported,
                    fmt::format("{}: unknown mesh format '{}' (.obj, .iv, .gltf or .glb)", path.string(), ext));
}

Status save_obj(const std::filesystem::path& path, const TriangleMesh& mesh) {
  std::string out;
  out.reserve(mesh.positions.size() * 40 + mesh.indices.size() * 8);
  for (const glm::vec3& p : mesh.positions) out += fmt::format("v {} {} {}\n", p.x, p.y, p.z);
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    out += fmt::format("f {} {} {}\n", mesh.indices[i] + 1, mesh.indices[i + 1] + 1, mesh.indices[i + 2] + 1);
  }
  return write_file_atomic(path, out);
}

TriangleMesh triangulate(const PolygonMesh& mesh) {
  TriangleMesh out;
  out.positions = mesh.positions;
  const bool uvs = mesh.corner_uvs.size() == mesh.face_indices.size() && !mesh.corner_uvs.empty();
  std::size_t at = 0;
  for (std::uint32_t n : mesh.face_sizes) {
    for (std::uint32_t k = 1; k + 1 < n; ++k) {
      for (const std::size_t corner : {at, at + k, at + k + 1}) {
        out.indices.push_back(mesh.face_indices[corner]);
        if (uvs) out.corner_uvs.push_back(mesh.corner_uvs[corner]);
      }
    }
    at += n;
  }
  return out;
}

namespace {
std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}
}  // namespace

MeshCheck check_mesh(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices) {
  MeshCheck c;
  std::unordered_map<std::uint64_t, std::uint32_t> edges;
  std::vector<std::array<std::uint32_t, 3>> sorted;
  edges.reserve(indices.size());
  for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
    const std::uint32_t a = indices[i], b = indices[i + 1], d = indices[i + 2];
    if (a == b || b == d || a == d) {
      ++c.degenerate;
      continue;
    }
    const glm::dvec3 e1 = glm::dvec3(positions[b]) - glm::dvec3(positions[a]);
    const glm::dvec3 e2 = glm::dvec3(positions[d]) - glm::dvec3(positions[a]);
    const glm::dvec3 cr = glm::cross(e1, e2);
    if (glm::dot(cr, cr) <= 1e-12 * glm::dot(e1, e1) * glm::dot(e2, e2)) ++c.degenerate;
    ++edges[edge_key(a, b)];
    ++edges[edge_key(b, d)];
    ++edges[edge_key(d, a)];
    std::array<std::uint32_t, 3> s{a, b, d};
    std::sort(s.begin(), s.end());
    sorted.push_back(s);
  }
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 1; i < sorted.size(); ++i) c.duplicate += sorted[i] == sorted[i - 1];
  for (const auto& [k, n] : edges) {
    (void)k;
    if (n == 1) ++c.boundary_edges;
    if (n > 2) ++c.non_manifold;
  }
  return c;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> boundary_edges(const std::vector<std::uint32_t>& indices) {
  std::unordered_map<std::uint64_t, int> edges;
  for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
    for (int k = 0; k < 3; ++k) ++edges[edge_key(indices[i + static_cast<std::size_t>(k)], indices[i + static_cast<std::size_t>((k + 1) % 3)])];
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (const auto& [k, n] : edges) {
    if (n == 1) out.emplace_back(static_cast<std::uint32_t>(k >> 32), static_cast<std::uint32_t>(k & 0xFFFFFFFFu));
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::size_t count_flipped(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& original,
                          const std::vector<std::uint32_t>& reduced) {
  std::vector<glm::dvec3> vertex_normal(positions.size(), glm::dvec3(0.0));
  for (std::size_t i = 0; i + 2 < original.size(); i += 3) {
    const glm::dvec3 a(positions[original[i]]), b(positions[original[i + 1]]), c(positions[original[i + 2]]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    for (int k = 0; k < 3; ++k) vertex_normal[original[i + static_cast<std::size_t>(k)]] += n;
  }
  std::size_t flipped = 0;
  for (std::size_t i = 0; i + 2 < reduced.size(); i += 3) {
    const glm::dvec3 a(positions[reduced[i]]), b(positions[reduced[i + 1]]), c(positions[reduced[i + 2]]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const glm::dvec3 ref = vertex_normal[reduced[i]] + vertex_normal[reduced[i + 1]] + vertex_normal[reduced[i + 2]];
    if (glm::dot(n, ref) < 0.0) ++flipped;
  }
  return flipped;
}

}  // namespace sylva::terrain
