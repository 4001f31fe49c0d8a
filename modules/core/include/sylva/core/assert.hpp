#pragma once
// Asserts for programming errors (never for user input: that returns Result). They stay on in
// every build type, name the function, and print the values the caller passes:
//   SYLVA_ASSERT(level < levels, "level={} levels={}", level, levels);

#include <fmt/format.h>

#include <string>

// The place is passed as __FILE__/__LINE__/__PRETTY_FUNCTION__ rather than std::source_location:
// clang 14 (the fuzz build, fuzz/) cannot compile libstdc++ 12's <source_location>.
namespace sylva::detail {
[[noreturn]] void assert_fail(const char* condition, const std::string& detail, const char* file,
                              unsigned line, const char* function);
}  // namespace sylva::detail

#define SYLVA_ASSERT(cond, ...)                                                             \
  do {                                                                                      \
    if (!(cond)) [[unlikely]]                                                               \
      ::sylva::detail::assert_fail(#cond, ::fmt::format(__VA_ARGS__), __FILE__, __LINE__,    \
                                   __PRETTY_FUNCTION__);                                    \
  } while (0)
