#include <sylva/core/file_fault.hpp>

#include <atomic>
#include <utility>

namespace sylva {
namespace {

FileFaultPredicate& active_fault() {
  static FileFaultPredicate fault;
  return fault;
}
std::atomic<bool> fault_installed{false};

}  // namespace

ScopedFileFault::ScopedFileFault(FileFaultPredicate predicate) : previous_(std::move(active_fault())) {
  active_fault() = std::move(predicate);
  fault_installed.store(static_cast<bool>(active_fault()), std::memory_order_relaxed);
}

ScopedFileFault::~ScopedFileFault() {
  active_fault() = std::move(previous_);
  fault_installed.store(static_cast<bool>(active_fault()), std::memory_order_relaxed);
}

bool file_fault_hits(const std::filesystem::path& target, FileFaultPoint point) {
  if (!fault_installed.load(std::memory_order_relaxed)) return false;
  return active_fault()(target, point);
}

}  // namespace sylva
