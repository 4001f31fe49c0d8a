#pragma once
// The size of a rendered image as users give it ("--size 1280x720", the editor's screenshot
// size), parsed and bounded in one place for the player, the editor and the bench.
//
// Bounds: each side in [kMinRenderSide, kMaxRenderSide] and at most kMaxRenderPixels pixels
// (8192 x 8192). A frame at that size keeps its render targets (HDR colour, depth, the
// tone-mapped target, the float readback of a screenshot) near 2 GiB; 16384 x 16384 is accepted
// per side by GL but exhausts a software rasteriser and writes a black picture.

#include <sylva/core/result.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <string_view>

namespace sylva {

inline constexpr int kMinRenderSide = 16;
inline constexpr int kMaxRenderSide = 16384;
inline constexpr std::int64_t kMaxRenderPixels = std::int64_t{1} << 26;

// "WxH" (or "WXH") in pixels. Errors are kInvalidArgument and start with `parameter` (the option
// or command the user wrote, e.g. "--size"), quoting the text and stating the limit broken.
Result<glm::ivec2> parse_render_size(std::string_view text, std::string_view parameter);

}  // namespace sylva
