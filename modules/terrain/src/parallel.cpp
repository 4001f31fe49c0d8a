#include "parallel.hpp"

#include <algorithm>
#include <thread>
#include <vector>

namespace sylva::terrain::detail {

int resolve_threads(int requested) {
  if (requested > 0) return requested;
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

bool parallel_for(std::size_t count, int threads, const std::function<void(std::size_t)>& fn,
                  const std::atomic<bool>* cancel, std::size_t block) {
  block = std::max<std::size_t>(block, 1);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stopped{false};
  auto worker = [&] {
    for (;;) {
      if (cancel != nullptr && cancel->load(std::memory_order_relaxed)) {
        stopped = true;
        return;
      }
      const std::size_t begin = next.fetch_add(block, std::memory_order_relaxed);
      if (begin >= count) return;
      const std::size_t end = std::min(count, begin + block);
      for (std::size_t i = begin; i < end; ++i) fn(i);
    }
  };
  const std::size_t blocks = (count + block - 1) / block;
  const int n = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), blocks));
  if (n <= 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    pool.reserve(static_cast<std::size_t>(n - 1));
    for (int t = 1; t < n; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
  }
  return !stopped.load();
}

}  // namespace sylva::terrain::detail
