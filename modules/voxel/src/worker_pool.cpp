#include <sylva/voxel/worker_pool.hpp>

#include <algorithm>

namespace sylva::voxel {

WorkerPool::WorkerPool(int threads) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (int i = 0; i < threads; ++i) threads_.emplace_back([this, i] { run(i); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& t : threads_) t.join();
}

std::size_t WorkerPool::parallel_for(std::size_t count, const std::function<void(std::size_t, int)>& fn,
                                     const std::atomic<bool>* cancel) {
  if (count == 0) return 0;
  std::unique_lock lock(mutex_);
  job_ = &fn;
  cancel_ = cancel;
  count_ = count;
  next_ = 0;
  finished_ = 0;
  active_ = size();
  ++generation_;
  wake_.notify_all();
  done_.wait(lock, [this] { return active_ == 0; });
  job_ = nullptr;
  return finished_.load();
}

void WorkerPool::run(int worker) {
  std::uint64_t seen = 0;
  for (;;) {
    const std::function<void(std::size_t, int)>* job = nullptr;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      job = job_;
    }
    for (;;) {
      if (cancel_ && cancel_->load(std::memory_order_relaxed)) break;
      const std::size_t i = next_.fetch_add(1);
      if (i >= count_) break;
      (*job)(i, worker);
      finished_.fetch_add(1);
    }
    {
      std::lock_guard lock(mutex_);
      if (--active_ == 0) done_.notify_all();
    }
  }
}

}  // namespace sylva::voxel
