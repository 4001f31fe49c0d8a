#pragma once
// The benchmark terrain: a 2 m fBm field of 900 m relief (9 octaves, 2 km features) with
// `size` samples per side, as the bake, build and cache benchmarks measure it.
#include <sylva/terrain/height_source.hpp>

namespace sylva::terrain {

inline HeightField bench_field(int size) {
  GeneratedFieldSettings g;
  g.size = size;
  g.spacing = 2.0;
  g.height_scale = 900.0f;
  g.feature_size = 2000.0f;
  g.fbm.octaves = 9;
  return generate_height_field(g).value();
}

}  // namespace sylva::terrain
