#include <sylva/terrain/subdivision.hpp>

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <cmath>
#include <memory>

namespace sylva::terrain {

namespace {
namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

// The vertex type PrimvarRefiner interpolates.
struct Point {
  float p[3] = {0.0f, 0.0f, 0.0f};
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0.0f; }
  void AddWithWeight(const Point& src, float w) {
    p[0] += w * src.p[0];
    p[1] += w * src.p[1];
    p[2] += w * src.p[2];
  }
};
}  // namespace

Result<PolygonMesh> subdivide(const PolygonMesh& cage, const SubdivisionSettings& settings) {
  SYLVA_TRY(validate_params(settings, "terrain.subdivision"));
  if (settings.scheme == SubdivisionScheme::kLoop && !cage.all_triangles()) {
    return make_error(ErrorCode::kInvalidArgument,
                      "terrain.subdivision.scheme: loop needs a triangle cage; this cage has other faces "
                      "(use catmull_clark)");
  }
  const double growth = settings.scheme == SubdivisionScheme::kLoop ? 4.0 : 4.0;
  if (static_cast<double>(cage.face_count()) * std::pow(growth, settings.level) > 64.0e6) {
    return make_error(ErrorCode::kLimit, fmt::format("terrain.subdivision.level: {} faces refined {} times exceed "
                                                     "64 M faces", cage.face_count(), settings.level));
  }
  Sdc::Options options;
  options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  Far::TopologyDescriptor desc;
  desc.numVertices = static_cast<int>(cage.positions.size());
  desc.numFaces = static_cast<int>(cage.face_count());
  std::vector<int> sizes(cage.face_sizes.begin(), cage.face_sizes.end());
  std::vector<Far::Index> indices(cage.face_indices.begin(), cage.face_indices.end());
  desc.numVertsPerFace = sizes.data();
  desc.vertIndicesPerFace = indices.data();
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  const Sdc::SchemeType type = settings.scheme == SubdivisionScheme::kLoop ? Sdc::SCHEME_LOOP : Sdc::SCHEME_CATMARK;
  std::unique_ptr<Far::TopologyRefiner> refiner(Factory::Create(desc, Factory::Options(type, options)));
  if (!refiner) {
    return make_error(ErrorCode::kInvalidArgument, "terrain.subdivision: OpenSubdiv rejected the cage topology "
                                                   "(non-manifold edges or degenerate faces)");
  }
  const int level = settings.level;
  Far::TopologyRefiner::UniformOptions uniform(level);
  uniform.fullTopologyInLastLevel = true;
  refiner->RefineUniform(uniform);

  std::vector<Point> verts(static_cast<std::size_t>(refiner->GetNumVerticesTotal()));
  for (std::size_t i = 0; i < cage.positions.size(); ++i) {
    verts[i].p[0] = cage.positions[i].x;
    verts[i].p[1] = cage.positions[i].y;
    verts[i].p[2] = cage.positions[i].z;
  }
  Far::PrimvarRefiner primvar(*refiner);
  Point* src = verts.data();
  for (int l = 1; l <= level; ++l) {
    Point* dst = src + refiner->GetLevel(l - 1).GetNumVertices();
    primvar.Interpolate(l, src, dst);
    src = dst;
  }
  const Far::TopologyLevel& last = refiner->GetLevel(level);
  std::vector<Point> finest(src, src + last.GetNumVertices());
  if (settings.limit_surface && level > 0) {
    std::vector<Point> limit(finest.size());
    primvar.Limit(finest, limit);
    finest = std::move(limit);
  }
  PolygonMesh out;
  out.positions.reserve(finest.size());
  for (const Point& p : finest) out.positions.emplace_back(p.p[0], p.p[1], p.p[2]);
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    const Far::ConstIndexArray fv = last.GetFaceVertices(f);
    out.face_sizes.push_back(static_cast<std::uint32_t>(fv.size()));
    for (int k = 0; k < fv.size(); ++k) out.face_indices.push_back(static_cast<std::uint32_t>(fv[k]));
  }
  return out;
}

}  // namespace sylva::terrain
