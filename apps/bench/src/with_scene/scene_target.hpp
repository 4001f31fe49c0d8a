#pragma once
// A modules/scene scene as a bench target: the scene file's sections are the parameters
// ("grass.render.cull.near_distance", "sun.elevation_deg", ...), its named camera paths are the
// paths (plus "start", the scene's camera, and "bookmark:<name>" for each bookmark), and one
// frame is Scene::update + Scene::render with the scene's per-pass, per-module statistics.
//
// Counts: primitives, fragments (samples), triangles, draw calls and instances are the sums of
// the scene's pass totals (frame_stats.hpp). Module facts come from Scene::module_stats(): every
// numeric entry becomes a metric "<module>.<key>" (nested keys joined with '.'), and an object
// "lod_instances": {"<level>": n} becomes the LOD instance counts "<module>.<level>". The terrain
// module's "max_projected_error_px" is the report's max geometric error. ("instances_per_lod" is
// accepted as a synonym of "lod_instances".)

#include "bench_target.hpp"

#include <filesystem>
#include <string>

namespace sylva::bench {

// A scene file (read when the factory is called, so every setting starts from the file).
Result<TargetFactory> scene_file_factory(const std::string& path);
// Scene JSON text (the suites' embedded scenes); `source` names it in messages, map paths are
// relative to `directory`.
TargetFactory scene_text_factory(std::string text, std::string source, std::filesystem::path directory = {});

}  // namespace sylva::bench
