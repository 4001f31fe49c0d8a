#pragma once
// The player's built-in scene until the scene module lands: the sky plus a lit ground mesh made
// from core fBm noise (Foundation issue). Its settings are plain reflected data, so a JSON file
// of the same shape and `--set ground.height=300` work without any hand-written parsing.

#include <sylva/core/noise.hpp>
#include <sylva/core/result.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/lighting.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/vertex_array.hpp>

#include <glm/glm.hpp>

namespace sylva::player {

struct CameraBookmark {
  glm::vec3 position{-620.0f, 260.0f, 700.0f};  // world metres
  float yaw_deg = -40.0f;     // 0 looks along -z, positive turns left
  float pitch_deg = -12.0f;   // positive looks up
  float fov_deg = 60.0f;      // vertical field of view

  template <class V>
  void visit(V& v) {
    v(position, "position", {.unit = "m", .help = "Camera position in world metres"});
    v(yaw_deg, "yaw_deg", {.min = -360.0, .max = 360.0, .unit = "deg", .help = "Heading, 0 looks along -z"});
    v(pitch_deg, "pitch_deg", {.min = -89.9, .max = 89.9, .unit = "deg", .help = "Elevation of the view"});
    v(fov_deg, "fov_deg", {.min = 1.0, .max = 170.0, .unit = "deg", .help = "Vertical field of view"});
  }
};

struct SunSettings {
  float azimuth_deg = 35.0f;    // 0 = toward -z (north), positive toward +x
  float elevation_deg = 28.0f;  // above the horizon; 90 = straight up
  float fog_density = 4.0e-4f;  // exponential fog [1/m]

  template <class V>
  void visit(V& v) {
    v(azimuth_deg, "azimuth_deg", {.min = -360.0, .max = 360.0, .unit = "deg", .help = "Sun heading"});
    v(elevation_deg, "elevation_deg", {.min = -10.0, .max = 90.0, .unit = "deg", .help = "Sun height"});
    v(fog_density, "fog_density", {.min = 0.0, .max = 0.1, .unit = "1/m", .help = "Distance fog density"});
  }
};

struct GroundSettings {
  int resolution = 257;     // vertices per side
  float size = 4000.0f;     // side length [m], centred on the origin
  float height = 220.0f;    // peak-to-valley scale [m]
  FbmSettings noise{.octaves = 7, .persistence = 0.48f, .lacunarity = 2.0f, .frequency = 1.0f / 700.0f,
                    .seed = 7, .ridge_gain = 2.0f};

  template <class V>
  void visit(V& v) {
    v(resolution, "resolution", {.min = 2, .max = 2049, .help = "Vertices per side of the ground mesh"});
    v(size, "size", {.min = 1.0, .max = 1.0e6, .unit = "m", .help = "Side length of the ground"});
    v(height, "height", {.min = 0.0, .max = 1.0e4, .unit = "m", .help = "Height scale of the noise"});
    v(noise, "noise");
  }
};

struct GroundSceneSettings {
  CameraBookmark camera;
  SunSettings sun;
  GroundSettings ground;

  template <class V>
  void visit(V& v) {
    v(camera, "camera");
    v(sun, "sun");
    v(ground, "ground");
  }
};

// Lighting for the scene's sun (direction from azimuth/elevation, fog density).
render::Lighting make_lighting(const SunSettings& sun);
// Camera placed at the bookmark with the given viewport aspect.
render::Camera make_camera(const CameraBookmark& bookmark, glm::ivec2 viewport);

// GPU ground mesh. Vertices are stored relative to the mesh origin (0, 0, 0) and drawn with the
// camera's relative model matrix, so the scene would stay exact far from the world origin.
class GroundRenderer {
 public:
  static Result<GroundRenderer> create(const GroundSettings& settings);
  GroundRenderer() = default;

  // Opaque pass into the bound framebuffer; the frame's LightingUniforms must be bound.
  // Counts draw calls and triangles into `stats`.
  void draw(const render::Camera& camera, render::PassStats& stats);

  std::size_t triangle_count() const { return index_count_ / 3; }

 private:
  render::Program program_;
  render::Buffer vertices_;
  render::Buffer indices_;
  render::VertexArray vao_;
  std::size_t index_count_ = 0;
  float snow_line_ = 0.0f;  // metres
};

}  // namespace sylva::player
