#pragma once
// Measured screen-space error of a drawn frame against the full-resolution field: the bound the
// selection promises, checked on what is actually drawn (tests, benchmarks, sylva-bench).
//
// The drawn body triangles are rasterised in the x/z plane onto the field's samples; at every
// covered sample the projected vertical error K * |y_drawn - h| / distance(camera, drawn point)
// is evaluated. Because the meshes are nested right triangulations of the samples, the vertical
// difference is linear between samples, so the maximum over samples is the maximum over the
// surface. Seams (vertical, no x/z area) and skirts are not surface and are skipped.

#include <sylva/core/height_field.hpp>
#include <sylva/terrain/frame_mesh.hpp>
#include <sylva/terrain/vertex_position.hpp>

#include <glm/glm.hpp>

#include <cstddef>
#include <vector>

namespace sylva::terrain {

struct ProjectedError {
  double max_px = 0.0;          // largest projected error [px]
  double max_m = 0.0;           // largest vertical error [m]
  std::size_t samples = 0;      // field samples under a drawn triangle
  glm::ivec2 worst{-1, -1};     // sample of max_px
};

// `k` is LodView::k of the frame's view.
ProjectedError measure_projected_error(const HeightField& field, const VertexFrame& frame, const FrameMesh& mesh,
                                       double k);

// Drawn height at every field sample (NaN where nothing is drawn), row-major (pops, debugging).
std::vector<float> drawn_heights(const HeightField& field, const VertexFrame& frame, const FrameMesh& mesh);

}  // namespace sylva::terrain
