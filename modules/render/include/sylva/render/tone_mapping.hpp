#pragma once
// HDR -> display: exposure, a tone curve and sRGB encoding as one small full-screen post pass
// (issue 7). Operators:
//  - kAces (default): Narkowicz's 2015 fit of the ACES RRT+ODT curve,
//    f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clamped to [0, 1]; filmic toe and
//    shoulder, slight contrast boost.
//  - kReinhard: f(x) = x / (1 + x) per channel (keeps hue better, flatter).
// Then the exact sRGB OETF (IEC 61966-2-1, linear segment below 0.0031308). NaN and negative
// inputs become 0 and +inf becomes white, so a broken pixel upstream never poisons the output.
// Shaders: "render/tone_map.vert" + "render/tone_map.frag" (HDR texture at unit 0).

#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/texture.hpp>
#include <sylva/render/vertex_array.hpp>

#include <array>

namespace sylva::render {

enum class ToneOperator { kAces, kReinhard };

constexpr std::array<EnumName<ToneOperator>, 2> enum_names(ToneOperator) {
  return {{{ToneOperator::kAces, "aces"}, {ToneOperator::kReinhard, "reinhard"}}};
}

struct ToneMapSettings {
  ToneOperator tone_operator = ToneOperator::kAces;
  float exposure = 1.0f;      // linear multiplier before the curve
  bool srgb_encode = true;    // false when the target is an sRGB format with GL_FRAMEBUFFER_SRGB

  template <class V>
  void visit(V& v) {
    v(tone_operator, "operator", {.help = "Tone curve: aces (filmic fit) or reinhard"});
    v(exposure, "exposure", {.min = 1.0e-4, .max = 1.0e4, .help = "Exposure multiplier", .log_scale = true});
    v(srgb_encode, "srgb_encode", {.help = "Apply the sRGB transfer function in the shader"});
  }
};

// CPU twins of the shader (per channel).
float tone_map_aces(float x);
float tone_map_reinhard(float x);
float linear_to_srgb_exact(float x);
// Full pipeline for one channel value: sanitise, exposure, curve, optional sRGB.
float tone_map_channel(float hdr, const ToneMapSettings& s);

class ToneMapper {
 public:
  // Builds the program. Errors: kGl from the compiler (naming file:line).
  static Result<ToneMapper> create();
  ToneMapper() = default;

  // Draws a full-screen triangle into the bound framebuffer (viewport set by the caller) reading
  // `hdr` (a 2D float or any colour texture) at texture unit 0. Depth test and blending are
  // disabled during the pass and the depth test is re-enabled afterwards.
  void apply(const Texture& hdr, const ToneMapSettings& settings);

 private:
  Program program_;
  VertexArray vao_;
};

}  // namespace sylva::render
