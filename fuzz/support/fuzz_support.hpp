#pragma once
// Shared pieces of the fuzz targets: the input as text or lines, a temporary file for parsers that
// open a path, and a hard check that turns a broken invariant into a crash the fuzzer records.

#include <sylva/core/result.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::fuzz {

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// The input split at '\n' (a trailing newline ends the last line, it adds no empty line).
std::vector<std::string> split_lines(std::string_view text);

// Writes the bytes to one file per process under the system temp folder, named with the given
// extension (".png"), and returns its path. The same path is reused by every input.
std::filesystem::path write_temp_file(std::span<const std::uint8_t> bytes, std::string_view extension);

// A field of a binary header in host (little-endian) order; `at + sizeof(T)` must be in range.
template <class T>
T load(const std::vector<std::uint8_t>& bytes, std::size_t at) {
  T value;
  std::memcpy(&value, bytes.data() + at, sizeof(T));
  return value;
}
template <class T>
void store(std::vector<std::uint8_t>& bytes, std::size_t at, T value) {
  std::memcpy(bytes.data() + at, &value, sizeof(T));
}

// Aborts with the message when `condition` is false (an invariant of the parser broke).
void require(bool condition, std::string_view what);

// A parser's error must say something: every user-facing failure carries a message.
void require_message(const Error& error);

}  // namespace sylva::fuzz
