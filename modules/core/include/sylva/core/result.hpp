#pragma once
// Result<T>: the return type of everything a user can get wrong (files, scene JSON, grammars,
// parameters, GL capability). A std::expected-like value-or-error; std::expected is C++23 and
// Debian 12's g++ 12 lacks it. The error message always names the file, line or parameter.

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace sylva {

enum class ErrorCode {
  kInvalidArgument,   // a parameter or value out of its range or of the wrong type
  kNotFound,          // a file, key, module or path that does not exist
  kParse,             // malformed text (JSON, grammar, OBJ, ...) with line/column in the message
  kCorrupt,           // a binary file whose size, header or checksum is wrong
  kUnsupported,       // a format, channel count or capability we do not handle
  kIo,                // the operating system refused a read or write
  kLimit,             // a size or count cap (image side, expansion length, memory budget)
  kGl,                // GL context creation, shader compile/link, framebuffer completeness
  kCancelled,         // a long job stopped on request
};

const char* to_string(ErrorCode code);

struct Error {
  ErrorCode code = ErrorCode::kInvalidArgument;
  std::string message;

  // "<code>: <message>", for logs and command-line output.
  std::string describe() const;
};

inline Error make_error(ErrorCode code, std::string message) { return Error{code, std::move(message)}; }

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : state_(std::in_place_index<0>, std::move(value)) {}  // NOLINT: implicit by design
  Result(Error error) : state_(std::in_place_index<1>, std::move(error)) {}  // NOLINT

  bool ok() const { return state_.index() == 0; }
  explicit operator bool() const { return ok(); }

  T& value() & { assert(ok() && "Result::value() on an error"); return std::get<0>(state_); }
  const T& value() const& { assert(ok() && "Result::value() on an error"); return std::get<0>(state_); }
  T&& value() && { assert(ok() && "Result::value() on an error"); return std::get<0>(std::move(state_)); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

  const Error& error() const { assert(!ok() && "Result::error() on a value"); return std::get<1>(state_); }

  T value_or(T fallback) const& { return ok() ? std::get<0>(state_) : std::move(fallback); }

 private:
  std::variant<T, Error> state_;
};

template <>
class [[nodiscard]] Result<void> {
 public:
  Result() = default;
  Result(Error error) : error_(std::move(error)), ok_(false) {}  // NOLINT: implicit by design

  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const Error& error() const { assert(!ok_ && "Result::error() on success"); return error_; }

 private:
  Error error_;
  bool ok_ = true;
};

using Status = Result<void>;

inline Status ok_status() { return {}; }

}  // namespace sylva

// Propagates an error from an expression returning Result<...>. Usage:
//   SYLVA_TRY(write_image(path, image));
#define SYLVA_TRY(expr)                            \
  do {                                             \
    auto sylva_try_result_ = (expr);               \
    if (!sylva_try_result_.ok()) return sylva_try_result_.error(); \
  } while (0)
