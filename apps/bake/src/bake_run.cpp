#include "bake_run.hpp"

#include <sylva/core/timer.hpp>
#if SYLVA_BAKE_TREE
#include "bake_tree.hpp"
#endif
#include <sylva/terrain/bake.hpp>

#include <fmt/format.h>

#include <sys/resource.h>

#include <cmath>
#include <filesystem>
#include <mutex>

namespace sylva::bake {

namespace {

// Peak resident memory of this process [MiB] (getrusage: ru_maxrss is in KiB on Linux).
double peak_rss_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

// One line per whole percent: "sylva-bake: 42 % (12.3 s, ETA 17.0 s)".
struct ProgressPrinter {
  std::ostream& err;
  bool quiet;
  Stopwatch watch;
  std::mutex mutex;
  int last = -1;
  void operator()(float f) {
    if (quiet) return;
    std::lock_guard<std::mutex> lock(mutex);
    const int percent = static_cast<int>(std::floor(f * 100.0f));
    if (percent <= last) return;
    last = percent;
    const double s = watch.elapsed_ms() / 1000.0;
    const std::string eta = f > 0.0f ? fmt::format("{:.1f} s", s * (1.0 - f) / f) : std::string("?");
    err << fmt::format("sylva-bake: {} % ({:.1f} s, ETA {})\n", percent, s, eta) << std::flush;
  }
};

int fail(std::ostream& err, const Error& e) {
  err << "sylva-bake: " << e.describe() << "\n";
  return e.code == ErrorCode::kCancelled ? 130 : 1;
}

// The output must not replace an input (a typo that would turn the user's raster or share into
// a chunk file).
Status check_not_an_input(const BakeCommand& command) {
  std::vector<std::filesystem::path> inputs = command.shares;
  if (command.kind == BakeCommand::Kind::kTerrain) inputs.push_back(command.source);
  for (const auto& in : inputs) {
    std::error_code ec;
    if (std::filesystem::equivalent(in, command.out, ec)) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: --out names an input file; give the baked file another name",
                                    command.out.string()));
    }
  }
  return ok_status();
}

}  // namespace

int run_bake(const BakeCommand& command, const std::atomic<bool>& cancel, std::ostream& out, std::ostream& err) {
  if (command.kind == BakeCommand::Kind::kTree) {
#if SYLVA_BAKE_TREE
    return run_tree_export(command, out, err);
#else
    return fail(err, make_error(ErrorCode::kUnsupported, "tree: sylva-bake was built without the vegetation module"));
#endif
  }
  Stopwatch watch;
  ProgressPrinter printer{err, command.quiet, {}, {}, -1};
  terrain::BuildControl control;
  control.cancel = &cancel;
  control.progress = [&](float f) { printer(f); };
  if (Status s = check_not_an_input(command); !s) return fail(err, s.error());
  Result<terrain::BakeReport> report = make_error(ErrorCode::kInvalidArgument, "nothing to do");
  if (command.kind == BakeCommand::Kind::kMerge) {
    report = terrain::merge_bake_shares(command.shares, command.out, control);
  } else {
    Result<ElevationRaster> raster = read_elevation(command.source, command.settings.elevation);
    if (!raster) return fail(err, raster.error());
    if (cancel.load()) return fail(err, make_error(ErrorCode::kCancelled, "cancelled; nothing was written"));
    if (!command.quiet) {
      err << fmt::format("sylva-bake: {} ({}): {} x {} samples, spacing {} m\n", command.source.string(),
                         raster->reader, raster->field.columns(), raster->field.rows(), raster->field.spacing());
    }
    terrain::BakeOptions options;
    options.tree = command.settings.tree;
    options.share = command.share;
    options.shares = command.shares_total;
    options.overview_max_samples = std::uint64_t{command.overview_side} * command.overview_side;
    options.control = control;
    report = command.tiled ? terrain::bake_share(std::move(raster->field), command.out, options)
                                      : terrain::bake_chunk_file(std::move(raster->field), command.out, options);
  }
  if (!report) return fail(err, report.error());
  out << fmt::format("sylva-bake: wrote {} ({} chunks, {} triangles, {:.1f} MB) in {:.1f} s "
                     "(grids {:.1f} s, meshes {:.1f} s, merge {:.1f} s), peak RSS {:.0f} MiB\n",
                     command.out.string(), report->chunks, report->triangles, static_cast<double>(report->bytes) / 1e6,
                     watch.elapsed_ms() / 1000.0, report->prepare_ms / 1000.0, report->meshes_ms / 1000.0,
                     report->merge_ms / 1000.0, peak_rss_mib());
  return 0;
}

}  // namespace sylva::bake
