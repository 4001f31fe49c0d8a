#include <sylva/core/assert.hpp>

#include <cstdio>
#include <cstdlib>

namespace sylva::detail {

void assert_fail(const char* condition, const std::string& detail, const std::source_location& where) {
  std::fprintf(stderr, "sylva assertion failed in %s (%s:%u): %s [%s]\n", where.function_name(),
               where.file_name(), static_cast<unsigned>(where.line()), condition, detail.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace sylva::detail
