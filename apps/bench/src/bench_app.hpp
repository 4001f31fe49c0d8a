#pragma once
// sylva-bench as a function (main.cpp forwards argv). Exit codes:
//   0 success; 1 a run failed (GL, I/O, a failing stability case); 2 bad arguments, unknown
//   parameter paths or values (nothing rendered); 3 a requested suite's module is not available.

#include <iosfwd>
#include <string>
#include <vector>

namespace sylva::bench {

int run_bench(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace sylva::bench
