#pragma once
// Asserts for programming errors (never for user input: that returns Result). They stay on in
// every build type, name the function, and print the values the caller passes:
//   SYLVA_ASSERT(level < levels, "level={} levels={}", level, levels);

#include <fmt/format.h>

#include <source_location>
#include <string>

namespace sylva::detail {
[[noreturn]] void assert_fail(const char* condition, const std::string& detail,
                              const std::source_location& where);
}  // namespace sylva::detail

#define SYLVA_ASSERT(cond, ...)                                                             \
  do {                                                                                      \
    if (!(cond)) [[unlikely]]                                                               \
      ::sylva::detail::assert_fail(#cond, ::fmt::format(__VA_ARGS__),                       \
                                   ::std::source_location::current());                      \
  } while (0)
