#include "bench_options.hpp"

#include "paper_tables.hpp"

#include <sylva/core/render_size.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

namespace sylva::bench {
namespace {

Result<long long> parse_integer(const std::string& text, const std::string& what, long long lo, long long hi) {
  long long value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: expected a whole number, got \"{}\"", what, text));
  }
  if (value < lo || value > hi) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: {} is outside {}..{}", what, value, lo, hi));
  }
  return value;
}

Result<double> parse_real(const std::string& text, const std::string& what, double lo, double hi) {
  double value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(value)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: expected a number, got \"{}\"", what, text));
  }
  if (value < lo || value > hi) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: {} is outside {}..{}", what, text, lo, hi));
  }
  return value;
}

Result<Assignment> parse_assignment(const std::string& text, const std::string& option) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: expected path=value such as terrain.max_pixel_error=0.5, got \"{}\"", option, text));
  }
  return Assignment{text.substr(0, eq), text.substr(eq + 1)};
}

}  // namespace

Result<BenchOptions> parse_bench_options(const std::vector<std::string>& args) {
  BenchOptions o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    std::string name = arg;
    std::optional<std::string> inline_value;
    if (arg.rfind("--", 0) == 0) {
      if (auto eq = arg.find('='); eq != std::string::npos) {
        name = arg.substr(0, eq);
        inline_value = arg.substr(eq + 1);
      }
    }
    auto value = [&](const char* what) -> Result<std::string> {
      if (inline_value) return *inline_value;
      if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0) {
        return make_error(ErrorCode::kInvalidArgument, fmt::format("{} needs a value: {}", name, what));
      }
      return args[++i];
    };
#define SYLVA_BENCH_VALUE(var, what) \
  auto var = value(what);            \
  if (!var.ok()) return var.error()

    if (name == "--help" || name == "-h") {
      o.help = true;
    } else if (name == "--stability") {
      o.stability = true;
    } else if (name == "--no-embed") {
      o.embed_images = false;
    } else if (name == "--list-params") {
      o.list_params = true;
    } else if (name == "--list-camera-paths") {
      o.list_camera_paths = true;
    } else if (name == "--sweep") {
      SYLVA_BENCH_VALUE(v, "path=v1,v2,... such as terrain.max_pixel_error=0.5,1,2");
      auto axis = parse_sweep(*v);
      if (!axis.ok()) return axis.error();
      o.sweeps.push_back(std::move(*axis));
    } else if (name == "--reference" || name == "--set") {
      SYLVA_BENCH_VALUE(v, "path=value");
      auto a = parse_assignment(*v, name);
      if (!a.ok()) return a.error();
      (name == "--set" ? o.overrides : o.reference).push_back(std::move(*a));
    } else if (name == "--suite") {
      SYLVA_BENCH_VALUE(v, "terrain, grass, trees, voxel, model, species, stream or all");
      if (*v != "terrain" && *v != "grass" && *v != "trees" && *v != "voxel" && *v != "model" && *v != "species" &&
          *v != "stream" && *v != "all") {
        return make_error(ErrorCode::kInvalidArgument,
                          fmt::format("--suite: \"{}\" is not terrain, grass, trees, voxel, model, species, stream or all", *v));
      }
      o.suite = *v;
    } else if (name == "--paper") {
      SYLVA_BENCH_VALUE(v, "000, 001, 002, 003, 004 or all (the thesis whose tables to reproduce)");
      if (*v != "000" && *v != "001" && *v != "002" && *v != "003" && *v != "004" && *v != "all") {
        return make_error(ErrorCode::kInvalidArgument,
                          fmt::format("--paper: \"{}\" is not 000, 001, 002, 003, 004 or all", *v));
      }
      o.paper = *v;
    } else if (name == "--quick") {
      o.quick = true;
    } else if (name == "--table") {
      SYLVA_BENCH_VALUE(v, "a table of the --paper thesis, as paper.md names it (e.g. 5.5, or 4.8 of \"4.6, 4.8, 4.10\")");
      o.tables.push_back(*v);
    } else if (name == "--camera-path") {
      SYLVA_BENCH_VALUE(v, "a camera path name of the scene (see --list-camera-paths)");
      o.camera_path = *v;
    } else if (name == "--frames") {
      SYLVA_BENCH_VALUE(v, "a frame count");
      auto n = parse_integer(*v, "--frames", 1, 100000);
      if (!n.ok()) return n.error();
      o.frames = static_cast<int>(*n);
    } else if (name == "--warmup") {
      SYLVA_BENCH_VALUE(v, "a frame count");
      auto n = parse_integer(*v, "--warmup", 0, 1000);
      if (!n.ok()) return n.error();
      o.warmup = static_cast<int>(*n);
    } else if (name == "--size") {
      SYLVA_BENCH_VALUE(v, "WxH such as 256x144");
      auto s = parse_render_size(*v, "--size");
      if (!s.ok()) return s.error();
      o.size = *s;
    } else if (name == "--dt") {
      SYLVA_BENCH_VALUE(v, "seconds per frame");
      auto d = parse_real(*v, "--dt", 0.0, 10.0);
      if (!d.ok()) return d.error();
      o.dt = *d;
    } else if (name == "--threshold") {
      SYLVA_BENCH_VALUE(v, "a colour difference in 0..1");
      auto t = parse_real(*v, "--threshold", 0.0, 1.0);
      if (!t.ok()) return t.error();
      o.threshold = static_cast<float>(*t);
    } else if (name == "--cost") {
      SYLVA_BENCH_VALUE(v, "gpu_ms, cpu_ms or frame_ms");
      auto c = parse_cost_metric(*v);
      if (!c.ok()) return c.error();
      o.cost = *c;
    } else if (name == "--error-metric") {
      SYLVA_BENCH_VALUE(v, "dssim, share_exceeding, coverage_loss or rmse");
      auto e = parse_error_metric(*v);
      if (!e.ok()) return e.error();
      o.error = *e;
    } else if (name == "--out") {
      SYLVA_BENCH_VALUE(v, "an output folder");
      o.out = *v;
    } else if (arg.rfind("-", 0) == 0) {
      return make_error(ErrorCode::kInvalidArgument, fmt::format("unknown option \"{}\" (see --help)", arg));
    } else if (o.scene) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("only one scene may be given; got \"{}\" and \"{}\"", *o.scene, arg));
    } else {
      o.scene = arg;
    }
#undef SYLVA_BENCH_VALUE
  }
  if (o.help) return o;
  if (o.list_params || o.list_camera_paths) {
    if (!o.scene && !o.suite) {
      return make_error(ErrorCode::kInvalidArgument, "--list-params and --list-camera-paths need a SCENE or --suite");
    }
    return o;
  }
  if (o.paper && (o.scene || o.suite || o.stability || !o.sweeps.empty() || !o.reference.empty())) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("--paper {} runs the thesis's own experiments; it takes no SCENE, --suite, --stability, "
                                  "--sweep or --reference",
                                  *o.paper));
  }
  if (o.quick && !o.paper) return make_error(ErrorCode::kInvalidArgument, "--quick goes with --paper");
  if (!o.tables.empty()) {
    if (!o.paper || *o.paper == "all") {
      return make_error(ErrorCode::kInvalidArgument, "--table goes with --paper and one thesis (000 .. 004, not all)");
    }
    const std::vector<PaperTable> known = paper_tables(*o.paper);
    for (const std::string& id : o.tables) {
      if (std::none_of(known.begin(), known.end(), [&](const PaperTable& t) { return paper_table_matches(t, id); })) {
        std::string ids;
        for (const PaperTable& t : known) ids += (ids.empty() ? "" : "; ") + t.id;
        return make_error(ErrorCode::kInvalidArgument,
                          fmt::format("--table: seed {} has no table \"{}\" (its tables: {})", *o.paper, id, ids));
      }
    }
  }
  if (!o.scene && !o.suite && !o.paper && (!o.sweeps.empty() || !o.reference.empty())) {
    return make_error(ErrorCode::kInvalidArgument, "--sweep and --reference need a SCENE to sweep");
  }
  if (!o.scene && !o.suite && !o.stability && !o.paper) {
    return make_error(ErrorCode::kInvalidArgument,
                      "nothing to do: give a SCENE with --sweep, a --suite, --paper or --stability (see --help)");
  }
  if (o.suite && o.scene) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("--suite {} brings its own scene; drop \"{}\" or drop --suite", *o.suite, *o.scene));
  }
  if (o.suite && (!o.sweeps.empty() || !o.reference.empty())) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("--suite {} has curated sweeps and references; --sweep and --reference go with a SCENE",
                                  *o.suite));
  }
  if (!o.scene && (!o.sweeps.empty() || !o.reference.empty())) {
    return make_error(ErrorCode::kInvalidArgument, "--sweep and --reference need a SCENE to sweep");
  }
  if (o.out.empty()) {
    return make_error(ErrorCode::kInvalidArgument, "--out DIR is required (results.csv, results.json, report.html)");
  }
  return o;
}

std::string bench_usage() {
  return "usage: sylva-bench SCENE --sweep path=v1,v2,... [options] --out DIR\n"
         "       sylva-bench --suite terrain|grass|trees|voxel|all [options] --out DIR\n"
         "       sylva-bench --stability [--suite ...] --out DIR\n"
         "       sylva-bench --paper 000|001|002|003|004|all [--quick] --out DIR\n"
         "Renders a camera path for every combination of the swept parameters and puts the image error against\n"
         "a maximum-quality reference next to the cost (GPU and CPU time, triangles, fragments, draw calls).\n"
         "  SCENE                  scene JSON file, or builtin:ground (sky + fBm ground, no content module)\n"
         "  --sweep path=v1,v2     parameter values to try; several --sweep give their cartesian product\n"
         "                         (vectors in brackets: --sweep camera.position=[0,10,0],[0,50,0])\n"
         "  --reference path=v     the maximum-quality setting errors are measured against (repeatable);\n"
         "                         without it the scene as loaded is the reference\n"
         "  --set path=value       applied to every setting and to the reference\n"
         "  --suite NAME           curated sweeps: terrain, grass, trees, voxel, model or all; species: load +\n"
         "                         bake of species files, plants/s of grammars, mixed vs one-species forest;\n"
         "                         stream: frame times of the terrain streamed from its bake vs in memory\n"
         "  --paper THESIS         the thesis's experiments: per table the thesis's numbers beside Sylva's\n"
         "                         (DIR/paper-THESIS/paper.md, paper.json, a sweep report per row)\n"
         "  --quick                with --paper: the first row of each table at 256x144, 2 frames (for CI)\n"
         "  --table ID             with --paper and one thesis: only this table (repeatable; e.g. 5.5)\n"
         "  --stability            run every available module's extreme cases; writes stability.{csv,json,html}\n"
         "  --camera-path NAME     named camera path of the scene (default: the scene's first)\n"
         "  --frames N             frames along the path (default 24)\n"
         "  --size WxH             render size (default 256x144)\n"
         "  --warmup N             unmeasured frames before each setting (default 2)\n"
         "  --dt S                 fixed simulation time step per frame (default 1/30 s)\n"
         "  --threshold T          colour difference counted by share_exceeding (default 0.05)\n"
         "  --cost M               x axis of the plot and the Pareto front: gpu_ms (timer queries), cpu_ms\n"
         "                         (submission) or frame_ms (until glFinish); default gpu_ms on hardware,\n"
         "                         frame_ms on software rasterisers such as llvmpipe\n"
         "  --error-metric M       y axis: dssim (1 - SSIM, default), share_exceeding, coverage_loss, rmse\n"
         "  --no-embed             link the PNG files from report.html instead of embedding them\n"
         "  --list-params          print every sweepable parameter of the scene and quit\n"
         "  --list-camera-paths    print the scene's camera paths and quit\n"
         "  --out DIR              output folder: results.csv, results.json, report.html, images/\n";
}

}  // namespace sylva::bench
