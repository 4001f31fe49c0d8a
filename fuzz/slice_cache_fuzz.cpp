// Vegetation slice caches (modules/vegetation slice_bake.cpp deserialize_slices): files in a cache
// folder the user may point anywhere. The key, payload size and checksum are taken from and
// written into the input, so mutations reach the slice headers and images behind them.
#include "support/fuzz_support.hpp"

#include <sylva/vegetation/slice_bake.hpp>

#include <cstring>

namespace {

constexpr std::size_t kKeyAt = 12, kSizeAt = 20, kSumAt = 28, kPayloadAt = 36;  // slice_bake.cpp layout

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sylva::vegetation;
  std::string bytes(sylva::fuzz::as_text(data, size));
  std::uint64_t key = 0;
  if (bytes.size() >= kPayloadAt) {
    std::memcpy(&key, bytes.data() + kKeyAt, 8);
    const std::uint64_t payload = bytes.size() - kPayloadAt;
    const std::uint64_t sum = fnv1a64(bytes.data() + kPayloadAt, payload);
    std::memcpy(bytes.data() + kSizeAt, &payload, 8);
    std::memcpy(bytes.data() + kSumAt, &sum, 8);
  }
  auto tree = deserialize_slices(bytes, key);
  if (!tree.ok()) {
    sylva::fuzz::require_message(tree.error());
    return 0;
  }
  sylva::fuzz::require(serialize_slices(*tree, key) == bytes, "a loaded slice cache does not serialise back");
  return 0;
}
