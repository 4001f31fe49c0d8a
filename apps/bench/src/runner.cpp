#include "runner.hpp"

#include "base64.hpp"
#include "report_html.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image_metrics.hpp>
#include <sylva/core/log.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/render/gl_debug.hpp>
#include <sylva/render/gpu_memory.hpp>
#include <sylva/render/readback.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ostream>

#include <sys/resource.h>

namespace sylva::bench {
namespace {

// Memory columns (issue #20): tracked GPU memory in total and per owner (render/gpu_memory.hpp;
// the scene attributes each module's allocations to its name) and the process's peak RSS, in MiB.
void add_memory_metrics(std::map<std::string, double>& metrics) {
  constexpr double kMiB = 1.0 / (1024.0 * 1024.0);
  metrics["memory.gpu_mib"] = static_cast<double>(render::gpu_memory_total()) * kMiB;
  for (const auto& [owner, usage] : render::gpu_memory_usage()) {
    if (usage.total() > 0) metrics["memory.gpu_mib." + owner] = static_cast<double>(usage.total()) * kMiB;
  }
  rusage self{};
  ::getrusage(RUSAGE_SELF, &self);
  metrics["memory.peak_rss_mib"] = static_cast<double>(self.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB
}

Status apply_assignments(const std::vector<ParamDescriptor>& params, const std::vector<Assignment>& list,
                         const char* option) {
  for (const Assignment& a : list) {
    Status s = set_param(params, a.path, a.value);
    if (!s.ok()) return make_error(s.error().code, fmt::format("{} {}={}: {}", option, a.path, a.value, s.error().message));
  }
  return {};
}

Result<std::unique_ptr<BenchTarget>> make_target(const RunSpec& spec, const std::vector<Assignment>& assignments,
                                                 const char* option) {
  auto target = spec.factory();
  if (!target.ok()) return target.error();
  const std::vector<ParamDescriptor> params = (*target)->params();
  SYLVA_TRY(apply_assignments(params, spec.overrides, "--set"));
  SYLVA_TRY(apply_assignments(params, assignments, option));
  return std::move(*target);
}

Result<std::string> pick_path(const BenchTarget& target, const std::optional<std::string>& name) {
  const std::vector<CameraPathInfo> paths = target.camera_paths();
  if (paths.empty()) return make_error(ErrorCode::kNotFound, "the scene has no camera path to render");
  if (!name) return paths.front().name;
  std::string known;
  for (const CameraPathInfo& p : paths) {
    if (p.name == *name) return p.name;
    known += (known.empty() ? "" : ", ") + p.name;
  }
  return make_error(ErrorCode::kNotFound, fmt::format("--camera-path: the scene has no path \"{}\"; it has {}", *name, known));
}

struct RenderedFrame {
  Image rgb;
  Image depth;
};

// Renders warm-up frames and then every frame of the path; `on_frame` sees each measured frame.
template <class OnFrame>
Status render_path(BenchTarget& target, const RunSpec& spec, const std::string& path, const render::Framebuffer& fb,
                   std::vector<FrameRecord>& records, OnFrame&& on_frame) {
  std::vector<CameraPose> poses;
  for (int i = 0; i < spec.frames; ++i) {
    auto pose = target.camera_pose(path, i, spec.frames);
    if (!pose.ok()) return pose.error();
    poses.push_back(*pose);
  }
  // Warm-up: the first pose at times 0, dt, ..., so caches, shader variants and simulations
  // settle the same way in every run; measured frame i runs at time (warmup + i) * dt.
  for (int w = 0; w < spec.warmup; ++w) {
    FrameInput in{-1 - w, w * spec.dt, static_cast<float>(spec.dt), poses.front()};
    FrameOutput out;
    const std::size_t mark = render::gl_error_mark();
    SYLVA_TRY(target.render(in, fb, out));
    SYLVA_TRY(render::check_frame_gl_errors(mark, fmt::format("warm-up frame {}", w)));
  }
  for (int i = 0; i < spec.frames; ++i) {
    FrameInput in{i, (spec.warmup + i) * spec.dt, static_cast<float>(spec.dt), poses[static_cast<std::size_t>(i)]};
    FrameOutput out;
    Stopwatch wall;
    const std::size_t mark = render::gl_error_mark();
    SYLVA_TRY(target.render(in, fb, out));
    glFinish();
    SYLVA_TRY(render::check_frame_gl_errors(mark, fmt::format("frame {}", i)));
    const double frame_ms = wall.elapsed_ms();
    auto color = render::read_color(fb);
    if (!color.ok()) return color.error();
    auto depth = render::read_depth(fb);
    if (!depth.ok()) return depth.error();
    FrameRecord rec;
    rec.frame = i;
    rec.cpu_ms = out.cpu_ms;
    rec.gpu_ms = out.gpu_ms;
    rec.frame_ms = frame_ms;
    rec.counts = out.counts;
    rec.metrics = out.metrics;
    add_memory_metrics(rec.metrics);
    RenderedFrame frame{to_rgb(*color), std::move(*depth)};
    SYLVA_TRY(on_frame(rec, frame));
    records.push_back(std::move(rec));
  }
  return {};
}

std::string rel_image(const std::string& name) { return "images/" + name + ".png"; }

Status save_png(const std::filesystem::path& out, const std::string& rel, const Image& image) {
  Image copy = downscale(image, 320);
  return write_image(out / rel, copy, PixelFormat::kU8);
}

}  // namespace

Image to_rgb(const Image& rgba) {
  if (rgba.channels() == 3) return rgba;
  Image rgb(rgba.width(), rgba.height(), 3, rgba.format());
  const int c = std::min(3, rgba.channels());
  for (int y = 0; y < rgba.height(); ++y) {
    for (int x = 0; x < rgba.width(); ++x) {
      for (int k = 0; k < 3; ++k) rgb.at(x, y, k) = rgba.at(x, y, std::min(k, c - 1));
    }
  }
  return rgb;
}

Image downscale(const Image& image, int max_width) {
  if (image.width() <= max_width || max_width <= 0) return image;
  const int factor = (image.width() + max_width - 1) / max_width;
  const int w = std::max(1, image.width() / factor), h = std::max(1, image.height() / factor);
  Image out(w, h, image.channels(), image.format());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < image.channels(); ++c) {
        float sum = 0.0f;
        for (int dy = 0; dy < factor; ++dy) {
          for (int dx = 0; dx < factor; ++dx) sum += image.at_clamped(x * factor + dx, y * factor + dy, c);
        }
        out.at(x, y, c) = sum / static_cast<float>(factor * factor);
      }
    }
  }
  return out;
}

Result<FrameError> compare_frames(const Image& reference_rgb, const Image& reference_depth, const Image& test_rgb,
                                  const Image& test_depth, float threshold) {
  FrameError e;
  auto m = mse(reference_rgb, test_rgb);
  if (!m.ok()) return m.error();
  e.mse = *m;
  e.psnr_db = *m > 0.0 ? 10.0 * std::log10(1.0 / *m) : INFINITY;
  SsimOptions so;
  if (reference_rgb.width() < 11 || reference_rgb.height() < 11) so.border = SsimBorder::kTruncated;
  auto s = ssim(reference_rgb, test_rgb, so);
  if (!s.ok()) return s.error();
  e.ssim = s->mean;
  auto share = share_exceeding(reference_rgb, test_rgb, threshold);
  if (!share.ok()) return share.error();
  e.share_exceeding = *share;
  // Foreground = depth written (reversed-Z clears to 0; the sky does not write depth).
  auto sil = silhouette_coverage(reference_depth, test_depth, {.channel = 0, .threshold = 0.0f});
  if (!sil.ok()) return sil.error();
  e.silhouette_coverage = sil->coverage;
  e.silhouette_iou = sil->iou;
  return e;
}

Status validate_spec(const RunSpec& spec) {
  if (spec.frames < 1) return make_error(ErrorCode::kInvalidArgument, "--frames must be at least 1");
  auto target = spec.factory();
  if (!target.ok()) return target.error();
  const std::vector<ParamDescriptor> params = (*target)->params();
  SYLVA_TRY(apply_assignments(params, spec.overrides, "--set"));
  // Each swept value and reference value is tried on the target's parameters, then the
  // parameter is put back, so the check needs no rendering.
  auto try_value = [&](const char* option, const std::string& path, const std::string& value) -> Status {
    auto p = find_param(params, path);
    if (!p.ok()) return make_error(p.error().code, fmt::format("{} {}: {}", option, path, p.error().message));
    const std::string before = p->get_string();
    Status s = p->set_string(value);
    if (!s.ok()) return make_error(s.error().code, fmt::format("{} {}={}: {}", option, path, value, s.error().message));
    Status back = p->set_string(before);
    SYLVA_ASSERT(back.ok(), "restoring {} to {} failed", path, before);
    return {};
  };
  for (const auto& group : spec.sweep_groups) {
    for (const SweepAxis& axis : group) {
      for (const std::string& v : axis.values) SYLVA_TRY(try_value("--sweep", axis.path, v));
    }
  }
  for (const Assignment& a : spec.reference) SYLVA_TRY(try_value("--reference", a.path, a.value));
  auto path = pick_path(**target, spec.camera_path);
  if (!path.ok()) return path.error();
  return {};
}

Result<BenchReport> run_sweep(const RunSpec& spec, std::ostream& log) {
  SYLVA_TRY(validate_spec(spec));
  auto settings = expand_sweep_groups(spec.sweep_groups);
  if (!settings.ok()) return settings.error();

  BenchReport report;
  RunInfo& info = report.info;
  info.scene = spec.scene;
  info.suite = spec.suite;
  info.description = spec.description;
  info.frames = spec.frames;
  info.width = spec.size.x;
  info.height = spec.size.y;
  info.warmup_frames = spec.warmup;
  info.dt = spec.dt;
  info.threshold = spec.threshold;
  info.sweep_groups = spec.sweep_groups;
  info.reference = spec.reference;
  info.reference_note = spec.reference_note;
  info.overrides = spec.overrides;
  info.cost = spec.cost;
  info.error = spec.error;
  info.machine = MachineInfo::collect();
  info.machine.gl_renderer = spec.gl_renderer;
  info.machine.gl_version = spec.gl_version;
  if (spec.reference.empty()) {
    info.notes.push_back("no --reference given: the scene as loaded (with --set) is the reference, so errors are "
                         "relative to it rather than to maximum quality");
  }
  if (default_cost_metric(info.machine.gl_renderer) == CostMetric::kFrameMs) {
    info.notes.push_back("the GL renderer is a software rasteriser: its timer queries need not cover the rasterisation "
                         "(which runs on CPU threads when the commands are flushed), so frame_ms (submission until "
                         "glFinish) is the cost to compare; it scales with pixels and triangles unlike a GPU");
  }

  std::error_code ec;
  std::filesystem::create_directories(spec.out / "images", ec);
  if (ec) {
    return make_error(ErrorCode::kIo, fmt::format("{}: cannot create the output folder: {}", (spec.out / "images").string(),
                                                  ec.message()));
  }

  auto fb = render::Framebuffer::create({.width = spec.size.x, .height = spec.size.y, .color_formats = {GL_RGBA8}});
  if (!fb.ok()) return fb.error();

  // Reference.
  std::vector<RenderedFrame> ref_frames;
  {
    auto target = make_target(spec, spec.reference, "--reference");
    if (!target.ok()) return target.error();
    auto path = pick_path(**target, spec.camera_path);
    if (!path.ok()) return path.error();
    info.camera_path = *path;
    log << fmt::format("reference ({}) along \"{}\", {} frames at {}x{}\n",
                       spec.reference.empty() ? std::string("scene as loaded") : Setting{0, spec.reference}.label(),
                       *path, spec.frames, spec.size.x, spec.size.y);
    Status prepared = (*target)->prepare(spec.size);
    if (!prepared.ok()) {
      return make_error(prepared.error().code, fmt::format("reference render: {}", prepared.error().message));
    }
    SettingResult& ref = report.reference;
    ref.reference = true;
    ref.setting = Setting{0, spec.reference};
    Status rendered = render_path(**target, spec, *path, *fb, ref.frame_records,
                                  [&](FrameRecord& rec, RenderedFrame& frame) -> Status {
                                    auto e = compare_frames(frame.rgb, frame.depth, frame.rgb, frame.depth, spec.threshold);
                                    if (!e.ok()) return e.error();
                                    rec.error = *e;
                                    ref_frames.push_back(std::move(frame));
                                    return {};
                                  });
    if (!rendered.ok()) return make_error(rendered.error().code, fmt::format("reference render: {}", rendered.error().message));
    ref.aggregate();
    const int mid = spec.frames / 2;
    ref.worst_frame = mid;
    ref.thumbnail = rel_image("reference");
    SYLVA_TRY(save_png(spec.out, ref.thumbnail, ref_frames[static_cast<std::size_t>(mid)].rgb));
  }

  for (const Setting& setting : *settings) {
    SettingResult result;
    result.setting = setting;
    auto run_one = [&]() -> Status {
      auto target = make_target(spec, setting.assignments, "--sweep");
      if (!target.ok()) return target.error();
      auto path = pick_path(**target, spec.camera_path);
      if (!path.ok()) return path.error();
      SYLVA_TRY((*target)->prepare(spec.size));
      double worst = INFINITY;
      RenderedFrame worst_frame;
      int worst_index = 0;
      SYLVA_TRY(render_path(**target, spec, *path, *fb, result.frame_records,
                            [&](FrameRecord& rec, RenderedFrame& frame) -> Status {
                              const RenderedFrame& ref = ref_frames[static_cast<std::size_t>(rec.frame)];
                              auto e = compare_frames(ref.rgb, ref.depth, frame.rgb, frame.depth, spec.threshold);
                              if (!e.ok()) return e.error();
                              rec.error = *e;
                              if (e->ssim < worst || worst_frame.rgb.empty()) {
                                worst = e->ssim;
                                worst_index = rec.frame;
                                worst_frame = std::move(frame);
                              }
                              return {};
                            }));
      result.aggregate();
      const std::string id = setting.id();
      const RenderedFrame& ref = ref_frames[static_cast<std::size_t>(worst_index)];
      result.thumbnail = rel_image(id);
      result.reference_image = rel_image(id + "-reference");
      result.difference = rel_image(id + "-difference");
      SYLVA_TRY(save_png(spec.out, result.thumbnail, worst_frame.rgb));
      SYLVA_TRY(save_png(spec.out, result.reference_image, ref.rgb));
      auto heat = difference_heatmap(ref.rgb, worst_frame.rgb, std::max(1e-3f, 4.0f * spec.threshold));
      if (!heat.ok()) return heat.error();
      SYLVA_TRY(save_png(spec.out, result.difference, *heat));
      return {};
    };
    Status status = run_one();
    if (!status.ok()) {
      result.error_message = status.error().message;
      result.frame_records.clear();
      result.aggregate();
      log << fmt::format("[{}/{}] {} {}: FAILED: {}\n", setting.index + 1, settings->size(), setting.id(),
                         setting.label(), result.error_message);
      log_warn("sylva-bench: setting {} ({}) failed: {}", setting.id(), setting.label(), result.error_message);
    } else {
      log << fmt::format("[{}/{}] {} {}: frame {:.3f} ms, gpu {:.3f} ms, cpu {:.3f} ms, {} triangles/frame, PSNR {:.2f} dB, "
                         "SSIM {:.4f}\n",
                         setting.index + 1, settings->size(), setting.id(), setting.label(), result.frame_ms.mean,
                         result.gpu_ms.mean, result.cpu_ms.mean, result.frames ? result.totals.triangles / result.frames : 0,
                         result.psnr_db, result.ssim_mean);
    }
    report.settings.push_back(std::move(result));
  }
  report.mark_pareto();
  return report;
}

Status write_report(const BenchReport& report, const std::filesystem::path& out, bool embed_images) {
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) return make_error(ErrorCode::kIo, fmt::format("{}: cannot create the output folder: {}", out.string(), ec.message()));
  SYLVA_TRY(write_file_atomic(out / "results.csv", to_csv(report)));
  SYLVA_TRY(write_file_atomic(out / "results.json", to_json(report).dump(2) + "\n"));
  std::optional<Error> image_error;
  const ImageSource src = [&](const std::string& rel) -> std::string {
    if (!embed_images) return rel;
    auto bytes = read_file(out / rel);
    if (!bytes.ok()) {
      if (!image_error) image_error = bytes.error();
      return rel;
    }
    return "data:image/png;base64," + base64_encode(*bytes);
  };
  const std::string html = render_report_html(report, src);
  if (image_error) return *image_error;
  return write_file_atomic(out / "report.html", html);
}

}  // namespace sylva::bench
