// sylva-player: the lean runtime. Plays a scene in a window, or headless to a PNG.
#include "player_app.hpp"
#include "player_options.hpp"

#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  auto options = sylva::player::parse_player_options(args);
  if (!options.ok()) {
    std::cerr << "sylva-player: " << options.error().message << "\n" << "Try 'sylva-player --help'.\n";
    return 2;
  }
  if (options->help) {
    std::cout << sylva::player::player_usage();
    return 0;
  }
  return sylva::player::run_player(*options, std::cout, std::cerr);
}
