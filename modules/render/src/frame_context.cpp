// Pass names (frame_context.hpp).
#include <sylva/render/frame_context.hpp>

namespace sylva::render {

const char* to_string(Pass pass) {
  switch (pass) {
    case Pass::kShadow: return "shadow";
    case Pass::kOpaque: return "opaque";
    case Pass::kTransparent: return "transparent";
  }
  return "unknown";
}

}  // namespace sylva::render
