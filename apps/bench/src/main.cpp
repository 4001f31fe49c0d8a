// sylva-bench entry point; everything else is in bench_app.cpp so tests can drive it.
#include "bench_app.hpp"

#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  return sylva::bench::run_bench(args, std::cout, std::cerr);
}
