#include <sylva/core/render_size.hpp>

#include <fmt/format.h>

#include <charconv>

namespace sylva {
namespace {

bool parse_side(std::string_view text, int& out) {
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, out);
  return ec == std::errc() && ptr == end && !text.empty();
}

}  // namespace

Result<glm::ivec2> parse_render_size(std::string_view text, std::string_view parameter) {
  const auto x = text.find_first_of("xX");
  int w = 0;
  int h = 0;
  if (x == std::string_view::npos || !parse_side(text.substr(0, x), w) || !parse_side(text.substr(x + 1), h)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: expected WxH in whole pixels such as 1280x720, got \"{}\"", parameter, text));
  }
  if (w < kMinRenderSide || h < kMinRenderSide || w > kMaxRenderSide || h > kMaxRenderSide) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: {}x{} is outside {}..{} pixels per side", parameter,
                                                               w, h, kMinRenderSide, kMaxRenderSide));
  }
  const std::int64_t pixels = std::int64_t{w} * h;
  if (pixels > kMaxRenderPixels) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: {}x{} is {} pixels, above the limit of {} (8192x8192) that the render targets "
                                  "of a frame can hold",
                                  parameter, w, h, pixels, kMaxRenderPixels));
  }
  return glm::ivec2(w, h);
}

}  // namespace sylva
