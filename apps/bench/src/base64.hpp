#pragma once
// Standard base64 (RFC 4648, with '=' padding) for data: URIs in the self-contained report.

#include <string>
#include <string_view>

namespace sylva::bench {

std::string base64_encode(std::string_view bytes);

}  // namespace sylva::bench
