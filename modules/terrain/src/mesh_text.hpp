// How the mesh readers quote a piece of the user's file in an error or warning: a binary file
// renamed .obj/.iv would otherwise print raw bytes (control characters, broken UTF-8) into the
// terminal and the editor's log. Printable ASCII is kept, any other byte becomes \xNN, and a
// long token is cut after `max_chars` characters with "...".
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace sylva::terrain::detail {

inline std::string printable(std::string_view token, std::size_t max_chars = 40) {
  constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (std::size_t i = 0; i < token.size(); ++i) {
    if (out.size() >= max_chars) return out + "...";
    const auto byte = static_cast<unsigned char>(token[i]);
    if (byte >= 0x20 && byte < 0x7f) {
      out += static_cast<char>(byte);
    } else {
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 15];
    }
  }
  return out;
}

}  // namespace sylva::terrain::detail
