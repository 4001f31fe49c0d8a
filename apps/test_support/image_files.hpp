#pragma once
// Comparing screenshots the shipped executables wrote, for tests.
#include <sylva/core/image.hpp>

#include <cstddef>
#include <filesystem>

namespace sylva::test {

// Pixels that differ in any channel between two image files (all of them when the sizes differ
// or a file cannot be read).
inline std::size_t differing_pixels(const std::filesystem::path& a_file, const std::filesystem::path& b_file) {
  auto a = read_image(a_file);
  auto b = read_image(b_file);
  if (!a.ok() || !b.ok() || a->width() != b->width() || a->height() != b->height()) return ~std::size_t{0};
  std::size_t n = 0;
  for (int y = 0; y < a->height(); ++y)
    for (int x = 0; x < a->width(); ++x)
      for (int c = 0; c < a->channels(); ++c)
        if (a->at(x, y, c) != b->at(x, y, c)) {
          ++n;
          break;
        }
  return n;
}

}  // namespace sylva::test
