// sylva-bake: offline baking (terrain chunk files, tiled shares + merge, tree export). See bake_options.hpp.
#include "bake_options.hpp"
#include "bake_run.hpp"

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <iostream>

namespace {

// Raised by SIGINT/SIGTERM; the bake stops at the next chunk and removes its temporaries.
std::atomic<bool> g_cancel{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");
extern "C" void on_signal(int) { g_cancel.store(true); }

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  auto command = sylva::bake::parse_bake_args(args);
  if (!command.ok()) {
    std::cerr << "sylva-bake: " << command.error().message << "\n" << "Try 'sylva-bake --help'.\n";
    return 2;
  }
  if (command->kind == sylva::bake::BakeCommand::Kind::kHelp) {
    std::cout << sylva::bake::bake_usage();
    return 0;
  }
  // read_elevation drops GDAL's cached blocks after each row of blocks, but within one row GDAL
  // keeps up to GDAL_CACHEMAX (by default 5 % of the RAM: 1.2 GB on a 24 GB machine) of blocks
  // it has already copied out, a second copy of the samples nothing reads again (terrain README,
  // "Baking": the 2 GiB budget). 64 MB unless the user set GDAL_CACHEMAX.
  ::setenv("GDAL_CACHEMAX", "64", 0);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  return sylva::bake::run_bake(*command, g_cancel, std::cout, std::cerr);
}
