#pragma once
// A minimal fork-join loop over [0, count) on up to `threads` std::threads (the chunk build and
// the error grid use it). Work is handed out by an atomic counter in blocks, so uneven items
// (chunks of different roughness) balance. fn(i) must be safe to call concurrently for
// different i. Returns false when `cancel` was raised (remaining items are skipped).

#include <atomic>
#include <cstddef>
#include <functional>

namespace sylva::terrain::detail {

int resolve_threads(int requested);

bool parallel_for(std::size_t count, int threads, const std::function<void(std::size_t)>& fn,
                  const std::atomic<bool>* cancel = nullptr, std::size_t block = 1);

}  // namespace sylva::terrain::detail
