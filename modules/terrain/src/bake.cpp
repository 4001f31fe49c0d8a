// bake_chunk_file: a one-process bake is one share and its merge (bake.hpp).
#include <sylva/terrain/bake.hpp>

#include "bake_merge.hpp"

#include <sylva/core/atomic_file.hpp>

namespace sylva::terrain {

Result<BakeReport> bake_chunk_file(HeightField field, const std::filesystem::path& out,
                                   const BakeOptions& options) {
  SYLVA_TRY(check_replaceable(out));
  BakeOptions one = options;
  one.share = 0;
  one.shares = 1;
  // Meshing is most of the work; the merge copies the blobs.
  if (options.control.progress) one.control.progress = [&](float f) { options.control.progress(0.9f * f); };
  const std::filesystem::path share = temp_path_beside(out).concat(".share");
  struct Remove {
    const std::filesystem::path& p;
    ~Remove() {
      std::error_code ec;
      std::filesystem::remove(p, ec);
    }
  } remove_share{share};
  Result<BakeReport> meshed = detail::bake_share(std::move(field), share, one, false);
  if (!meshed) return meshed.error();
  BuildControl merge_control = options.control;
  if (options.control.progress) merge_control.progress = [&](float f) { options.control.progress(0.9f + 0.1f * f); };
  Result<BakeReport> merged = detail::merge_shares({share}, out, merge_control, true);
  if (!merged) return merged.error();
  BakeReport report = merged.value();
  report.prepare_ms = meshed->prepare_ms;
  report.meshes_ms = meshed->meshes_ms;
  return report;
}

}  // namespace sylva::terrain
