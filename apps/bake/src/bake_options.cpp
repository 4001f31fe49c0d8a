#include "bake_options.hpp"

#include <sylva/core/params.hpp>

#include <fmt/format.h>

#include <charconv>

namespace sylva::bake {

std::string bake_usage() {
  return "usage:\n"
         "  sylva-bake terrain SOURCE --out FILE.sylvaterrain [--tiles I/N] [--set terrain.KEY=VALUE]... [--quiet]\n"
         "  sylva-bake merge SHARE... --out FILE.sylvaterrain [--quiet]\n"
         "Bakes an elevation raster's chunk tree into a chunk file (modules/terrain/README.md, 'Baking').\n"
         "  --tiles I/N   bake share I of N (0 <= I < N) into --out; join the N shares with 'merge'\n"
         "  --set K=V     terrain.tree.* (leaf_dimension, flat_tolerance, threads, ...) or\n"
         "                terrain.elevation.* (spacing, height_scale, height_offset, nodata)\n"
         "Ctrl+C stops the bake and leaves no output file (exit status 130).\n";
}

namespace {

Result<std::pair<int, int>> parse_tiles(const std::string& text) {
  const auto slash = text.find('/');
  int i = -1, n = -1;
  auto bad = [&] {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("--tiles '{}': expected I/N with 0 <= I < N <= 1024 (e.g. 0/3)", text));
  };
  if (slash == std::string::npos) return bad();
  const char* b = text.data();
  auto r1 = std::from_chars(b, b + slash, i);
  auto r2 = std::from_chars(b + slash + 1, b + text.size(), n);
  if (r1.ec != std::errc() || r1.ptr != b + slash || r2.ec != std::errc() || r2.ptr != b + text.size() || n < 1 ||
      n > 1024 || i < 0 || i >= n) {
    return bad();
  }
  return std::pair<int, int>{i, n};
}

}  // namespace

Result<BakeCommand> parse_bake_args(const std::vector<std::string>& args) {
  BakeCommand cmd;
  if (args.empty() || args[0] == "--help" || args[0] == "-h") return cmd;
  if (args[0] == "terrain") {
    cmd.kind = BakeCommand::Kind::kTerrain;
  } else if (args[0] == "merge") {
    cmd.kind = BakeCommand::Kind::kMerge;
  } else {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("unknown command '{}' (terrain or merge)", args[0]));
  }
  ParamRegistry registry;
  registry.add("terrain", cmd.settings);
  std::vector<std::filesystem::path> positional;
  for (std::size_t k = 1; k < args.size(); ++k) {
    const std::string& a = args[k];
    auto value = [&]() -> Result<std::string> {
      if (k + 1 >= args.size()) return make_error(ErrorCode::kInvalidArgument, fmt::format("{} needs a value", a));
      return args[++k];
    };
    if (a == "--out") {
      auto v = value();
      if (!v) return v.error();
      cmd.out = *v;
    } else if (a == "--tiles" && cmd.kind == BakeCommand::Kind::kTerrain) {
      auto v = value();
      if (!v) return v.error();
      auto t = parse_tiles(*v);
      if (!t) return t.error();
      cmd.share = t->first;
      cmd.shares_total = t->second;
      cmd.tiled = true;
    } else if (a == "--set" && cmd.kind == BakeCommand::Kind::kTerrain) {
      auto v = value();
      if (!v) return v.error();
      SYLVA_TRY(registry.set_assignment(*v));
    } else if (a == "--quiet") {
      cmd.quiet = true;
    } else if (a == "--help" || a == "-h") {
      cmd.kind = BakeCommand::Kind::kHelp;
      return cmd;
    } else if (!a.empty() && a[0] == '-') {
      return make_error(ErrorCode::kInvalidArgument, fmt::format("unknown option '{}' for '{}'", a, args[0]));
    } else {
      positional.emplace_back(a);
    }
  }
  if (cmd.out.empty()) return make_error(ErrorCode::kInvalidArgument, fmt::format("'{}' needs --out FILE", args[0]));
  if (cmd.kind == BakeCommand::Kind::kTerrain) {
    if (positional.size() != 1) {
      return make_error(ErrorCode::kInvalidArgument, "'terrain' takes exactly one SOURCE raster");
    }
    cmd.source = positional.front();
  } else {
    if (positional.empty()) return make_error(ErrorCode::kInvalidArgument, "'merge' needs the share files");
    cmd.shares = positional;
  }
  SYLVA_TRY(registry.validate());
  return cmd;
}

}  // namespace sylva::bake
