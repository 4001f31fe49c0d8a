#pragma once
// Per-process temporary paths for the vegetation tests: ctest runs every test case as its own
// process, two at a time, and suites may run side by side, so a fixed name in the temporary
// folder is written, damaged or removed by another test while this one reads it.

#include <filesystem>
#include <string>

#include <unistd.h>

namespace sylva::vegetation::testing {

// "<temp>/sylva_vegetation_<pid>_<name>".
inline std::filesystem::path unique_temp(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("sylva_vegetation_" + std::to_string(::getpid()) + "_" + name);
}

}  // namespace sylva::vegetation::testing
