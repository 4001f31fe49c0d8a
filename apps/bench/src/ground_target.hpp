#pragma once
// "builtin:ground": the bench's own scene, the sky plus a lit grid of an fBm height field. It
// needs no content module, so the bench's end-to-end tests run on any build; its LOD knob is the
// grid resolution (ground.resolution), whose reference is the finest grid (1025 vertices per
// side). Normals come from the full-detail noise at every vertex, so a coarse grid keeps its
// shading and the image error measures the lost geometry (silhouettes, ridges, occlusion).

#include "bench_target.hpp"

#include <sylva/core/noise.hpp>
#include <sylva/render/lighting.hpp>

namespace sylva::bench {

struct BenchGroundSettings {
  int resolution = 129;    // vertices per side of the grid
  float size = 4000.0f;    // side length [m], centred on the origin
  float height = 240.0f;   // height scale [m]
  FbmSettings noise{.octaves = 6, .persistence = 0.5f, .lacunarity = 2.0f, .frequency = 1.0f / 1100.0f, .seed = 11,
                    .ridge_gain = 2.0f};

  template <class V>
  void visit(V& v) {
    v(resolution, "resolution", {.min = 2, .max = 2049, .help = "Grid vertices per side (the LOD knob)",
                                 .rebuild = Rebuild::kGpu, .log_scale = true});
    v(size, "size", {.min = 1.0, .max = 1.0e6, .unit = "m", .help = "Side length of the ground",
                     .rebuild = Rebuild::kGpu});
    v(height, "height", {.min = 0.0, .max = 1.0e4, .unit = "m", .help = "Height scale of the noise",
                         .rebuild = Rebuild::kGpu});
    v(noise, "noise");
  }
};

struct GroundTargetSettings {
  BenchGroundSettings ground;
  render::Lighting lighting;

  template <class V>
  void visit(V& v) {
    v(ground, "ground");
    v(lighting, "lighting");
  }
};

// Height [m] of the built-in ground at world (x, z), the function the grid samples.
float builtin_ground_height(const BenchGroundSettings& s, double x, double z);

// Factory for "builtin:ground".
std::unique_ptr<BenchTarget> make_ground_target();

// The built-in ground's camera paths (also used by the tests): "flyover" (diagonal flight at
// 420 m looking ahead and down), "low_pass" (just above the ridges, horizon in view: silhouettes
// and grazing angles), "orbit" (a full circle around the centre).
std::vector<CameraPath> ground_camera_paths();

}  // namespace sylva::bench
