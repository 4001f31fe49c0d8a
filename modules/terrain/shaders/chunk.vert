#version 450 core
// terrain/chunk.vert: places a chunk vertex. Operation for operation the twin of
// sylva::terrain::vertex_position (src/vertex_position.cpp): every input is a property of the
// grid point or of the frame, never of the chunk being drawn, so all chunks (and the seam
// batch, drawn with this same program) compute bit-identical positions for a shared point.
// Camera-relative: integer grid offsets from a grid point near the camera times the spacing.

layout(location = 0) in uvec2 a_grid;    // root-grid point (gx, gz)
layout(location = 1) in vec3 a_height;   // x: height h, y: morph target G, z: morph error [m]
layout(location = 2) in float a_skirt;   // metres to hang below the surface (skirt bottoms), else 0
layout(location = 3) in float a_centre;  // 1: an hq2 leaf centre at (gx + 0.5, gz + 0.5), else 0

uniform ivec2 u_origin;       // grid point near the camera
uniform vec3 u_camera;        // camera - world(origin) in x/z; camera height in y [m]
uniform float u_spacing;      // metres per grid interval
uniform float u_k_over_tau;   // K / tau
uniform float u_morph_start;  // 1 - morph_fraction
uniform int u_morph;          // 0 = no morphing
uniform mat4 u_view_projection;  // camera-relative position -> clip
uniform ivec2 u_field_size;      // field samples (columns, rows): beyond them is padding

// Aerial perspective (TerrainRenderSettings::aerial_perspective): 1 = per vertex, evaluated here
// and interpolated; 0 (per pixel, terrain.frag) and 2 (off) compute nothing here.
#ifndef SYLVA_TERRAIN_AIR
#define SYLVA_TERRAIN_AIR 0
#endif
#if SYLVA_TERRAIN_AIR == 1 || SYLVA_TERRAIN_AIR == 3
#include "render/lib/fog.glsl"
out vec3 v_air_extinction;  // air and haze extinction along the vertex's view ray [1/m], per channel
#endif
#if SYLVA_TERRAIN_AIR == 3
out vec3 v_air_sky;  // sky radiance of the vertex's view direction (chunks below the camera)
#endif

out vec3 v_rel;      // camera-relative position [m]
out vec2 v_grid;     // grid coordinates (for the height texture)
out float v_morph;   // morph weight (debug view)

invariant gl_Position;

void main() {
  // + 0.0 for every grid point leaves its float unchanged, bit for bit.
  precise float centre_offset = 0.5 * a_centre;
  precise float rx = (float(int(a_grid.x) - u_origin.x) + centre_offset) * u_spacing - u_camera.x;
  precise float rz = (float(int(a_grid.y) - u_origin.y) + centre_offset) * u_spacing - u_camera.z;
  float h = a_height.x;
  float g = a_height.y;
  precise float ry0 = h - u_camera.y;
  precise float mu = 0.0;
  if (u_morph != 0) {
    // Distance to the nearest point between h and G (see vertex_position.hpp).
    precise float d = sqrt(rx * rx + ry0 * ry0 + rz * rz) - abs(g - h);
    precise float m1 = u_k_over_tau * a_height.z;
    precise float m0 = u_morph_start * m1;
    if (d >= m1) {
      mu = 1.0;
    } else if (d <= m0) {
      mu = 0.0;
    } else {
      mu = (d - m0) / (m1 - m0);
    }
  }
  precise float y = h + (g - h) * mu;
  precise float ry = y - u_camera.y;
  v_rel = vec3(rx, ry - a_skirt, rz);
  v_grid = vec2(a_grid) + centre_offset;
  v_morph = mu;
  // Padding beyond the field (non-square / non-power-of-two fields) is not terrain: clipped here
  // (enabled by the renderer only for padded trees) rather than discarded in the fragment shader,
  // because a shader that can discard loses the early depth test (a software rasteriser then
  // shades every hidden fragment). Linear in the grid, so it cuts where the discard did.
  gl_ClipDistance[0] = float(u_field_size.x - 1) + 1e-3 - v_grid.x;
  gl_ClipDistance[1] = float(u_field_size.y - 1) + 1e-3 - v_grid.y;
  gl_Position = u_view_projection * vec4(v_rel, 1.0);
#if SYLVA_TERRAIN_AIR == 1 || SYLVA_TERRAIN_AIR == 3
  v_air_extinction = air_extinction(v_rel);
#endif
#if SYLVA_TERRAIN_AIR == 3
  v_air_sky = atmosphere_radiance(normalize(v_rel));
#endif
}
