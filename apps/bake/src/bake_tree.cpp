#include "bake_tree.hpp"

#include <sylva/core/timer.hpp>
#include <sylva/render/gl_context.hpp>
#include <sylva/vegetation/lod_settings.hpp>
#include <sylva/vegetation/tree_export.hpp>

#include <fmt/format.h>

#include <optional>

namespace sylva::bake {

namespace {

Result<vegetation::ExportTree> load_tree(const TreeCommand& tree, std::ostream& err, bool quiet) {
  constexpr int kTextureSize = 256;  // the scenes' default leaf and bark texture side
  if (tree.species.empty()) {
    for (const auto& e : enum_names(vegetation::SpeciesPreset{}))
      if (tree.preset == e.name) return vegetation::export_tree_from_preset(e.value, tree.seed, kTextureSize);
    return make_error(ErrorCode::kInvalidArgument, fmt::format("--preset '{}': unknown preset", tree.preset));
  }
  std::vector<std::string> warnings;
  Result<vegetation::ExportTree> t = vegetation::export_tree_from_species_file(tree.species, kTextureSize, warnings);
  if (!quiet)
    for (const std::string& w : warnings) err << "sylva-bake: warning: " << w << "\n";
  return t;
}

}  // namespace

int run_tree_export(const BakeCommand& command, std::ostream& out, std::ostream& err) {
  Stopwatch watch;
  const auto fail = [&](const Error& e) {
    err << "sylva-bake: " << e.describe() << "\n";
    return 1;
  };
  Result<vegetation::ExportTree> tree = load_tree(command.tree, err, command.quiet);
  if (!tree) return fail(tree.error());
  vegetation::TreeExportOptions options;
  options.objt = command.tree.objt;
  options.gltf = command.tree.gltf;
  std::optional<vegetation::BakedTree> baked;
  if (command.tree.slices) {
    // The slices are rendered (seed 000 §2.6) like a forest bakes them, at the forest's defaults.
    Result<render::GlContext> context = render::GlContext::create_headless({.debug = false});
    if (!context) return fail(context.error());
    const vegetation::LodSettings lod;
    Result<vegetation::BakedTree> b = vegetation::bake_export_slices(*tree, options, lod.slice_resolution, lod.slice_margin);
    if (!b) return fail(b.error());
    baked = std::move(b).value();
  }
  Result<vegetation::TreeExportReport> report =
      vegetation::export_tree(*tree, command.out, options, baked ? &*baked : nullptr);
  if (!report) return fail(report.error());
  out << fmt::format("sylva-bake: wrote tree '{}' to {}: {} files; bark {} vertices / {} triangles, leaves {} vertices / "
                     "{} triangles; bounds ({:.3f}, {:.3f}, {:.3f}) to ({:.3f}, {:.3f}, {:.3f}) m; {} slice layers; {:.1f} s\n",
                     tree->name, command.out.string(), report->files.size(), report->bark_vertices,
                     report->bark_triangles, report->leaf_vertices, report->leaf_triangles, report->bounds_min.x,
                     report->bounds_min.y, report->bounds_min.z, report->bounds_max.x, report->bounds_max.y,
                     report->bounds_max.z, report->slice_layers, watch.elapsed_ms() / 1000.0);
  if (!command.quiet)
    for (const auto& f : report->files) out << "  " << f.string() << "\n";
  return 0;
}

}  // namespace sylva::bake
