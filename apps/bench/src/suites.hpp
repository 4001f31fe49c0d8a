#pragma once
// Curated sweeps (--suite): per content module, the settings that matter, the camera path that
// shows them, and what "maximum quality" means for the reference. A suite whose module is not
// part of the build, or not yet able to render, is "not available": make_suite returns
// kUnsupported with a message saying which module is missing, and the bench exits non-zero, so a
// missing module never passes silently.

#include "runner.hpp"

#include <string>
#include <vector>

namespace sylva::bench {

struct SuiteSpec {
  std::string name;         // terrain, grass, trees, voxel
  std::string module;       // the module it measures
  RunSpec run;              // factory, sweep groups, reference, camera path, defaults
};

// Every suite name, in the order --suite all runs them.
std::vector<std::string> suite_names();

// The suite, with frames and size defaults the caller may override. kUnsupported: "module not
// available: ..." (the message names the module and why); kNotFound: unknown suite name.
Result<SuiteSpec> make_suite(const std::string& name);

}  // namespace sylva::bench
