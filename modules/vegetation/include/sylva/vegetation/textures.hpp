#pragma once
// Procedural textures for LOD0 trees (seed 000 §3.2, §4.3.2, §4.6), generated as core Images so
// they can be saved, inspected, replaced by painted ones and loaded back.
//
// Leaf textures per side (seed Fig. 3.15 c-f; the seed used R. Habel's data, we generate them):
//   color        RGBA: rgb = 0.5 + c_v, the colour deviation from the seasonal base colour
//                (eq. 3.34: diffuse = (c_v + c_s) M_d), alpha = outline coverage;
//   normal       RGBA: rgb = tangent-space normal * 0.5 + 0.5 (venation; veins are grooves on the
//                upper side and ribs on the lower side), alpha = thickness d in [0, 1];
//   translucency RGBA: rgb = 0.5 + 0.5 h_i, the Half-Life-2 basis coefficients of the precomputed
//                hemispherical convolution L_t^C (eqs. 3.28-3.31), alpha = transmittance rho_t.
// Tangent space: x = u (across the blade), y = v (base to tip), z = the side's normal.
//
// Leaf clusters (`cluster` > 1): the card shows a twig along v with cluster - 1 leaves alternating
// left and right and one terminal leaf, as the cluster cards of game foliage (SpeedTree, ez-tree):
// a crown of a few thousand cards then reads as foliage masses instead of single slivers. Each
// leaf has its own tint and a tilt about its midrib in the normal map, so one card shades as
// several leaves. cluster = 1 is the single leaf filling the card (bit-identical to before).
//
// Translucency precomputation (eq. 3.28): light arriving at texel x_i of the far side from
// direction L gives irradiance E(x_i, L) = max(n(x_i) . L, 0) with that side's normal map; it
// diffuses to x_0 through the kernel T(r, d) = exp(-r^2 / 2 sigma^2) exp(-k d(x_i)), normalised
// so that a flat leaf of zero thickness transmits E unchanged. The convolution for each of 64
// directions of the hemisphere is projected by least squares onto the three HL2 lobes
// sqrt(3 / 2 pi) H_i . L (eqs. 3.29-3.31), so the shader reconstructs it from one texture fetch
// (eq. 3.32).
//
// Season texture (§4.6): one column (width 1), sampled at (0.5, seasonCoord) with REPEAT and
// linear filtering as in the seed (errata 16); rgb = seasonal base colour c_s (linear), alpha =
// presence: leaves whose seasonal alpha is below 0.5 are discarded (budding, leaf fall).
//
// Alpha mipmaps (the seed's LOD0 lost its leaves at distance, §5): coverage_preserving_mips
// scales each level's alpha so that the share of texels above the alpha-test threshold stays that
// of level 0 (Castano, "Computing Alpha Mipmaps", 2010).

#include <sylva/core/image.hpp>
#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/vegetation/generator.hpp>

#include <glm/glm.hpp>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace sylva::vegetation {

struct LeafTextureSettings {
  int size = 256;                     // square texture side [px], power of two
  LeafShape shape = LeafShape::kOvate;
  int cluster = 1;                    // leaves (or needle sprays) per card, along one twig
  int veins = 7;                      // secondary veins per side of the midrib
  float serration = 0.0f;             // depth of edge teeth [0, 1]
  float vein_depth = 1.0f;            // strength of the venation in the normal map
  float color_variation = 0.05f;      // amplitude of the colour deviation c_v
  float back_lightness = 0.08f;       // the lower side is paler by this much
  float translucency = 0.6f;          // rho_t of the lamina
  float scattering_radius = 2.0f;     // sigma of the transport kernel [px]
  float thickness_absorption = 1.5f;  // k of the transport kernel
  std::uint32_t seed = 1;

  template <class V>
  void visit(V& v) {
    v(size, "size", {.min = 16, .max = 2048, .unit = "px", .help = "Texture side (power of two)", .rebuild = Rebuild::kGpu});
    v(shape, "shape", {.help = "Leaf outline", .rebuild = Rebuild::kGpu});
    v(cluster, "cluster", {.min = 1, .max = 16, .help = "Leaves per card: 1 = one leaf, more = a twig spray", .rebuild = Rebuild::kGpu});
    v(veins, "veins", {.min = 0, .max = 32, .help = "Secondary veins per side", .rebuild = Rebuild::kGpu});
    v(serration, "serration", {.min = 0.0, .max = 1.0, .help = "Depth of edge teeth", .rebuild = Rebuild::kGpu});
    v(vein_depth, "vein_depth", {.min = 0.0, .max = 4.0, .help = "Strength of the venation relief", .rebuild = Rebuild::kGpu});
    v(color_variation, "color_variation", {.min = 0.0, .max = 0.5, .help = "Amplitude of the colour deviation", .rebuild = Rebuild::kGpu});
    v(back_lightness, "back_lightness", {.min = -0.5, .max = 0.5, .help = "How much paler the lower side is", .rebuild = Rebuild::kGpu});
    v(translucency, "translucency", {.min = 0.0, .max = 1.0, .help = "Transmittance of the lamina", .rebuild = Rebuild::kGpu});
    v(scattering_radius, "scattering_radius", {.min = 0.1, .max = 16.0, .unit = "px", .help = "Light diffusion radius inside the leaf", .rebuild = Rebuild::kGpu});
    v(thickness_absorption, "thickness_absorption", {.min = 0.0, .max = 20.0, .help = "Absorption per unit thickness", .rebuild = Rebuild::kGpu});
    v(seed, "seed", {.min = 0.0, .max = 4294967295.0, .help = "Random seed", .rebuild = Rebuild::kGpu});
  }
};

struct LeafSide {
  Image color;         // RGBA8-ready, see above
  Image normal;
  Image translucency;
};

struct LeafTextures {
  LeafSide front;  // upper side (faces +n)
  LeafSide back;   // lower side
};

// The texture settings that suit a leaf shape (serration for birch, thin needles, ...).
LeafTextureSettings leaf_texture_settings_for(LeafShape shape, std::uint32_t seed = 1);
// Errors: invalid settings (kInvalidArgument naming the parameter, "leaf_texture.size").
Result<LeafTextures> generate_leaf_textures(const LeafTextureSettings& settings);

// Outline coverage of the shape at texture coordinate (u, v) in [0, 1]^2 for a texture of `size`
// pixels (anti-aliased over about one pixel). Exposed for tests.
float leaf_coverage(const LeafTextureSettings& settings, float u, float v);

// What a card texel shows: coverage in [0, 1], and for the topmost leaf there its own (u, v)
// (the single-leaf coordinates, blade base at v = 0) and index (0 .. cluster - 1; -1 = only the
// twig or nothing). With cluster = 1, (u, v) are the card's and leaf = 0.
struct ClusterSample {
  float coverage = 0.0f;
  float u = 0.0f;
  float v = 0.0f;
  int leaf = -1;
};
ClusterSample cluster_sample(const LeafTextureSettings& settings, float u, float v);

// Mean over the covered texels (alpha > 0.5) of the front side of the light passed straight
// through the leaf (eq. 3.32 for light along the far side's normal): the translucency strength of
// the image-based levels, which have no translucency maps. 0 for a texture with no covered texel.
float mean_leaf_transmittance(const LeafTextures& textures);

// The three HL2 basis vectors of eq. 3.29 (tangent space, z = normal).
std::array<glm::vec3, 3> hl2_basis();
// Reconstruction of eq. 3.32 without the light intensity: rho * max(0, sum h_i sqrt(3/2pi) H_i . L).
float hl2_reconstruct(const glm::vec3& h, float rho, const glm::vec3& light_tangent);

struct BarkTextureSettings {
  int size = 256;                          // square side [px], power of two; tiles in u and v
  glm::vec3 color{0.32f, 0.24f, 0.17f};    // linear albedo of the bark plates
  glm::vec3 furrow_color{0.10f, 0.075f, 0.06f};
  int furrows = 9;                         // furrows around the circumference (u)
  float furrow_depth = 1.0f;               // normal map strength
  float roughness = 0.5f;                  // fine noise share
  float horizontal_marks = 0.0f;           // birch-like horizontal lenticels [0, 1]
  std::uint32_t seed = 1;

  template <class V>
  void visit(V& v) {
    v(size, "size", {.min = 16, .max = 2048, .unit = "px", .help = "Texture side (power of two)", .rebuild = Rebuild::kGpu});
    v(color, "color", {.min = 0.0, .max = 1.0, .help = "Bark plate albedo (linear)", .rebuild = Rebuild::kGpu});
    v(furrow_color, "furrow_color", {.min = 0.0, .max = 1.0, .help = "Furrow albedo (linear)", .rebuild = Rebuild::kGpu});
    v(furrows, "furrows", {.min = 1, .max = 64, .help = "Furrows around the branch", .rebuild = Rebuild::kGpu});
    v(furrow_depth, "furrow_depth", {.min = 0.0, .max = 4.0, .help = "Relief strength", .rebuild = Rebuild::kGpu});
    v(roughness, "roughness", {.min = 0.0, .max = 1.0, .help = "Fine noise share", .rebuild = Rebuild::kGpu});
    v(horizontal_marks, "horizontal_marks", {.min = 0.0, .max = 1.0, .help = "Birch-like horizontal marks", .rebuild = Rebuild::kGpu});
    v(seed, "seed", {.min = 0.0, .max = 4294967295.0, .help = "Random seed", .rebuild = Rebuild::kGpu});
  }
};

struct BarkTextures {
  Image albedo;  // RGBA: rgb linear albedo, a 1
  Image normal;  // RGBA: rgb tangent-space normal * 0.5 + 0.5 (x around, y along), a height
};

BarkTextureSettings bark_texture_settings_for(SpeciesPreset preset, std::uint32_t seed = 1);
Result<BarkTextures> generate_bark_textures(const BarkTextureSettings& settings);

enum class SeasonPalette { kDeciduous, kBirch, kEvergreen };
constexpr std::array<EnumName<SeasonPalette>, 3> enum_names(SeasonPalette) {
  return {{{SeasonPalette::kDeciduous, "deciduous"}, {SeasonPalette::kBirch, "birch"}, {SeasonPalette::kEvergreen, "evergreen"}}};
}

// One key of a season palette: at season coordinate `at` (0 = 1 January, 1 = a year later) the
// base colour c_s (linear RGB) and the presence alpha.
struct SeasonKey {
  float at = 0.0f;
  glm::vec4 color{0.0f};
};
std::vector<SeasonKey> season_keys(SeasonPalette palette);
SeasonPalette season_palette_for(SpeciesPreset preset);

// 1 x rows RGBA image (see above); row 0 is the top of the image, i.e. the texel at v = 1 - 0.5/rows.
Image generate_season_texture(SeasonPalette palette, int rows = 64);
// What the GPU returns for texture(season, vec2(0.5, coord)) with REPEAT and LINEAR filtering.
glm::vec4 sample_season(const Image& season_texture, float coord);

// Mip chain of an RGBA image (level 0 = the image, down to 1x1): colour averaged weighted by
// alpha (no dark fringes), alpha box-filtered then scaled per level so the share of texels with
// alpha > threshold matches level 0. Width and height must be powers of two (asserted).
std::vector<Image> coverage_preserving_mips(const Image& rgba, float threshold = 0.5f);
// Plain box-filtered chain (for comparison in tests).
std::vector<Image> box_mips(const Image& rgba);
// Share of texels with alpha (channel 3) > threshold.
double alpha_coverage(const Image& rgba, float threshold = 0.5f);

// Images of any size resampled to width x height (bilinear, supersampled over the source
// footprint when shrinking). With `alpha_weighted` (4 channels), rgb is averaged weighted by
// alpha, so the background of a leaf photo does not bleed into the outline's texels.
Image resample_image(const Image& src, int width, int height, bool alpha_weighted = false);

// Leaf maps from painted or photographed images (species files; seed 000 §3.2, Fig. 3.15 a, b):
// the colour-deviation map is the original colour map minus the leaf's base colour (the mean
// over the covered texels), which comes back as the seasonal colour c_s (eq. 3.34); the original
// translucency map is an intensity map, rho_t, and the HL2 coefficients are precomputed from the
// normal map as for the generated leaves (eqs. 3.28-3.31). The lower side shows the same colour;
// its normal is the upper side's seen from below, (x, -y, z) in its mirrored tangent space.
struct LeafImages {
  Image color;         // RGBA, linear colour, alpha = outline coverage (required)
  Image normal;        // optional: RGB(A) upper-side tangent-space normal * 0.5 + 0.5 (x = u,
                       // y = v), alpha thickness in [0, 1] (default 0.25); empty: flat
  Image translucency;  // optional: rho_t (mean of rgb, or the one channel); empty: settings.translucency
};
struct LeafImageTextures {
  LeafTextures textures;
  glm::vec3 base_color{0.0f};  // linear mean colour of the covered texels
};
// Everything is resampled to settings.size (a power of two). Errors: invalid settings, an empty
// or non-RGBA colour image, an outline with no texel of alpha above 0.5 (kInvalidArgument).
Result<LeafImageTextures> leaf_textures_from_images(const LeafImages& images, const LeafTextureSettings& settings);
// Bark maps from images (tiling in u and v): albedo from `color` (RGB(A), linear), the normal
// from `normal` (RGB tangent-space * 0.5 + 0.5, x around, y along; A height) or flat when empty.
Result<BarkTextures> bark_textures_from_images(const Image& color, const Image& normal, int size);

// Saves the six leaf images as PNG (8-bit) files "<prefix>_{front,back}_{color,normal,translucency}.png"
// in `folder` (atomically, through core write_image), and loads them back. Load errors name the
// file; sizes of the six images must agree (kInvalidArgument naming the file).
Status save_leaf_textures(const std::filesystem::path& folder, const std::string& prefix, const LeafTextures& textures);
Result<LeafTextures> load_leaf_textures(const std::filesystem::path& folder, const std::string& prefix);
Status save_bark_textures(const std::filesystem::path& folder, const std::string& prefix, const BarkTextures& textures);
Result<BarkTextures> load_bark_textures(const std::filesystem::path& folder, const std::string& prefix);

}  // namespace sylva::vegetation
