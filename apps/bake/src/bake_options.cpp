#include "bake_options.hpp"

#include <sylva/core/params.hpp>
#if SYLVA_BAKE_TREE
#include <sylva/vegetation/generator.hpp>
#endif

#include <fmt/format.h>

#include <charconv>

namespace sylva::bake {

std::string bake_usage() {
  return "usage:\n"
         "  sylva-bake terrain SOURCE --out FILE.sylvaterrain [--tiles I/N] [--overview-side S] [--set terrain.KEY=VALUE]... [--quiet]\n"
         "  sylva-bake merge SHARE... --out FILE.sylvaterrain [--quiet]\n"
         "  sylva-bake tree SPECIES.json|--preset NAME [--seed N] --out DIR [--format gltf|objt|both] [--slices] [--quiet]\n"
         "Bakes an elevation raster's chunk tree into a chunk file (modules/terrain/README.md, 'Baking').\n"
         "Exports a tree species as OBJT and glTF 2.0 (modules/vegetation/README.md, 'Export'):\n"
         "  --preset NAME  broadleaf, conifer, birch or shrub (instead of a species file), --seed N its seed\n"
         "  --format F     gltf, objt or both (default both); --slices also writes the LOD1/LOD2 slice layers\n"
         "  --tiles I/N   bake share I of N (0 <= I < N) into --out; join the N shares with 'merge'\n"
         "  --overview-side S  a field above S x S samples stores an overview of its ground of at most\n"
         "                S x S samples (every 2nd, 4th, ... sample; default 4097; every share alike)\n"
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

Result<std::uint32_t> parse_overview_side(const std::string& text) {
  std::uint32_t side = 0;
  const char* b = text.data();
  auto r = std::from_chars(b, b + text.size(), side);
  if (text.empty() || r.ec != std::errc() || r.ptr != b + text.size() || side < 2 || side > 65537) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("--overview-side '{}': expected samples per side, 2 to 65537", text));
  }
  return side;
}

Result<std::uint32_t> parse_seed(const std::string& text) {
  std::uint32_t seed = 0;
  const char* b = text.data();
  auto r = std::from_chars(b, b + text.size(), seed);
  if (text.empty() || r.ec != std::errc() || r.ptr != b + text.size())
    return make_error(ErrorCode::kInvalidArgument, fmt::format("--seed '{}': expected an integer 0 to 4294967295", text));
  return seed;
}

Status parse_format(const std::string& text, TreeCommand& tree) {
  if (text != "gltf" && text != "objt" && text != "both")
    return make_error(ErrorCode::kInvalidArgument, fmt::format("--format '{}': expected gltf, objt or both", text));
  tree.gltf = text != "objt";
  tree.objt = text != "gltf";
  return ok_status();
}

Status check_preset(const std::string& name) {
#if !SYLVA_BAKE_TREE
  return make_error(ErrorCode::kUnsupported, fmt::format("--preset '{}': sylva-bake was built without the vegetation module", name));
#else
  std::string names;
  for (const auto& e : enum_names(vegetation::SpeciesPreset{})) {
    if (name == e.name) return ok_status();
    names += names.empty() ? e.name : fmt::format(", {}", e.name);
  }
  return make_error(ErrorCode::kInvalidArgument, fmt::format("--preset '{}': expected one of {}", name, names));
#endif
}

}  // namespace

Result<BakeCommand> parse_bake_args(const std::vector<std::string>& args) {
  BakeCommand cmd;
  if (args.empty() || args[0] == "--help" || args[0] == "-h") return cmd;
  if (args[0] == "terrain") {
    cmd.kind = BakeCommand::Kind::kTerrain;
  } else if (args[0] == "merge") {
    cmd.kind = BakeCommand::Kind::kMerge;
  } else if (args[0] == "tree") {
    cmd.kind = BakeCommand::Kind::kTree;
  } else {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("unknown command '{}' (terrain, merge or tree)", args[0]));
  }
  bool seed_given = false;
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
    } else if (a == "--overview-side" && cmd.kind == BakeCommand::Kind::kTerrain) {
      auto v = value();
      if (!v) return v.error();
      auto side = parse_overview_side(*v);
      if (!side) return side.error();
      cmd.overview_side = *side;
    } else if (a == "--set" && cmd.kind == BakeCommand::Kind::kTerrain) {
      auto v = value();
      if (!v) return v.error();
      SYLVA_TRY(registry.set_assignment(*v));
    } else if (a == "--preset" && cmd.kind == BakeCommand::Kind::kTree) {
      auto v = value();
      if (!v) return v.error();
      SYLVA_TRY(check_preset(*v));
      cmd.tree.preset = *v;
    } else if (a == "--seed" && cmd.kind == BakeCommand::Kind::kTree) {
      auto v = value();
      if (!v) return v.error();
      auto seed = parse_seed(*v);
      if (!seed) return seed.error();
      cmd.tree.seed = *seed;
      seed_given = true;
    } else if (a == "--format" && cmd.kind == BakeCommand::Kind::kTree) {
      auto v = value();
      if (!v) return v.error();
      SYLVA_TRY(parse_format(*v, cmd.tree));
    } else if (a == "--slices" && cmd.kind == BakeCommand::Kind::kTree) {
      cmd.tree.slices = true;
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
  if (cmd.out.empty())
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("'{}' needs --out {}", args[0], cmd.kind == BakeCommand::Kind::kTree ? "DIR" : "FILE"));
  if (cmd.kind == BakeCommand::Kind::kTree) {
    if (positional.size() > 1) return make_error(ErrorCode::kInvalidArgument, "'tree' takes one SPECIES.json");
    if (positional.empty() == cmd.tree.preset.empty())
      return make_error(ErrorCode::kInvalidArgument, "'tree' takes either a SPECIES.json or --preset NAME");
    if (seed_given && cmd.tree.preset.empty())
      return make_error(ErrorCode::kInvalidArgument, "--seed applies to --preset (a species file names its own seed)");
    if (!positional.empty()) cmd.tree.species = positional.front();
  } else if (cmd.kind == BakeCommand::Kind::kTerrain) {
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
