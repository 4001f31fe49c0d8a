#pragma once
// The one formula that places a chunk vertex on screen, shared by the CPU (tests, error
// measurement) and, operation for operation, by shaders/chunk.vert. Everything it reads is a
// property of the grid point (ChunkVertex) or of the frame, never of the chunk drawing it, so
// every chunk that holds a point computes bit-identical coordinates for it: the basis of the
// crack-free guarantee (seams only close T-junctions, see seams.hpp).
//
// Camera-relative: x and z are (integer grid offset from a grid point near the camera) * spacing
// minus the camera's small offset from that point, so a terrain 1e5 m from the origin keeps
// sub-millimetre precision and no chunk-dependent origin enters the result. An hq2 leaf centre
// (ChunkVertex::centre) adds half a grid interval to the offset; every other point adds 0.0.
//
// Morphing (CDLOD-style, per point): a vertex moves from its height h to the coarser level's
// surface height G as its distance d to the camera grows from (1 - f) * m1 to m1, where
// m1 = K * morph_error / tau is the distance at which the coarser chunk becomes acceptable and
// d = |camera - (x, h, z)| - |G - h| is a lower bound of the distance of every point between h
// and G (so the projected morph offset stays within tau wherever it puts the vertex):
//   mu = clamp((d - (1 - f) m1) / (f m1), 0, 1),  y = h + (G - h) * mu.
// A chunk is replaced by its parent only when K * delta / (D - delta) <= tau for the parent's
// box distance D and bound delta >= |G - h|, so d >= m1 for all its vertices by then: they have
// all reached G and the switch does not pop.

#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/lod_view.hpp>
#include <sylva/terrain/settings.hpp>

#include <glm/glm.hpp>

namespace sylva::terrain {

struct VertexFrame {
  glm::ivec2 origin{0};      // root-grid point near the camera
  glm::vec3 camera{0.0f};    // camera - world(origin) in x/z [m]; absolute camera height in y [m]
  float spacing = 1.0f;      // metres per root-grid interval
  float k_over_tau = 0.0f;   // K / tau [1/m... px per m over px]: m1 = k_over_tau * morph_error
  float morph_start = 1.0f;  // 1 - morph_fraction
  bool morph = false;
};

VertexFrame make_vertex_frame(const ChunkTree& tree, const LodView& view, const LodSettings& settings);

// Morph weight mu in [0, 1] of a vertex this frame (0 when morphing is off).
float morph_weight(const VertexFrame& frame, const ChunkVertex& v);
// Camera-relative position [m] of a vertex this frame.
glm::vec3 vertex_position(const VertexFrame& frame, const ChunkVertex& v);

}  // namespace sylva::terrain
