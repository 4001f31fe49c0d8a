// sylva-player's command line (apps/player player_options.cpp): one argument per input line.
#include "support/fuzz_support.hpp"

#include "player_options.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto options = sylva::player::parse_player_options(sylva::fuzz::split_lines(sylva::fuzz::as_text(data, size)));
  if (!options.ok()) sylva::fuzz::require_message(options.error());
  return 0;
}
