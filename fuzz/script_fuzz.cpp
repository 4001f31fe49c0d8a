// The editor's script language (apps/editor script.cpp, `sylva-editor --script FILE`).
#include "support/fuzz_support.hpp"

#include "script.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto commands = sylva::editor::parse_script(sylva::fuzz::as_text(data, size), "fuzz.script");
  if (!commands.ok()) sylva::fuzz::require_message(commands.error());
  return 0;
}
