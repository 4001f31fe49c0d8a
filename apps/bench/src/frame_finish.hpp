#pragma once
// The end of a built-in bench target's frame (GroundTarget, TerrainTarget): the sky as its own
// pass, the profiler's end of frame, and the FrameOutput's timings and summed pass counts.

#include "bench_target.hpp"

#include <sylva/core/result.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/lighting.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/sky.hpp>

#include <string_view>

namespace sylva::bench {

// Draws the sky pass, ends the frame, sets out.cpu_ms (from `cpu`), out.gpu_ms and out.counts.
// kGl naming `target` (e.g. "builtin:ground") when the frame's GPU queries return no result.
// The caller adds its module's lod_instances and metrics afterwards.
Status finish_sky_frame(render::FrameProfiler& profiler, render::SkyRenderer& sky, const render::Camera& camera,
                        const render::Lighting& lighting, double time, const Stopwatch& cpu, std::string_view target,
                        FrameOutput& out);

}  // namespace sylva::bench
