#include "results.hpp"

#include "pareto.hpp"

#include <fmt/format.h>

#include <sys/utsname.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <set>
#include <thread>

#ifndef SYLVA_BENCH_BUILD_TYPE
#define SYLVA_BENCH_BUILD_TYPE "unknown"
#endif

namespace sylva::bench {

FrameCounts& FrameCounts::operator+=(const FrameCounts& o) {
  triangles += o.triangles;
  primitives += o.primitives;
  fragments += o.fragments;
  draw_calls += o.draw_calls;
  instances += o.instances;
  for (const auto& [k, v] : o.lod_instances) lod_instances[k] += v;
  return *this;
}

void SettingResult::aggregate() {
  frames = static_cast<int>(frame_records.size());
  std::vector<double> gpu, cpu, wall;
  totals = {};
  double mse_sum = 0.0, ssim_sum = 0.0, share_sum = 0.0, cov_sum = 0.0;
  int mse_n = 0, ssim_n = 0, share_n = 0, cov_n = 0;
  psnr_min_db = kNaN;
  ssim_min = kNaN;
  share_exceeding_max = kNaN;
  silhouette_coverage_min = kNaN;
  worst_frame = -1;
  std::map<std::string, std::pair<double, int>> metric_sum;
  metrics.clear();
  auto fmin = [](double a, double b) { return std::isnan(a) ? b : std::min(a, b); };
  auto fmax = [](double a, double b) { return std::isnan(a) ? b : std::max(a, b); };
  for (const FrameRecord& f : frame_records) {
    gpu.push_back(f.gpu_ms);
    cpu.push_back(f.cpu_ms);
    wall.push_back(f.frame_ms);
    totals += f.counts;
    const FrameError& e = f.error;
    if (!std::isnan(e.mse)) { mse_sum += e.mse; ++mse_n; }
    if (!std::isnan(e.psnr_db)) psnr_min_db = fmin(psnr_min_db, e.psnr_db);
    if (!std::isnan(e.ssim)) {
      ssim_sum += e.ssim;
      ++ssim_n;
      if (std::isnan(ssim_min) || e.ssim < ssim_min) {
        ssim_min = e.ssim;
        worst_frame = f.frame;
      }
    }
    if (!std::isnan(e.share_exceeding)) {
      share_sum += e.share_exceeding;
      ++share_n;
      share_exceeding_max = fmax(share_exceeding_max, e.share_exceeding);
    }
    if (!std::isnan(e.silhouette_coverage)) {
      cov_sum += e.silhouette_coverage;
      ++cov_n;
      silhouette_coverage_min = fmin(silhouette_coverage_min, e.silhouette_coverage);
    }
    for (const auto& [k, v] : f.metrics) {
      auto& [sum, n] = metric_sum[k];
      sum += v;
      ++n;
      metrics[k].max = fmax(metrics[k].max, v);
    }
  }
  gpu_ms = summarize(gpu);
  cpu_ms = summarize(cpu);
  frame_ms = summarize(wall);
  psnr_db = mse_n ? (mse_sum > 0.0 ? 10.0 * std::log10(mse_n / mse_sum) : INFINITY) : kNaN;
  ssim_mean = ssim_n ? ssim_sum / ssim_n : kNaN;
  share_exceeding_mean = share_n ? share_sum / share_n : kNaN;
  silhouette_coverage_mean = cov_n ? cov_sum / cov_n : kNaN;
  for (const auto& [k, sn] : metric_sum) metrics[k].mean = sn.first / sn.second;
  if (worst_frame < 0 && !frame_records.empty()) worst_frame = frame_records[frame_records.size() / 2].frame;
}

std::optional<double> SettingResult::max_geometric_error_px() const {
  auto it = metrics.find("terrain.max_projected_error_px");
  if (it == metrics.end()) return std::nullopt;
  return it->second.max;
}

MachineInfo MachineInfo::collect() {
  MachineInfo m;
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  int processors = 0;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("processor", 0) == 0) ++processors;
    if (m.cpu_model.empty() && line.rfind("model name", 0) == 0) {
      if (auto colon = line.find(':'); colon != std::string::npos) {
        m.cpu_model = line.substr(colon + 1);
        while (!m.cpu_model.empty() && m.cpu_model.front() == ' ') m.cpu_model.erase(0, 1);
      }
    }
  }
  if (m.cpu_model.empty()) m.cpu_model = "unknown";
  m.cpu_cores = processors > 0 ? processors : static_cast<int>(std::thread::hardware_concurrency());
  utsname u{};
  if (uname(&u) == 0) m.os = fmt::format("{} {} {}", u.sysname, u.release, u.machine);
#if defined(__clang__)
  m.compiler = fmt::format("clang {}", __clang_version__);
#elif defined(__GNUC__)
  m.compiler = fmt::format("g++ {}", __VERSION__);
#endif
  m.build_type = SYLVA_BENCH_BUILD_TYPE;
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  m.date_utc = buf;
  return m;
}

const char* to_string(CostMetric m) {
  switch (m) {
    case CostMetric::kGpuMs: return "gpu_ms";
    case CostMetric::kCpuMs: return "cpu_ms";
    case CostMetric::kFrameMs: return "frame_ms";
  }
  return "?";
}
CostMetric default_cost_metric(const std::string& gl_renderer) {
  for (const char* soft : {"llvmpipe", "softpipe", "SwiftShader", "swrast"}) {
    if (gl_renderer.find(soft) != std::string::npos) return CostMetric::kFrameMs;
  }
  return CostMetric::kGpuMs;
}
const char* to_string(ErrorMetric m) {
  switch (m) {
    case ErrorMetric::kDssim: return "dssim";
    case ErrorMetric::kShareExceeding: return "share_exceeding";
    case ErrorMetric::kCoverageLoss: return "coverage_loss";
    case ErrorMetric::kRmse: return "rmse";
  }
  return "?";
}
const char* axis_title(CostMetric m) {
  switch (m) {
    case CostMetric::kGpuMs: return "GPU time per frame, mean [ms]";
    case CostMetric::kCpuMs: return "CPU submission time per frame, mean [ms]";
    case CostMetric::kFrameMs: return "frame time until glFinish, mean [ms]";
  }
  return "?";
}
const char* axis_title(ErrorMetric m) {
  switch (m) {
    case ErrorMetric::kDssim: return "1 - SSIM (mean over frames)";
    case ErrorMetric::kShareExceeding: return "share of pixels over the threshold";
    case ErrorMetric::kCoverageLoss: return "1 - silhouette coverage";
    case ErrorMetric::kRmse: return "RMSE (from the mean MSE)";
  }
  return "?";
}
Result<CostMetric> parse_cost_metric(std::string_view text) {
  if (text == "gpu_ms" || text == "gpu") return CostMetric::kGpuMs;
  if (text == "cpu_ms" || text == "cpu") return CostMetric::kCpuMs;
  if (text == "frame_ms" || text == "frame") return CostMetric::kFrameMs;
  return make_error(ErrorCode::kInvalidArgument, fmt::format("--cost: \"{}\" is not gpu_ms, cpu_ms or frame_ms", text));
}
Result<ErrorMetric> parse_error_metric(std::string_view text) {
  for (ErrorMetric m : {ErrorMetric::kDssim, ErrorMetric::kShareExceeding, ErrorMetric::kCoverageLoss, ErrorMetric::kRmse}) {
    if (text == to_string(m)) return m;
  }
  return make_error(ErrorCode::kInvalidArgument,
                    fmt::format("--error-metric: \"{}\" is not dssim, share_exceeding, coverage_loss or rmse", text));
}
double cost_of(const SettingResult& r, CostMetric m) {
  switch (m) {
    case CostMetric::kGpuMs: return r.gpu_ms.mean;
    case CostMetric::kCpuMs: return r.cpu_ms.mean;
    case CostMetric::kFrameMs: return r.frame_ms.mean;
  }
  return kNaN;
}
double error_of(const SettingResult& r, ErrorMetric m) {
  switch (m) {
    case ErrorMetric::kDssim: return 1.0 - r.ssim_mean;
    case ErrorMetric::kShareExceeding: return r.share_exceeding_mean;
    case ErrorMetric::kCoverageLoss: return 1.0 - r.silhouette_coverage_mean;
    case ErrorMetric::kRmse: return std::isinf(r.psnr_db) ? 0.0 : std::pow(10.0, -r.psnr_db / 20.0);
  }
  return kNaN;
}

void BenchReport::mark_pareto() {
  std::vector<ParetoPoint> points;
  for (const SettingResult& r : settings) {
    if (!r.error_message.empty()) {
      points.push_back({kNaN, kNaN});
    } else {
      points.push_back({cost_of(r, info.cost), error_of(r, info.error)});
    }
  }
  const std::vector<bool> front = pareto_front(points);
  for (std::size_t i = 0; i < settings.size(); ++i) settings[i].pareto = front[i];
  reference.pareto = false;
}

std::string format_number(double v, bool empty_nan) {
  if (std::isnan(v)) return empty_nan ? "" : "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{}", v);
}

namespace {

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::vector<std::string> lod_keys(const BenchReport& report) {
  std::set<std::string> keys;
  for (const auto& [k, v] : report.reference.totals.lod_instances) keys.insert(k);
  for (const SettingResult& r : report.settings) {
    for (const auto& [k, v] : r.totals.lod_instances) keys.insert(k);
  }
  return {keys.begin(), keys.end()};
}

std::vector<std::string> metric_keys(const BenchReport& report) {
  std::set<std::string> keys;
  for (const auto& [k, v] : report.reference.metrics) keys.insert(k);
  for (const SettingResult& r : report.settings) {
    for (const auto& [k, v] : r.metrics) keys.insert(k);
  }
  return {keys.begin(), keys.end()};
}

std::string value_of(const Setting& s, const std::string& path) {
  for (const Assignment& a : s.assignments) {
    if (a.path == path) return a.value;
  }
  return "";
}

nlohmann::json number(double v) {
  if (std::isnan(v)) return nullptr;
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}

nlohmann::json counts_json(const FrameCounts& c) {
  nlohmann::json j = {{"triangles", c.triangles},   {"primitives", c.primitives}, {"fragments", c.fragments},
                      {"draw_calls", c.draw_calls}, {"instances", c.instances}};
  j["lod_instances"] = nlohmann::json::object();
  for (const auto& [k, v] : c.lod_instances) j["lod_instances"][k] = v;
  return j;
}

nlohmann::json setting_json(const SettingResult& r) {
  nlohmann::json j;
  j["id"] = r.reference ? "reference" : r.setting.id();
  j["label"] = r.setting.label();
  j["assignments"] = nlohmann::json::object();
  for (const Assignment& a : r.setting.assignments) j["assignments"][a.path] = a.value;
  j["reference"] = r.reference;
  j["pareto"] = r.pareto;
  if (!r.error_message.empty()) j["error"] = r.error_message;
  j["frames"] = r.frames;
  j["gpu_ms"] = r.gpu_ms;
  j["cpu_ms"] = r.cpu_ms;
  j["frame_ms"] = r.frame_ms;
  j["totals"] = counts_json(r.totals);
  j["image_error"] = {{"psnr_db", number(r.psnr_db)},
                      {"psnr_min_db", number(r.psnr_min_db)},
                      {"ssim_mean", number(r.ssim_mean)},
                      {"ssim_min", number(r.ssim_min)},
                      {"share_exceeding_mean", number(r.share_exceeding_mean)},
                      {"share_exceeding_max", number(r.share_exceeding_max)},
                      {"silhouette_coverage_mean", number(r.silhouette_coverage_mean)},
                      {"silhouette_coverage_min", number(r.silhouette_coverage_min)}};
  if (auto g = r.max_geometric_error_px()) j["image_error"]["max_geometric_error_px"] = number(*g);
  j["metrics"] = nlohmann::json::object();
  for (const auto& [k, m] : r.metrics) j["metrics"][k] = {{"mean", number(m.mean)}, {"max", number(m.max)}};
  j["worst_frame"] = r.worst_frame;
  j["thumbnail"] = r.thumbnail;
  j["difference"] = r.difference;
  j["reference_image"] = r.reference_image;
  nlohmann::json frames = nlohmann::json::array();
  for (const FrameRecord& f : r.frame_records) {
    nlohmann::json fj = {{"frame", f.frame}, {"cpu_ms", number(f.cpu_ms)}, {"gpu_ms", number(f.gpu_ms)},
                       {"frame_ms", number(f.frame_ms)}};
    fj["counts"] = counts_json(f.counts);
    fj["error"] = {{"mse", number(f.error.mse)},
                   {"psnr_db", number(f.error.psnr_db)},
                   {"ssim", number(f.error.ssim)},
                   {"share_exceeding", number(f.error.share_exceeding)},
                   {"silhouette_coverage", number(f.error.silhouette_coverage)},
                   {"silhouette_iou", number(f.error.silhouette_iou)}};
    fj["metrics"] = nlohmann::json::object();
    for (const auto& [k, v] : f.metrics) fj["metrics"][k] = number(v);
    frames.push_back(std::move(fj));
  }
  j["frame_records"] = std::move(frames);
  return j;
}

nlohmann::json assignments_json(const std::vector<Assignment>& list) {
  nlohmann::json j = nlohmann::json::object();
  for (const Assignment& a : list) j[a.path] = a.value;
  return j;
}

}  // namespace

std::string to_csv(const BenchReport& report) {
  const std::vector<std::string> lods = lod_keys(report);
  const std::vector<std::string> mets = metric_keys(report);
  std::string out = "setting,id";
  const std::vector<std::string> paths = swept_paths(report.info.sweep_groups);
  for (const std::string& p : paths) out += "," + csv_field(p);
  out += ",frames,gpu_ms_mean,gpu_ms_p50,gpu_ms_p99,cpu_ms_mean,cpu_ms_p50,cpu_ms_p99,frame_ms_mean,frame_ms_p50"
         ",frame_ms_p99"
         ",triangles,primitives,fragments,draw_calls,instances";
  for (const std::string& k : lods) out += "," + csv_field("instances." + k);
  out += ",psnr_db,psnr_min_db,ssim_mean,ssim_min,share_exceeding_mean,share_exceeding_max"
         ",silhouette_coverage_mean,silhouette_coverage_min";
  for (const std::string& k : mets) out += "," + csv_field(k + ".mean") + "," + csv_field(k + ".max");
  out += ",pareto,error\n";
  auto row = [&](const SettingResult& r) {
    out += csv_field(r.setting.label()) + "," + (r.reference ? std::string("reference") : r.setting.id());
    for (const std::string& p : paths) out += "," + csv_field(value_of(r.setting, p));
    out += fmt::format(",{},{},{},{},{},{},{},{},{},{}", r.frames, format_number(r.gpu_ms.mean, true),
                       format_number(r.gpu_ms.p50, true), format_number(r.gpu_ms.p99, true),
                       format_number(r.cpu_ms.mean, true), format_number(r.cpu_ms.p50, true),
                       format_number(r.cpu_ms.p99, true), format_number(r.frame_ms.mean, true),
                       format_number(r.frame_ms.p50, true), format_number(r.frame_ms.p99, true));
    out += fmt::format(",{},{},{},{},{}", r.totals.triangles, r.totals.primitives, r.totals.fragments,
                       r.totals.draw_calls, r.totals.instances);
    for (const std::string& k : lods) {
      auto it = r.totals.lod_instances.find(k);
      out += "," + std::to_string(it == r.totals.lod_instances.end() ? 0 : it->second);
    }
    for (double v : {r.psnr_db, r.psnr_min_db, r.ssim_mean, r.ssim_min, r.share_exceeding_mean,
                     r.share_exceeding_max, r.silhouette_coverage_mean, r.silhouette_coverage_min}) {
      out += "," + format_number(v, true);
    }
    for (const std::string& k : mets) {
      auto it = r.metrics.find(k);
      out += "," + (it == r.metrics.end() ? std::string() : format_number(it->second.mean, true));
      out += "," + (it == r.metrics.end() ? std::string() : format_number(it->second.max, true));
    }
    out += fmt::format(",{},{}\n", r.pareto ? 1 : 0, csv_field(r.error_message));
  };
  row(report.reference);
  for (const SettingResult& r : report.settings) row(r);
  return out;
}

nlohmann::json to_json(const BenchReport& report) {
  const RunInfo& i = report.info;
  nlohmann::json j;
  j["tool"] = i.tool_version;
  j["machine"] = {{"cpu_model", i.machine.cpu_model}, {"cpu_cores", i.machine.cpu_cores},
                  {"gl_renderer", i.machine.gl_renderer}, {"gl_version", i.machine.gl_version},
                  {"os", i.machine.os}, {"compiler", i.machine.compiler},
                  {"build_type", i.machine.build_type}, {"date_utc", i.machine.date_utc}};
  j["run"] = {{"scene", i.scene},
              {"suite", i.suite},
              {"description", i.description},
              {"camera_path", i.camera_path},
              {"frames", i.frames},
              {"size", {i.width, i.height}},
              {"warmup_frames", i.warmup_frames},
              {"dt", i.dt},
              {"threshold", i.threshold},
              {"cost_metric", to_string(i.cost)},
              {"error_metric", to_string(i.error)},
              {"reference", assignments_json(i.reference)},
              {"reference_note", i.reference_note},
              {"overrides", assignments_json(i.overrides)},
              {"notes", i.notes}};
  nlohmann::json groups = nlohmann::json::array();
  for (const auto& g : i.sweep_groups) {
    nlohmann::json axes = nlohmann::json::array();
    for (const SweepAxis& a : g) axes.push_back({{"path", a.path}, {"values", a.values}});
    groups.push_back(std::move(axes));
  }
  j["run"]["sweep_groups"] = std::move(groups);
  j["reference"] = setting_json(report.reference);
  nlohmann::json settings = nlohmann::json::array();
  for (const SettingResult& r : report.settings) settings.push_back(setting_json(r));
  j["settings"] = std::move(settings);
  return j;
}

}  // namespace sylva::bench
