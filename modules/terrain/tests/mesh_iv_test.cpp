// The Open Inventor ASCII subset (mesh_iv.cpp) in detail: Separators scope the current
// Coordinate3, DEF names and other nodes are passed over, faces keep their size and are fanned by
// triangulate(), and every refusal names the file and line.
#include <sylva/terrain/mesh.hpp>

#include <gtest/gtest.h>

namespace sylva::terrain {
namespace {

TEST(InventorMesh, SeparatorsScopeTheCoordinatesAndFacesKeepTheirSize) {
  const char* text =
      "#Inventor V2.1 ascii\n"
      "# two shapes\n"
      "Separator {\n"
      "  DEF Ground Coordinate3 { point [ 0 0 0, 4 0 0, 4 0 4 ] }\n"
      "  Material { diffuseColor 0.4 0.5 0.3 }\n"
      "  ShapeHints { vertexOrdering COUNTERCLOCKWISE creaseAngle 0.5 }\n"
      "  Separator {\n"
      "    Coordinate3 { point [ 0 1 0, 1 1 0, 1 1 1, 0 1 1, 0.5 1 1.5 ] }\n"
      "    IndexedFaceSet { coordIndex [ 0, 1, 2, 4, 3 ] materialIndex [ 0 ] }\n"
      "  }\n"
      "  IndexedFaceSet { coordIndex [ 0, 1, 2, -1 ] }\n"
      "}\n";
  auto mesh = parse_iv(text, "two.iv");
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  EXPECT_EQ(mesh->positions.size(), 8u);
  EXPECT_EQ(mesh->face_sizes, (std::vector<std::uint32_t>{5, 3}));
  // The pentagon indexes the inner points (3..7); the triangle after the Separator the outer ones.
  EXPECT_EQ(mesh->face_indices, (std::vector<std::uint32_t>{3, 4, 5, 7, 6, 0, 1, 2}));
  const TriangleMesh t = triangulate(*mesh);
  EXPECT_EQ(t.triangle_count(), 4u) << "a pentagon fans into 3 triangles";
  EXPECT_EQ(t.indices, (std::vector<std::uint32_t>{3, 4, 5, 3, 5, 7, 3, 7, 6, 0, 1, 2}));
}

TEST(InventorMesh, RefusalsNameTheFileAndLine) {
  struct Case {
    const char* text;
    const char* expect;
  };
  const Case cases[] = {
      {"#VRML V2.0 utf8\nShape {}\n", "bad.iv:1: not an ASCII Open Inventor file"},
      {"#Inventor V2.1 binary\n", "bad.iv:1: not an ASCII Open Inventor file"},
      {"#Inventor V2.1 ascii\nCoordinate3 { point [ 0 0 0, 1 0\n ] }\n", "bad.iv:2: a point with 2 coordinates"},
      {"#Inventor V2.1 ascii\nCoordinate3 { point [ 0 0 0, 1 0 x ] }\n", "bad.iv:2: 'x' is not a coordinate"},
      {"#Inventor V2.1 ascii\nCoordinate3 { point [ 0 0 1e39 ] }\n", "bad.iv:2: "},
      {"#Inventor V2.1 ascii\nCoordinate3 { point [ 0 0 0, 1 0 0, 0 0 1 ] }\nIndexedFaceSet { coordIndex [ 0, 1, -1 ] }\n",
       "bad.iv:3: a face with 2 vertices"},
      {"#Inventor V2.1 ascii\nIndexedFaceSet { coordIndex [ 0, 1, 2 ] }\n",
       "bad.iv:2: coordIndex 0 is outside the 0 points"},
      {"#Inventor V2.1 ascii\nCoordinate3 { point [ 0 0 0, 1 0 0, 0 0 1 ] }\nIndexedFaceSet { coordIndex [ 0, 1, -2 ] }\n",
       "bad.iv:3: coordIndex -2 is outside"},
      {"#Inventor V2.1 ascii\nSeparator {\n Coordinate3 { point [ 0 0 0 ] }\n", "bad.iv:4: end of file inside Separator"},
      {"#Inventor V2.1 ascii\nSeparator {\n Coordinate3 { point [ 0 0 0 ] }\n}\n", "bad.iv: no faces"},
      {"#Inventor V2.1 ascii\nSeparator { ] }\n", "bad.iv:2: unexpected ']'"},
  };
  for (const Case& c : cases) {
    auto mesh = parse_iv(c.text, "bad.iv");
    ASSERT_FALSE(mesh.ok()) << c.text;
    EXPECT_NE(mesh.error().message.find(c.expect), std::string::npos) << mesh.error().message << " | wanted " << c.expect;
  }
}

TEST(InventorMesh, LoadMeshPicksTheFormatByExtension) {
  auto unknown = load_mesh("terrain.stl");
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().code, ErrorCode::kUnsupported);
  EXPECT_NE(unknown.error().message.find("terrain.stl: unknown mesh format '.stl'"), std::string::npos)
      << unknown.error().message;
  auto missing = load_mesh("/nonexistent/cilaos.IV");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("cilaos.IV"), std::string::npos) << missing.error().message;
  EXPECT_EQ(missing.error().message.find("unknown mesh format"), std::string::npos) << "upper-case .IV is Inventor";
}

}  // namespace
}  // namespace sylva::terrain
