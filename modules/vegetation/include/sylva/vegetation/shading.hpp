#pragma once
// Leaf and bark shading settings and the CPU twins of the shading formulas of seed 000 §3.2
// (shaders/lib/leaf_shading.glsl evaluates the same expressions).
//
//   L = sun * (N.L D + spec S + translucency T) + ambient(N) A            (eqs. 3.20, 3.33)
//   D = A = c_v + c_s + instance variation,  T = (c_v + c_s + variation) * translucent_color,
//   S = specular_color                                                    (eq. 3.34; c_t = c_v)
//
// Specular: Cook-Torrance (Cook & Torrance 1981) in its standard form - the seed's eq. 3.23 lost
// the N.H dependence of the Beckmann exponent and eq. 3.24 the square of the Fresnel ratio
// (errata 3, 4):
//   R = exp((NH^2 - 1) / (sigma^2 NH^2)) / (sigma^2 NH^4)
//   c = H.E, g = sqrt(n^2 + c^2 - 1),
//   F = 1/2 ((g - c)/(g + c))^2 (1 + ((c (g + c) - 1) / (c (g - c) + 1))^2)
//   G = min(1, 2 NH NE / EH, 2 NH NL / EH)
//   BRDF = R F G / (pi NL NE); the reflected radiance is BRDF * NL.
// Translucency: eq. 3.32 with the Half-Life-2 coefficients of the side facing the viewer (see
// textures.hpp), evaluated only when the sun is behind the visible side.

#include <sylva/core/params.hpp>

#include <glm/glm.hpp>

#include <array>

namespace sylva::vegetation {

// How leaf outlines become pixels (the seed lost its distant leaves to the alpha test, §5).
//  kAlphaToCoverage: multisampled targets; the alpha is sharpened to one pixel where the texture is
//    magnified and is the box-filtered coverage where it is minified, so a sub-pixel leaf covers
//    its share of the samples. The shader writes the sample mask itself with a hashed dither
//    (shaders/lib/leaf_alpha.glsl) because the fixed patterns of GL_SAMPLE_ALPHA_TO_COVERAGE give
//    overlapping leaves the same samples and thin out distant crowns.
//  kHashedAlphaTest: single-sampled targets; threshold 0.5 where magnified, a hashed threshold
//    (Wyman & McGuire, "Hashed Alpha Testing", I3D 2017) on the box-filtered coverage where
//    minified, so the expected covered share stays right at any distance. The hash is taken on the
//    rest object-space position in power-of-two cells of the pixel footprint: stable under wind.
//  kAlphaTest: threshold 0.5 everywhere (the seed's behaviour), on coverage-preserving mipmaps.
//  kAuto: alpha-to-coverage on multisampled targets, else hashed. Depth passes use the hashed (or,
//    for kAlphaTest, the plain) test, the same as the colour pass of a single-sampled target.
enum class AlphaMode { kAuto, kAlphaToCoverage, kHashedAlphaTest, kAlphaTest };
constexpr std::array<EnumName<AlphaMode>, 4> enum_names(AlphaMode) {
  return {{{AlphaMode::kAuto, "auto"},
           {AlphaMode::kAlphaToCoverage, "alpha_to_coverage"},
           {AlphaMode::kHashedAlphaTest, "hashed_alpha_test"},
           {AlphaMode::kAlphaTest, "alpha_test"}}};
}

struct ShadingSettings {
  float roughness = 0.35f;                         // sigma of the Beckmann distribution
  float refractive_index = 1.45f;                  // n of the leaf cuticle (waxes ~1.4-1.5)
  glm::vec3 specular_color{0.25f, 0.25f, 0.22f};   // M_specular
  glm::vec3 translucent_color{1.2f, 1.35f, 0.6f};  // M_translucent: light through a leaf is yellow-green
  float diffuse = 1.0f;                            // M_diffuse scale
  float ambient = 1.0f;                            // M_ambient scale
  float season = 0.55f;                            // 0 = 1 January, 1 = a year later; wraps
  float leaf_season_spread = 0.2f;                 // seed §4.6: seasonCoord += 0.2 * leafSpecificNumber
  AlphaMode alpha_mode = AlphaMode::kAuto;         // see AlphaMode
  float bark_specular = 0.04f;

  template <class V>
  void visit(V& v) {
    v(roughness, "roughness", {.min = 0.02, .max = 1.0, .help = "Beckmann roughness of the leaf surface"});
    v(refractive_index, "refractive_index", {.min = 1.0, .max = 3.0, .help = "Refractive index of the leaf surface (Fresnel)"});
    v(specular_color, "specular_color", {.min = 0.0, .max = 10.0, .help = "Specular colour M_specular"});
    v(translucent_color, "translucent_color", {.min = 0.0, .max = 10.0, .help = "Translucent colour M_translucent"});
    v(diffuse, "diffuse", {.min = 0.0, .max = 10.0, .help = "Diffuse scale M_diffuse"});
    v(ambient, "ambient", {.min = 0.0, .max = 10.0, .help = "Ambient scale M_ambient"});
    v(season, "season", {.min = -1000.0, .max = 1000.0, .help = "Time of year (0 = 1 January, 1 = one year)"});
    v(leaf_season_spread, "leaf_season_spread", {.min = 0.0, .max = 1.0, .help = "Season offset spread between leaves"});
    v(alpha_mode, "alpha_mode", {.help = "Leaf edges: alpha-to-coverage or alpha test"});
    v(bark_specular, "bark_specular", {.min = 0.0, .max = 1.0, .help = "Bark specular strength"});
  }
};

// Cook-Torrance terms (standard forms above); n, l, e (towards the eye) unit vectors.
float beckmann(float n_dot_h, float sigma);
float fresnel_cook_torrance(float h_dot_e, float refractive_index);
float geometric_attenuation(float n_dot_h, float n_dot_e, float n_dot_l, float e_dot_h);
// BRDF * N.L (0 when the light or the eye is below the surface).
float cook_torrance_specular(const glm::vec3& n, const glm::vec3& l, const glm::vec3& e, float sigma, float refractive_index);

}  // namespace sylva::vegetation
