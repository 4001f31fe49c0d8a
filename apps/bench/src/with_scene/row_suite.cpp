// Scene targets and results.csv for the row-printing suites (row_suite.hpp).
#include "with_scene/row_suite.hpp"

#include "with_scene/scene_target.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/render/framebuffer.hpp>

#include <fmt/format.h>

#include <ostream>
#include <system_error>

namespace sylva::bench {

Result<std::unique_ptr<BenchTarget>> make_scene_target(const std::string& scene, const std::string& source,
                                                       const std::vector<Assignment>& settings) {
  auto target = scene_text_factory(scene, source)();
  if (!target.ok()) return target.error();
  const std::vector<ParamDescriptor> params = (*target)->params();
  for (const Assignment& a : settings) {
    Status set = set_param(params, a.path, a.value);
    if (!set.ok()) return make_error(set.error().code, fmt::format("--set {}={}: {}", a.path, a.value, set.error().message));
  }
  return target;
}

Result<BuiltTarget> build_scene_target(const std::string& scene, const std::string& source, glm::ivec2 size,
                                       const std::vector<Assignment>& settings) {
  Stopwatch wall;
  auto target = make_scene_target(scene, source, settings);
  if (!target.ok()) return target.error();
  SYLVA_TRY((*target)->prepare(size));
  glFinish();
  return BuiltTarget{std::move(*target), wall.elapsed_ms()};
}

Status write_rows_csv(const std::vector<SuiteRow>& rows, const std::filesystem::path& dir, std::ostream& out) {
  std::string text = "kind,name,count,value,unit\n";
  for (const SuiteRow& r : rows) text += fmt::format("{},\"{}\",{},{},{}\n", r.kind, r.name, r.count, r.value, r.unit);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  SYLVA_TRY(write_file_atomic(dir / "results.csv", text));
  out << fmt::format("sylva-bench: wrote {}\n", std::filesystem::absolute(dir / "results.csv").string());
  return {};
}

}  // namespace sylva::bench
