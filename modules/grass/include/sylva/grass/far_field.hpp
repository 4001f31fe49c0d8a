#pragma once
// The far field of seed 003: blades near (GrassField), camera-independent billboard clumps in the
// middle distance, a textured ground layer far, with cross-fades instead of pops.
//
// - Clumps (seed 003 §2.4): two crossed vertical quads with a random rotation, placed by the
//   same world-anchored tile sampler as the blades (generator.hpp) at clumps_per_m2 times the
//   density map. They do not turn towards the camera (seed 003's billboards do not either), so
//   nothing changes when only the camera rotates. Texture: a procedural atlas of strands whose
//   alpha holds a graded threshold per strand (seed 003 §2.4.2); a fragment is kept when its
//   strand's threshold is below density * fade, so density and fades add or remove whole
//   strands one by one instead of fading alpha. Tops sway with the shared wind.
// - Ground layer (seed 003 §2.5): the height field's surface, lifted by ground_offset, textured
//   with a procedural top-view grass texture whose alpha is histogram-equalised noise, kept
//   where alpha < density * fade: the density interpolates per pixel (seed 003's per-vertex
//   density fix for seams, done by sampling the density map itself) and no seams appear.
// - Fades: for a distance d from the camera,
//     blades:    culling.hpp keep(d), ends at cull.near_distance;
//     clumps:    ramp(d; near_distance - clump_fade_in, near_distance) * (1 - ramp(d; mid_distance - mid_fade, mid_distance));
//     ground:    ramp(d; mid_distance - mid_fade, mid_distance) * (1 - ramp(d; far_distance - far_fade, far_distance)),
//   ramp(d; a, b) = clamp((d - a) / (b - a), 0, 1). Each representation's coverage therefore
//   changes continuously with distance; the GL test dollies through the transitions and checks
//   that the covered share of the picture changes by at most 1 % per frame.
//
// Ground coverage model. Blades and clumps are vertical, so the share of ground they hide grows
// as the view gets flatter; a flat texture does not. The ground layer therefore keeps a texel
// when alpha < density * fade * coverage(theta), a Beer-Lambert estimate of what the blades
// would hide: coverage = 1 - exp(-gain * (tau_top + tau_side * cot(theta))) with theta the view
// elevation above the surface, tau_side = blades/m^2 * mean width * mean height * 2/pi (mean
// projected side area of randomly turned blades) and tau_top = 0.2 * that (leaning tips).
// ground_coverage() is its CPU twin; the dolly test calibrates coverage_gain.
//
// Under-layer (not in seed 003). Seed 003 lets the terrain show between blades and between
// clumps; any difference between that terrain and the grass then reads as a band where the
// blades thin into clumps (measured 35..150 m). With `under_layer` the ground layer draws from
// the camera on: where the threshold above rejects a texel but the density map has grass (alpha <
// density), it draws undergrowth (the grass's mean colour times `under_shade`, same light). The
// seed's far texture keeps its role: it is the top-view grass that takes over beyond the clumps.
// All three representations share grass/color.glsl (albedo, dry tips, light) and the colour
// field of field_color.hpp, and `clump_brightness` / `ground_brightness` calibrate their means
// to the blades' (grass_band_gl_test measures the field's brightness in distance bins).
//
// Wide billboards (seed 003 §2.4.3, Tab. 4.2; off by default). A second middle sub-level:
// beyond wide_distance the small clumps give way (cross-fade over wide_fade) to wide_per_group
// billboards per group of wide_group x wide_group tiles (the thesis: 20 per 5 x 5 tiles at the
// densest; 20 ceil(N/5)^2 for an N x N map). A group is clipped to the map (the thesis groups the
// map's tiles), holds wide_per_group x its mean density of billboards (stochastic rounding), each
// as wide as the clipped group's longer side, so no billboard reaches far beyond the grass. They
// are clumps (same record, shaders and sway) placed by the tile sampler on the group grid. The
// strand texture repeats along the width (strands keep their size) and a strand is kept below
// fade * wide_keep, wide_keep = min(1, small strand length per m^2 / wide strand length per
// m^2) per group (in Clump::size.z): the thesis's "shifted alpha threshold" (§2.4.2), so the wide
// level shows about as much grass as the small one. Not worth it on small maps (thesis §4.2).
//
// Overcrowding guard (seed 003 §2.4.2, Tab. 4.5's step between density 5 and 6; off by default).
// With dense_extra_billboards, a tile whose mean density (density integral / its area inside the
// map) is above 0.5 gets dense_extra_per_tile clumps more than the plain rule's n (placed by the
// tile sampler, following the map), and every strand of the tile is kept below fade * k with k =
// dense_keep: the threshold at which (n + extra) clumps cover as much as n clumps at 1, i.e.
// (n + extra) c(k) = n c(1), c(t) = share of the atlas's texels with alpha < t (one clump's cover).
// Under independent (Poisson) overlap of clumps the expected covered share of the tile is then the
// plain rule's. The thesis gives neither the counts nor the shift; this is our rule. Keeping the
// strand count instead (k = n / (n + extra)) covered 8 % more: fewer strands per clump overlap
// less inside the atlas. k moves in the atlas's strand steps (56 per cell). The keep is in
// Clump::size.z (the small clumps' rank is not used by the shaders).
//
// Noise sub-regions (seed 003 §2.5, Fig. 3.15; off by default). With noise_subregions the ground
// layer's texture is no longer one world-space mapping: each far tile of noise_tile x noise_tile
// metres (world-anchored grid) samples the texture at a random offset and quarter turn
// (noise_subregion(), hashed from the tile's key: deterministic). The density stays per pixel
// (continuous across tiles, the thesis's per-vertex fix) and the alpha is equalised in every
// sub-region, so the covered share does not change; only the pattern no longer repeats with the
// texture. The thesis's caveat holds: the noise does not join at a tile border (visible where the
// pattern is coarse against the tile).
//
// Coarse far ground (seed 003 §4.3 "another far sub-level with much larger polygons"; off by
// default). With coarse_ground the ground layer also gets coarse chunks, each covering
// coarse_spacing_factor^2 ordinary chunks with the same 16 x 16 quads at coarse_spacing_factor
// times the spacing. A coarse chunk whose nearest point is at least coarse_distance away is drawn
// instead of its ordinary chunks. Its outer ring of quads is drawn per side either with coarse
// edges (the neighbour is coarse too, or there is none) or stitched to the ordinary chunks'
// vertices (the neighbour is drawn ordinary), so the layer stays watertight without skirts.
//
// Height fields only. A mesh surface gets one when the mesh is a height field
// (mesh_height_field.hpp rasterises it into one); otherwise it draws its blades to near_distance.
//
// Tile-local updates (issue 16). After a map or ground edit, update_region() remakes only what the
// edit reaches: the clumps of the tiles (and wide-billboard groups) whose maps changed, the texels
// of the margin-extended maps (extend_maps) whose samples lie in the edit, the changed texels of the
// density and tint textures (glTextureSubImage2D) and, after a ground edit, the ground layer's
// vertices within two samples of it (glNamedBufferSubData of the changed range) and the bounds of
// the chunks holding them. Clumps are a function of their tile alone (world-anchored sampler), so
// the result equals create() with the same inputs bit for bit (far_field_edit_gl_test compares records, GPU buffers and textures; the scene's
// grass_tile_edit_gl_test the pictures). A tint map that appears, or maps of another size or
// rectangle, need create() again.

#include <sylva/core/height_field.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/result.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/grass/generator.hpp>
#include <sylva/grass/maps.hpp>
#include <sylva/grass/settings.hpp>
#include <sylva/render/buffer.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/drawable.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/texture.hpp>
#include <sylva/render/vertex_array.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace sylva::grass {

struct FarFieldSettings {
  bool clumps = true;
  bool ground = true;
  float clumps_per_m2 = 0.9f;     // clumps per square metre at density 1 [1/m^2]
  float clump_width = 0.9f;       // width of a clump quad [m]
  float clump_fade_in = 15.0f;    // clumps grow in over this band before cull.near_distance [m]
  float mid_distance = 150.0f;    // clumps end, the ground layer is complete [m]
  float mid_fade = 40.0f;         // clump -> ground cross-fade band before mid_distance [m]
  float far_distance = 2000.0f;   // the ground layer ends [m]
  float far_fade = 200.0f;        // ground fade-out band before far_distance [m]
  float ground_offset = 0.03f;    // ground layer lift above the surface [m]
  float ground_spacing = 2.0f;    // vertex spacing of the ground layer mesh [m], rounded to height-field samples
  float texture_scale = 3.0f;     // world metres per repeat of the ground texture [m]
  float sway = 0.5f;              // clump sway relative to the blades' wind response
  float coverage_gain = 0.6f;     // calibration of the ground layer's coverage model (see below)
  bool receive_shadows = true;    // clumps and ground layer receive the render core's sun shadows
  // Under-layer (header comment): the ground layer also draws from the camera on, as undergrowth.
  bool under_layer = true;
  float under_shade = 1.0f;       // undergrowth albedo relative to the layer's grass texels
  // Brightness calibrations: the mean of each far representation against the blades' mean at
  // the same place (measured, README "Colour and brightness across the LODs").
  float clump_brightness = 0.635f;
  float ground_brightness = 0.45f;
  float lift_per_m = 0.0005f;     // extra ground-layer lift per metre of distance [m/m]
  // Margins: clumps and the ground layer continue beyond the blades' rectangle with the density
  // (and height, tint) of its edge, so a field of blades near the camera can run to the horizon.
  float clump_margin = 0.0f;      // [m]
  float ground_margin = 0.0f;     // [m]
  // No far grass on cliffs: clumps and the ground layer thin out between max_slope_deg - 8 and
  // max_slope_deg of ground slope, so margins that reach mountains leave their rock bare.
  float max_slope_deg = 40.0f;    // [deg]; 90 = grass on any slope
  // Wide billboards (header comment; seed 003 §2.4.3, Tab. 4.2). Off: the shipped look.
  bool wide_billboards = false;
  float wide_distance = 80.0f;    // small clumps are replaced from here on [m]
  float wide_fade = 20.0f;        // small -> wide cross-fade band before wide_distance [m]
  int wide_group = 5;             // tiles per side of a group (thesis: 5)
  float wide_per_group = 20.0f;   // wide billboards per group at density 1 (thesis: 20)
  // Overcrowding guard (header comment; seed 003 §2.4.2, Tab. 4.5). Off: the shipped look.
  bool dense_extra_billboards = false;
  int dense_extra_per_tile = 4;   // extra clumps per tile above 50 % of the maximum density
  // Random noise sub-regions per far tile (header comment; seed 003 §2.5). Off: the shipped look.
  bool noise_subregions = false;
  float noise_tile = 8.0f;        // side of a far tile that gets its own sub-region [m]
  // Coarse far ground sub-level (header comment; seed 003 §4.3). Off: the shipped look.
  bool coarse_ground = false;
  float coarse_distance = 400.0f; // coarse chunks are drawn from this distance on [m]
  int coarse_spacing_factor = 4;  // coarse mesh spacing / ground layer spacing

  template <class V>
  void visit(V& v) {
    v(clumps, "clumps", {.help = "Draw billboard clumps in the middle distance"});
    v(ground, "ground", {.help = "Draw the textured ground layer far away"});
    v(clumps_per_m2, "clumps_per_m2", {.min = 0.01f, .max = 20.0f, .unit = "1/m^2", .help = "Clump density at density 1",
                                       .rebuild = Rebuild::kOffline});
    v(clump_width, "clump_width", {.min = 0.05f, .max = 5.0f, .unit = "m", .help = "Width of a clump",
                                   .rebuild = Rebuild::kOffline});
    v(clump_fade_in, "clump_fade_in", {.min = 0.0f, .max = 500.0f, .unit = "m", .help = "Blade-to-clump cross-fade band"});
    v(mid_distance, "mid_distance", {.min = 1.0f, .max = 10000.0f, .unit = "m", .help = "Where clumps end"});
    v(mid_fade, "mid_fade", {.min = 0.0f, .max = 1000.0f, .unit = "m", .help = "Clump-to-ground cross-fade band"});
    v(far_distance, "far_distance", {.min = 1.0f, .max = 100000.0f, .unit = "m", .help = "Where the ground layer ends"});
    v(far_fade, "far_fade", {.min = 0.0f, .max = 10000.0f, .unit = "m", .help = "Ground layer fade-out band"});
    v(ground_offset, "ground_offset", {.min = 0.0f, .max = 1.0f, .unit = "m", .help = "Lift of the ground layer"});
    v(ground_spacing, "ground_spacing", {.min = 0.25f, .max = 64.0f, .unit = "m", .help = "Ground layer mesh spacing",
                                         .rebuild = Rebuild::kOffline});
    v(texture_scale, "texture_scale", {.min = 0.1f, .max = 100.0f, .unit = "m", .help = "Ground texture repeat"});
    v(sway, "sway", {.min = 0.0f, .max = 4.0f, .help = "Clump sway relative to blades"});
    v(coverage_gain, "coverage_gain", {.min = 0.0f, .max = 10.0f,
                                       .help = "Scales the ground layer's coverage to match the blades"});
    v(receive_shadows, "receive_shadows", {.help = "Clumps and the ground layer receive the sun's cascaded shadows"});
    v(under_layer, "under_layer", {.help = "The ground layer also draws near the camera, as undergrowth between the blades"});
    v(under_shade, "under_shade", {.min = 0.0f, .max = 2.0f, .help = "Undergrowth brightness relative to the layer's grass"});
    v(clump_brightness, "clump_brightness", {.min = 0.0f, .max = 4.0f, .help = "Clump brightness calibration against the blades"});
    v(ground_brightness, "ground_brightness", {.min = 0.0f, .max = 4.0f,
                                               .help = "Ground layer brightness calibration against the blades"});
    v(lift_per_m, "lift_per_m", {.min = 0.0f, .max = 0.1f, .unit = "m/m", .help = "Ground layer lift per metre of distance"});
    v(clump_margin, "clump_margin", {.min = 0.0f, .max = 10000.0f, .unit = "m",
                                     .help = "Clumps continue this far beyond the grass area", .rebuild = Rebuild::kOffline});
    v(ground_margin, "ground_margin", {.min = 0.0f, .max = 100000.0f, .unit = "m",
                                       .help = "The ground layer continues this far beyond the grass area", .rebuild = Rebuild::kOffline});
    v(max_slope_deg, "max_slope_deg", {.min = 8.0f, .max = 90.0f, .unit = "deg",
                                       .help = "Clumps and the ground layer thin out on slopes steeper than this", .rebuild = Rebuild::kOffline});
    v(wide_billboards, "wide_billboards", {.help = "Seed 003 wide billboards over tile groups beyond wide_distance",
                                           .rebuild = Rebuild::kOffline});
    v(wide_distance, "wide_distance", {.min = 0.0f, .max = 10000.0f, .unit = "m",
                                       .help = "Wide billboards replace the small clumps from this distance"});
    v(wide_fade, "wide_fade", {.min = 0.0f, .max = 1000.0f, .unit = "m", .help = "Small-to-wide billboard cross-fade band"});
    v(wide_group, "wide_group", {.min = 1, .max = 64, .help = "Tiles per side of a wide-billboard group",
                                 .rebuild = Rebuild::kOffline});
    v(wide_per_group, "wide_per_group", {.min = 1.0f, .max = 1000.0f, .help = "Wide billboards per group at density 1",
                                         .rebuild = Rebuild::kOffline});
    v(dense_extra_billboards, "dense_extra_billboards",
      {.help = "Seed 003 overcrowding guard: more clumps with a shifted strand threshold above 50 % density",
       .rebuild = Rebuild::kOffline});
    v(dense_extra_per_tile, "dense_extra_per_tile", {.min = 1, .max = 256, .help = "Extra clumps per tile above 50 % density",
                                                     .rebuild = Rebuild::kOffline});
    v(noise_subregions, "noise_subregions", {.help = "Seed 003: each far tile samples a random sub-region of the ground texture"});
    v(noise_tile, "noise_tile", {.min = 0.5f, .max = 10000.0f, .unit = "m", .help = "Side of a far tile with its own noise sub-region"});
    v(coarse_ground, "coarse_ground", {.help = "Seed 003 future work: a coarse ground layer sub-level beyond coarse_distance",
                                       .rebuild = Rebuild::kOffline});
    v(coarse_distance, "coarse_distance", {.min = 0.0f, .max = 100000.0f, .unit = "m",
                                           .help = "Coarse ground chunks are drawn from this distance on"});
    v(coarse_spacing_factor, "coarse_spacing_factor", {.min = 2, .max = 16, .help = "Coarse ground mesh spacing over the layer's spacing",
                                                       .rebuild = Rebuild::kOffline});
  }
};

// `maps` over its rectangle grown by `margin` metres on every side; outside the original rectangle
// every map continues its edge value. Texels keep the density map's size up to 2048 per side.
Result<GrassMaps> extend_maps(const GrassMaps& maps, double margin);

// extend_maps' images, kept so that an edit resamples only its texels. Empty rect: margin 0 (the
// maps are used as they are).
struct ExtendedMapImages {
  Rect rect;
  Image density, height, tint;
  Result<GrassMaps> maps() const { return GrassMaps::from_images(rect, &density, &height, &tint); }
};
ExtendedMapImages extend_map_images(const GrassMaps& maps, double margin);
// Resamples the texels of `images` whose sample point lies in `changed` (a rectangle of `maps`
// where its interpolant changed) and returns the rectangle where the extended interpolant may
// have changed (those texels' cells grown by one texel); empty when no texel was resampled.
Rect refresh_extended_map_images(ExtendedMapImages& images, const GrassMaps& maps, const Rect& changed);

// Share in [0, 1] of far grass kept on ground whose normal has this y (max_slope_deg above).
float slope_keep(float normal_y, float max_slope_deg);

// Fade weights in [0, 1] of the three representations at distance d (header comment). With
// wide_billboards, clump_fade is the small clumps' (times 1 - the wide ramp) and wide_fade_at the
// wide billboards' share before wide_keep.
float clump_fade(float distance, float near_distance, const FarFieldSettings& s);
float wide_fade_at(float distance, float near_distance, const FarFieldSettings& s);
// wide_keep of the header comment, in (0, 1], for a group of `group_area` [m^2] whose
// billboards are `width` [m] wide.
float wide_keep(const FarFieldSettings& s, double group_area, float width);
float ground_fade(float distance, const FarFieldSettings& s);
// Ground coverage model (above); sin_elevation = |dot(view direction, surface normal)|.
float ground_coverage(float sin_elevation, float tau_side, float tau_top, float gain);

// Coverage curve of a clump atlas (make_clump_atlas): its texels' alphas, sorted;
// clump_coverage(curve, t) = share of atlas texels with alpha < t, c(t) of the header comment.
std::vector<float> clump_coverage_curve(const Image& atlas);
double clump_coverage(const std::vector<float>& curve, float threshold);
// dense_keep of the header comment for a tile whose plain rule places `plain_count` clumps when
// `extra` more are added: the threshold whose c is nearest n / (n + extra) c(1), halfway between
// two strand thresholds (robust to 8-bit alpha); 1 without extras.
float dense_keep(double plain_count, int extra, const std::vector<float>& curve);

// The noise sub-region of far tile (tx, tz) (header comment): offset in texture repeats, [0, 1)^2,
// and quarter turns 0..3. shaders/far.glsl grass_noise_subregion() is its bit-exact twin.
struct NoiseSubregion {
  glm::vec2 offset{0.0f};
  int quarter_turns = 0;
};
NoiseSubregion noise_subregion(std::int32_t tx, std::int32_t tz, std::uint32_t seed);

// One clump (std430, 3 x vec4 = 48 bytes; shaders/far.glsl mirrors it).
struct Clump {
  glm::vec4 root;   // xyz root (blade-set local), w rotation [rad]
  glm::vec4 size;   // x width, y height [m], z rank [0, 1) (wide billboards: strand keep), w atlas cell (0..3)
  glm::vec4 color;  // rgb colour multiplier (per clump variation x tint), w sway phase [0, 1)
};
static_assert(sizeof(Clump) == 48);

struct ClumpSet {
  glm::dvec3 origin{0.0};
  std::vector<Clump> clumps;
  std::vector<GrassTile> tiles;  // runs of clumps, bounds for culling
};

// World-anchored clumps for every tile overlapping maps.rect() (same tiles as the blades); with
// `within`, only the tiles of clump_tile_range(maps.rect(), *within, tile) (update_region).
Result<ClumpSet> generate_clumps(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                                 const HeightField& ground, const glm::dvec3& origin, const FarFieldSettings& far,
                                 const Rect* within = nullptr);

// Wide billboards over groups of far.wide_group^2 tiles (header comment); tiles are the groups.
Result<ClumpSet> generate_wide_billboards(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                                          const HeightField& ground, const glm::dvec3& origin, const FarFieldSettings& far,
                                          const Rect* within = nullptr);

// The tiles of side `tile` [m] overlapping both the clumps' area and `within`; empty (x0 == x1)
// when they do not meet.
TileRange clump_tile_range(const Rect& area, const Rect& within, double tile);

// The ground layer's mesh (GL-free; FarField::create uploads it). Vertices: xyz blade-set local
// position, xyz normal, rgb field colour. `chunks`: 16 x 16 quads each; `coarse` (coarse_ground
// only): chunks over coarse_spacing_factor^2 of them (header comment), their interior and, per
// side (0 -x, 1 +x, 2 -z, 3 +z), the outer ring with coarse edges [0] or stitched [1].
struct GroundChunk {
  std::uint32_t first_index = 0;
  std::uint32_t index_count = 0;
  glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};
  // The vertices its bounds are taken over (a coarse chunk's interior: its own and its stitched
  // sides'), so an edit can refresh them.
  std::uint32_t first_vertex = 0;
  std::uint32_t vertex_count = 0;
};
struct CoarseGroundChunk {
  GroundChunk interior;  // bounds: the whole coarse chunk
  GroundChunk sides[4][2];
  std::vector<std::uint32_t> fine;      // the ordinary chunks it covers
  std::int32_t neighbour[4] = {-1, -1, -1, -1};  // coarse chunk across each side, -1 none
};
struct GroundLayerMesh {
  std::vector<float> vertices;
  std::vector<glm::ivec2> samples;  // per vertex: the height-field sample it stands on
  std::vector<std::uint32_t> indices;
  std::vector<GroundChunk> chunks;
  std::vector<CoarseGroundChunk> coarse;
};
inline constexpr std::size_t kGroundVertexFloats = 9;
Result<GroundLayerMesh> build_ground_layer(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                                           const HeightField& ground, const glm::dvec3& origin, const FarFieldSettings& far);

// Procedural textures (deterministic for a seed). Billboard atlas: 2 x 2 cells of `size`/2,
// RGBA: rgb strand colour (root dark, tip light), a = strand threshold (graded, uniform in
// [0, 1) over strands), 1 where there is no strand. Ground: RGBA tileable top-view grass, rgb
// colour, a = histogram-equalised noise (exactly uniform: coverage = threshold).
Image make_clump_atlas(int size, std::uint32_t seed);
Image make_ground_texture(int size, std::uint32_t seed);

// A mip chain (level 0 = `level0`, halving to 1 x 1) whose colour is box-filtered and whose alpha
// is histogram-matched to level 0: the share of texels with alpha < f is the same at every
// level for every f. Alpha-threshold coverage therefore does not drift with distance (plain
// mipmaps average thresholds towards 0.5 and make distant grass pop in or vanish), and each
// level is smooth, so coverage does not flicker from frame to frame. Power-of-two square input.
std::vector<Image> coverage_preserving_mips(const Image& level0);

// GL renderer of clumps and ground layer for one grass field.
class FarField : public render::Drawable {
 public:
  FarField() = default;
  static Result<FarField> create(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                                 const HeightField& ground, const glm::dvec3& origin, const FarFieldSettings& far = {});

  FarFieldSettings& settings() { return settings_; }

  // Tile-local update after an edit (header comment "Tile-local updates"): `areas` are the world
  // rectangles where the maps' interpolants (or, with ground_changed, the ground's heights)
  // changed, as for regenerate_tiles. `field`, `blade`, the origin and the far settings must be
  // create()'s; `maps` and `ground` are the edited ones. Errors (the far field is then unchanged
  // on the GPU but may hold partly updated CPU data: rebuild it with create()): a maps rectangle,
  // map size or tint presence other than at create() ("needs a full rebuild"), or those of create().
  Status update_region(const GrassFieldSettings& field, const BladeSettings& blade, const GrassMaps& maps,
                       const HeightField& ground, std::span<const Rect> areas, bool ground_changed);

  // What the far field holds, for tests comparing an update with a rebuild. CPU: the clump records
  // (small clumps, then wide billboards), tiles, the density and tint images of the textures, the
  // ground layer's vertices and chunks; GPU: the same read back (first clump_records().size() records).
  const std::vector<Clump>& clump_records() const { return clump_records_; }
  const std::vector<GrassTile>& clump_tiles() const { return clump_tiles_; }
  const std::vector<GrassTile>& wide_tiles() const { return wide_tiles_; }
  const Image& density_image() const { return density_image_; }
  const Image& tint_image() const { return tint_image_; }
  const std::vector<float>& ground_vertices() const { return ground_vertex_data_; }
  const std::vector<GroundChunk>& ground_chunks() const { return chunks_; }
  const std::vector<CoarseGroundChunk>& coarse_ground_chunks() const { return coarse_chunks_; }
  std::vector<Clump> read_clump_buffer() const;
  std::vector<float> read_ground_vertex_buffer() const;
  Image read_density_texture() const;
  Image read_tint_texture() const;
  // The blades' culling, wind response, colours and shading (ambient, translucency: ShadingSettings),
  // so the far representations match the near field.
  void set_near(float near_distance, float wind_response, float mean_stiffness, const glm::vec3& base_color,
                const glm::vec3& tip_color, float ambient = 0.35f, float translucency = 0.5f);
  // Seed 003 §3.4 motion by colour (ShadingSettings::color_motion, color_motion_hz); 0 = off.
  void set_color_motion(float amplitude, float hz) {
    color_motion_ = amplitude;
    color_motion_hz_ = hz;
  }

  void update(const render::FrameContext& frame) override;
  void draw(render::Pass pass, const render::FrameContext& frame, render::PassStats& stats) override;
  void update(const render::Camera& camera, glm::ivec2 viewport);
  void draw_far(const render::Camera& camera, const WindField& wind, double time, render::PassStats* stats = nullptr);

  std::size_t clump_count() const { return clump_count_; }
  std::uint64_t last_clumps_drawn() const { return clumps_drawn_; }
  std::uint64_t last_ground_chunks_drawn() const { return ground_drawn_; }
  // Coarse ground chunks among them (coarse_ground).
  std::uint64_t last_coarse_chunks_drawn() const { return coarse_drawn_; }
  std::size_t wide_billboard_count() const { return wide_count_; }
  std::uint64_t last_wide_billboards_drawn() const { return wide_drawn_; }

 private:
  // The clump buffer holds clump_records_ in room for clump_capacity_ records (an edit that adds
  // clumps re-uploads from its first changed record without reallocating).
  void upload_clumps(std::size_t first_changed);
  // update_region's ground edit: the ground layer's vertices within reach of `areas`.
  void update_ground_layer(const GrassFieldSettings& field, const BladeSettings& blade, const HeightField& ground,
                           std::span<const Rect> areas);

  FarFieldSettings settings_;
  FarFieldSettings built_;  // the settings create() generated with (update_region uses them)
  glm::dvec3 origin_{0.0};
  std::vector<Clump> clump_records_;
  std::size_t clump_capacity_ = 0;
  ExtendedMapImages clump_map_images_;  // extend_maps(maps, clump_margin); empty rect: margin 0
  Image density_image_;
  Image tint_image_;
  std::vector<float> ground_vertex_data_;
  std::vector<glm::ivec2> ground_samples_;  // GroundLayerMesh::samples
  float near_distance_ = 50.0f;
  float wind_response_ = 6.0f;
  float mean_stiffness_ = 60.0f;
  float tau_side_ = 0.0f;
  float tau_top_ = 0.0f;
  glm::vec3 base_color_{0.045f, 0.16f, 0.035f};
  glm::vec3 tip_color_{0.32f, 0.50f, 0.13f};
  float ambient_ = 0.35f;
  float translucency_ = 0.5f;
  float color_motion_ = 0.0f;
  float color_motion_hz_ = 0.5f;
  std::vector<GrassTile> clump_tiles_;
  std::vector<GroundChunk> chunks_;
  std::vector<std::uint32_t> visible_clump_tiles_;
  std::vector<CoarseGroundChunk> coarse_chunks_;
  std::vector<std::uint8_t> coarse_selected_;  // per coarse chunk: drawn coarse this frame
  std::vector<GroundChunk> ground_draws_;       // index ranges to draw this frame
  std::uint64_t coarse_drawn_ = 0;
  std::uint64_t ground_chunks_ = 0;  // chunks (ordinary or coarse) in ground_draws_
  std::uint32_t noise_seed_ = 0;
  bool dense_keeps_ = false;  // the clumps hold dense_keep in size.z (built with dense_extra_billboards)
  std::vector<GrassTile> wide_tiles_;  // groups; `first` indexes the clump buffer after the small clumps
  std::vector<std::uint32_t> visible_wide_tiles_;
  std::size_t wide_count_ = 0;
  std::uint64_t wide_drawn_ = 0;
  std::size_t clump_count_ = 0;
  std::uint64_t clumps_drawn_ = 0;
  std::uint64_t ground_drawn_ = 0;
  glm::vec3 camera_local_{0.0f};

  render::Buffer clumps_;
  render::Buffer ground_vertices_;
  render::Buffer ground_indices_;
  render::Buffer wind_;
  render::VertexArray clump_vao_;
  render::VertexArray ground_vao_;
  render::Texture atlas_;
  render::Texture ground_texture_;
  render::Texture density_;
  render::Texture tint_;   // the maps' tint (1 x 1 white without a tint map)
  bool tinted_ = false;    // whether the maps have a tint map (else the ground layer skips it)
  render::Program clump_program_;
  render::Program ground_program_;
  Rect map_rect_;
  Rect layer_rect_;  // the ground layer's rectangle: map_rect_ grown by ground_margin
};

}  // namespace sylva::grass
