#pragma once
// Levelled logging to stderr, formatted with {fmt} (g++ 12 has no <format>). Tests and tools can redirect it with set_log_sink.

#include <fmt/format.h>
#include <functional>
#include <string_view>

namespace sylva {

enum class LogLevel { kDebug = 0, kInfo = 1, kWarn = 2, kError = 3, kOff = 4 };

void set_log_level(LogLevel level);
LogLevel log_level();

// Replaces the output (default: stderr with a level prefix). Pass nullptr to restore stderr.
using LogSink = std::function<void(LogLevel, std::string_view)>;
void set_log_sink(LogSink sink);

void log_message(LogLevel level, std::string_view message);

template <class... Args>
void log_debug(fmt::format_string<Args...> fmt, Args&&... args) {
  if (log_level() <= LogLevel::kDebug) log_message(LogLevel::kDebug, fmt::format(fmt, std::forward<Args>(args)...));
}
template <class... Args>
void log_info(fmt::format_string<Args...> fmt, Args&&... args) {
  if (log_level() <= LogLevel::kInfo) log_message(LogLevel::kInfo, fmt::format(fmt, std::forward<Args>(args)...));
}
template <class... Args>
void log_warn(fmt::format_string<Args...> fmt, Args&&... args) {
  if (log_level() <= LogLevel::kWarn) log_message(LogLevel::kWarn, fmt::format(fmt, std::forward<Args>(args)...));
}
template <class... Args>
void log_error(fmt::format_string<Args...> fmt, Args&&... args) {
  if (log_level() <= LogLevel::kError) log_message(LogLevel::kError, fmt::format(fmt, std::forward<Args>(args)...));
}

}  // namespace sylva
