#include <sylva/core/assert.hpp>

#include <cstdio>
#include <cstdlib>

namespace sylva::detail {

void assert_fail(const char* condition, const std::string& detail, const char* file, unsigned line,
                 const char* function) {
  std::fprintf(stderr, "sylva assertion failed in %s (%s:%u): %s [%s]\n", function, file, line, condition,
               detail.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace sylva::detail
