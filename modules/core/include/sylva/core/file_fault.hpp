#pragma once
// Injected write failures, so tests can put a user's old file at risk and prove it survives:
// every atomic write (atomic_file.hpp) and every FileTransaction asks the active fault before it
// writes a temporary file's last bytes and before each rename. Production code never installs
// one; with none installed the cost is one relaxed atomic load per write.
//
//   ScopedFileFault fault([](const std::filesystem::path& target, FileFaultPoint point) {
//     return point == FileFaultPoint::kRename && target.filename() == "scene.json";
//   });
//   EXPECT_FALSE(scene.save("scene.json").ok());   // maps were renamed, then rolled back
//
// Threading: install and remove faults while no other thread writes files.

#include <filesystem>
#include <functional>

namespace sylva {

enum class FileFaultPoint {
  kWrite,   // the temporary file is half written, then the disk is "full" (ENOSPC)
  kRename,  // renaming the temporary file over the target fails (EIO)
};

// Returns true to make the write of `target` fail at `point`.
using FileFaultPredicate = std::function<bool(const std::filesystem::path& target, FileFaultPoint point)>;

class ScopedFileFault {
 public:
  explicit ScopedFileFault(FileFaultPredicate predicate);
  ~ScopedFileFault();
  ScopedFileFault(const ScopedFileFault&) = delete;
  ScopedFileFault& operator=(const ScopedFileFault&) = delete;

 private:
  FileFaultPredicate previous_;
};

// Whether the active fault (if any) fails `target` at `point`. For the file writers only.
bool file_fault_hits(const std::filesystem::path& target, FileFaultPoint point);

}  // namespace sylva
