#pragma once
// Triangle and polygon meshes for the general-model terrain (seed 002 §4), the OBJ loader and
// the topology checks every reduction result must pass (no holes, no degenerate or flipped
// triangles, manifold edges). Positions in metres, y up.

#include <sylva/core/result.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::terrain {

struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;  // three per triangle
  std::vector<glm::vec2> corner_uvs;   // parallel to indices when the source has UVs, else empty
  std::size_t triangle_count() const { return indices.size() / 3; }
};

// Faces of any size (a subdivision control cage keeps its quads).
struct PolygonMesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> face_sizes;    // vertices per face, >= 3
  std::vector<std::uint32_t> face_indices;  // concatenated
  // Per position when the file has vertex colours (OBJ `v x y z r g b`, glTF COLOR_0), else empty.
  std::vector<glm::vec3> colors;
  // Per face corner (parallel to face_indices) when every face has texture coordinates (OBJ
  // `f a/t`, glTF TEXCOORD_0), else empty. Image convention: (0, 0) is the image's top-left
  // corner and v grows downwards (glTF's; OBJ's vt v is flipped to 1 - v on reading).
  std::vector<glm::vec2> corner_uvs;
  std::size_t face_count() const { return face_sizes.size(); }
  bool all_triangles() const;
};

// Parses Wavefront OBJ text: `v x y z [w]` or `v x y z r g b` (the common vertex-colour
// extension: colours in [0, 1], on every vertex or none) and `f a b c ...` with a, a/t, a/t/n
// or a//n (1-based or negative relative indices), `vt u [v [w]]` (texture coordinates, kept in
// corner_uvs when every face corner names one; a mix of corners with and without drops them with a
// warning); comments, vn, o, g, s, usemtl and mtllib are ignored; other statements are skipped with a warning naming the line. Errors (kParse) name
// `source:line` and say what is wrong: a bad number, a face with fewer than 3 vertices, an
// index of 0 or outside the vertices, a non-finite coordinate, a colour outside [0, 1], a
// vertex without a colour among coloured ones (or the reverse), a texture index outside the vt
// read so far, no faces at all.
Result<PolygonMesh> parse_obj(std::string_view text, std::string_view source = "<obj>");
Result<PolygonMesh> load_obj(const std::filesystem::path& path);
// The Open Inventor ASCII subset of the seed's general-model files (cilaos.iv): the first line
// `#Inventor V2.x ascii`, then `Coordinate3 { point [ x y z, ... ] }` and `IndexedFaceSet {
// coordIndex [ a, b, c, -1, ... ] }` anywhere among Separators and other nodes (skipped by their
// braces and brackets; DEF names allowed, USE not followed). A face set indexes the Coordinate3
// current at its place (scoped by Separators); the last face may omit its -1; faces keep their
// size (triangulate() fans them). Errors (kParse) name `source:line`: an index outside the
// current points, a face of fewer than 3, a point with fewer than 3 numbers, end of file inside
// a node or list, no faces at all.
Result<PolygonMesh> parse_iv(std::string_view text, std::string_view source = "<iv>");
Result<PolygonMesh> load_iv(const std::filesystem::path& path);

// glTF 2.0 (.gltf with external or data-URI buffers, .glb) through Debian's libtinygltf: every
// triangle primitive (mode 4) of every mesh reached from the default scene's nodes (or from every
// root node when there is no scene), transformed by the node's world matrix; other modes are
// skipped. COLOR_0 (VEC3/VEC4 of FLOAT or normalized unsigned byte/short) fills colors (white for
// primitives without it). TEXCOORD_0 (VEC2 of FLOAT or normalized unsigned byte/short) fills
// corner_uvs when every primitive has it (dropped with a warning otherwise). Errors name the file and the glTF JSON path
// (`meshes[0].primitives[1].indices`, `bufferViews[2]`): a missing buffer file, an accessor past
// its view or buffer, POSITION not VEC3 FLOAT, an index outside the primitive's vertices, a
// COLOR_0 or TEXCOORD_0 of another type or count, a COLOR_0 outside [0, 1], a non-finite UV. gltf_supported() is false when the build
// has no tinygltf; load_gltf then returns kUnsupported.
bool gltf_supported();
Result<PolygonMesh> load_gltf(const std::filesystem::path& path);

// Mesh files are read whole (OBJ and IV as text, glTF by tinygltf), so load_mesh refuses a file
// above this size unread (kLimit naming the path and both sizes): a 2 GiB OBJ had taken 6.5 GB
// and 30 s before failing. 1 GiB of OBJ text is about 15 M vertices, far above a terrain mesh.
inline constexpr std::uintmax_t kMeshFileByteLimit = std::uintmax_t{1} << 30;

// By the file extension (case-insensitive): .obj, .iv, .gltf or .glb; any other is kUnsupported;
// a file larger than kMeshFileByteLimit is kLimit.
Result<PolygonMesh> load_mesh(const std::filesystem::path& path);

// Writes OBJ text (vertices and faces) through an atomic file write.
Status save_obj(const std::filesystem::path& path, const TriangleMesh& mesh);

// Fan triangulation of every face (faces of a cage are planar-ish quads or triangles).
TriangleMesh triangulate(const PolygonMesh& mesh);

struct MeshCheck {
  std::size_t degenerate = 0;      // repeated index or |e1 x e2|^2 <= 1e-12 |e1|^2 |e2|^2
  std::size_t duplicate = 0;       // two triangles with the same three vertices
  std::size_t non_manifold = 0;    // edges used by more than two triangles
  std::size_t boundary_edges = 0;  // edges used by one triangle
  bool ok() const { return degenerate == 0 && duplicate == 0 && non_manifold == 0; }
};
MeshCheck check_mesh(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices);

// Undirected boundary edges (used by exactly one triangle) as (min, max) vertex pairs, sorted.
std::vector<std::pair<std::uint32_t, std::uint32_t>> boundary_edges(const std::vector<std::uint32_t>& indices);

// Triangles of `reduced` whose normal points against the original surface around their
// vertices (area-weighted normal of the original triangles using those vertices). Both index the
// same position array.
std::size_t count_flipped(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& original,
                          const std::vector<std::uint32_t>& reduced);

}  // namespace sylva::terrain
