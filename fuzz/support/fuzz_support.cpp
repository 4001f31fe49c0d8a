#include "fuzz_support.hpp"

#include <sylva/core/log.hpp>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <unistd.h>

namespace sylva::fuzz {
namespace {

// Parsers log warnings (unknown keys, skipped statements); at thousands of inputs a second that
// output would drown the fuzzer's own report, so logging is off in every target.
const bool kQuiet = [] {
  set_log_level(LogLevel::kOff);
  return true;
}();

}  // namespace

std::vector<std::string> split_lines(std::string_view text) {
  std::vector<std::string> lines;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    lines.emplace_back(text.substr(0, end));
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return lines;
}

std::filesystem::path write_temp_file(std::span<const std::uint8_t> bytes, std::string_view extension) {
  std::error_code ec;
  const std::filesystem::path path = std::filesystem::temp_directory_path(ec) /
                                     ("sylva-fuzz-" + std::to_string(::getpid()) + std::string(extension));
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  out.close();
  require(static_cast<bool>(out), "cannot write the temporary input file " + path.string());
  return path;
}

void require(bool condition, std::string_view what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz invariant broken: %.*s\n", static_cast<int>(what.size()), what.data());
  std::abort();
}

void require_message(const Error& error) { require(!error.message.empty(), "an error without a message"); }

}  // namespace sylva::fuzz
