#pragma once
// A fixed pool of worker threads for world generation and meshing (DESIGN.md §2b: long CPU work
// runs on a worker pool, reports progress and can be cancelled).

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace sylva::voxel {

class WorkerPool {
 public:
  // threads <= 0 uses std::thread::hardware_concurrency() (at least 1).
  explicit WorkerPool(int threads = 0);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int size() const { return static_cast<int>(threads_.size()); }

  // Calls fn(index, worker) for every index in [0, count) on the workers and waits. worker is in
  // [0, size()) so callers can keep per-worker scratch (e.g. one Mesher each). Stops handing
  // out indices once *cancel becomes true; returns the number of indices run. Not reentrant.
  std::size_t parallel_for(std::size_t count, const std::function<void(std::size_t, int)>& fn,
                           const std::atomic<bool>* cancel = nullptr);

 private:
  void run(int worker);

  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  const std::function<void(std::size_t, int)>* job_ = nullptr;
  const std::atomic<bool>* cancel_ = nullptr;
  std::size_t count_ = 0;
  std::atomic<std::size_t> next_{0};
  std::atomic<std::size_t> finished_{0};
  int active_ = 0;
  std::uint64_t generation_ = 0;
  bool stop_ = false;
};

}  // namespace sylva::voxel
