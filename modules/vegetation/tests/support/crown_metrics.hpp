#pragma once
// Crown metrics of a rendered tree (issue 19, "a picture worth showing"): how closed a crown looks
// and what colour it has, so the presets and their slices can be held to stated bounds.
//
// The crown region is the convex hull of the silhouette (pixels whose coverage exceeds one half),
// the outline a person would draw around the crown; its closure is the mean per-pixel coverage
// (fractional, from a multisampled render) inside that hull: 1 = no sky shows through the crown.

#include <sylva/core/image.hpp>

#include <glm/glm.hpp>

namespace sylva::vegetation::testing {

// 1 inside the convex hull of the pixels with mask > 0.5 (pixel centres; hull edges included),
// 0 elsewhere. An empty mask gives an empty hull.
Image convex_hull_mask(const Image& mask);

struct CrownStats {
  double hull_pixels = 0.0;    // pixels of the convex hull of the silhouette
  double covered = 0.0;        // sum of coverage inside the hull [px]
  double closure = 0.0;        // covered / hull_pixels in [0, 1] (0 for an empty hull)
  glm::dvec3 mean_color{0.0};  // mean colour of the covered part inside the hull (linear rgb)
};

// coverage: one channel in [0, 1]; over_black: the same render over a black background (rgb,
// same size), so a pixel's colour is coverage x the tree's colour there.
CrownStats crown_stats(const Image& coverage, const Image& over_black);

}  // namespace sylva::vegetation::testing
