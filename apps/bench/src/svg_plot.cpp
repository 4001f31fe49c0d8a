#include "svg_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace sylva::bench {

std::string html_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) return {0.0, 1.0};
  if (hi < lo) std::swap(lo, hi);
  if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) {
    const double pad = lo == 0.0 ? 1.0 : std::abs(lo) * 0.1;
    lo -= pad;
    hi += pad;
  }
  const double raw = (hi - lo) / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * mag;
    if (step >= raw) break;
  }
  const double first = std::floor(lo / step) * step;
  std::vector<double> ticks;
  for (int k = 0;; ++k) {
    const double t = first + k * step;
    // Snap values that are zero up to rounding so labels read "0", not "-1.1e-17".
    ticks.push_back(std::abs(t) < step * 1e-9 ? 0.0 : t);
    if (t >= hi - step * 1e-9 || k > 1000) break;
  }
  return ticks;
}

bool wants_log_axis(const std::vector<double>& values) {
  double lo = INFINITY, hi = 0.0;
  for (double v : values) {
    if (std::isfinite(v) && v > 0.0) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  return std::isfinite(lo) && hi / lo > 10.0;
}

std::vector<double> log_ticks(double lo, double hi) {
  if (!(lo > 0.0) || !(hi >= lo) || !std::isfinite(hi)) return {1.0, 10.0};
  const int k0 = static_cast<int>(std::floor(std::log10(lo)));
  const int k1 = static_cast<int>(std::ceil(std::log10(hi)));
  const bool fine = k1 - k0 <= 3;  // few decades: also 2 and 5
  std::vector<double> ticks;
  for (int k = k0; k <= k1; ++k) {
    for (double m : {1.0, 2.0, 5.0}) {
      if (m != 1.0 && !fine) continue;
      const double t = m * std::pow(10.0, k);
      if (t >= lo / (fine ? 2.0 : 10.0) && (ticks.empty() || ticks.back() < hi)) ticks.push_back(t);
    }
  }
  if (ticks.size() < 2) ticks.push_back(ticks.empty() ? 1.0 : ticks.back() * 10.0);
  return ticks;
}

namespace {

std::string tick_label(double v, double step) {
  if (v == 0.0) return "0";
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  if (std::abs(v) >= 1e5 || (std::abs(v) < 1e-3)) return fmt::format("{:.2g}", v);
  return fmt::format("{:.{}f}", v, decimals);
}

}  // namespace

std::string scatter_svg(const std::vector<PlotPoint>& points, const PlotSpec& spec) {
  const double left = 78, right = 24, top = 20, bottom = 58;
  const double pw = spec.width - left - right;
  const double ph = spec.height - top - bottom;

  std::vector<const PlotPoint*> shown;
  std::size_t hidden = 0;
  double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
  for (const PlotPoint& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || (spec.log_x && p.x <= 0.0)) {
      ++hidden;
      continue;
    }
    shown.push_back(&p);
    xmin = std::min(xmin, p.x);
    xmax = std::max(xmax, p.x);
    ymin = std::min(ymin, p.y);
    ymax = std::max(ymax, p.y);
  }
  if (shown.empty()) xmin = xmax = ymin = ymax = 0.0;
  // Time and error are both non-negative: start the axes at 0 so distances read as ratios.
  const std::vector<double> xt = spec.log_x ? log_ticks(xmin, xmax) : nice_ticks(std::min(0.0, xmin), xmax);
  const std::vector<double> yt = nice_ticks(std::min(0.0, ymin), ymax);
  const double x0 = xt.front(), x1 = xt.back(), y0 = yt.front(), y1 = yt.back();
  auto sx = [&](double x) {
    if (spec.log_x) return left + (std::log10(x) - std::log10(x0)) / (std::log10(x1) - std::log10(x0)) * pw;
    return left + (x - x0) / (x1 - x0) * pw;
  };
  auto sy = [&](double y) { return top + ph - (y - y0) / (y1 - y0) * ph; };

  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot\" width=\"{0}\" height=\"{1}\" "
      "viewBox=\"0 0 {0} {1}\" font-family=\"sans-serif\" font-size=\"12\">\n"
      "<rect x=\"0\" y=\"0\" width=\"{0}\" height=\"{1}\" fill=\"#ffffff\"/>\n",
      spec.width, spec.height);
  // Grid and ticks.
  const double xstep = spec.log_x ? 0.0 : (xt.size() > 1 ? xt[1] - xt[0] : 1.0);
  const double ystep = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
  for (double t : xt) {
    s += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"#e4e4e4\"/>\n"
                     "<text x=\"{0:.1f}\" y=\"{3:.1f}\" text-anchor=\"middle\" fill=\"#333\">{4}</text>\n",
                     sx(t), top, top + ph, top + ph + 16, spec.log_x ? fmt::format("{:g}", t) : tick_label(t, xstep));
  }
  for (double t : yt) {
    s += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"#e4e4e4\"/>\n"
                     "<text x=\"{3:.1f}\" y=\"{4:.1f}\" text-anchor=\"end\" fill=\"#333\">{5}</text>\n",
                     left, sy(t), left + pw, left - 6, sy(t) + 4, tick_label(t, ystep));
  }
  s += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#888\"/>\n", left, top,
                   pw, ph);
  s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\" fill=\"#111\">{}{}</text>\n",
                   left + pw / 2, spec.height - 14.0, html_escape(spec.x_title), spec.log_x ? " (log scale)" : "");
  s += fmt::format("<text transform=\"translate(18,{:.1f}) rotate(-90)\" text-anchor=\"middle\" fill=\"#111\">{}</text>\n",
                   top + ph / 2, html_escape(spec.y_title));

  // Pareto staircase: from each front point right to the next one's cost, then down.
  std::vector<const PlotPoint*> front;
  for (const PlotPoint* p : shown) {
    if (p->front) front.push_back(p);
  }
  std::sort(front.begin(), front.end(), [](const PlotPoint* a, const PlotPoint* b) {
    return a->x != b->x ? a->x < b->x : a->y < b->y;
  });
  if (front.size() > 1) {
    std::string d = fmt::format("M{:.1f},{:.1f}", sx(front[0]->x), sy(front[0]->y));
    for (std::size_t i = 1; i < front.size(); ++i) {
      d += fmt::format(" H{:.1f} V{:.1f}", sx(front[i]->x), sy(front[i]->y));
    }
    s += fmt::format("<path class=\"pareto-line\" d=\"{}\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"1.5\" "
                     "stroke-dasharray=\"5,3\"/>\n", d);
  }
  // Labels are nudged down until they do not overlap an earlier one (settings with nearly
  // equal cost and error would otherwise print over each other).
  std::vector<std::pair<double, double>> placed;
  auto label_position = [&](double x, double y) {
    for (int tries = 0; tries < 8; ++tries) {
      bool clash = false;
      for (const auto& [px, py] : placed) clash = clash || (std::abs(px - x) < 30.0 && std::abs(py - y) < 11.0);
      if (!clash) break;
      y += 11.0;
    }
    placed.emplace_back(x, y);
    return y;
  };
  for (const PlotPoint* p : shown) {
    const double cx = sx(p->x), cy = sy(p->y);
    const std::string tip = html_escape(p->tooltip.empty() ? p->label : p->tooltip);
    if (p->reference) {
      s += fmt::format("<g class=\"point reference\"><title>{}</title><path d=\"M{:.1f},{:.1f} l6,6 l-6,6 l-6,-6 z\" "
                       "fill=\"#2ca02c\" stroke=\"#145214\"/></g>\n", tip, cx, cy - 6);
    } else if (p->front) {
      s += fmt::format("<g class=\"point pareto\"><title>{}</title><circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"5\" "
                       "fill=\"#d62728\" stroke=\"#7a1010\"/></g>\n", tip, cx, cy);
    } else {
      s += fmt::format("<g class=\"point\"><title>{}</title><circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4.5\" "
                       "fill=\"#ffffff\" stroke=\"#1f77b4\" stroke-width=\"1.5\"/></g>\n", tip, cx, cy);
    }
    if (!p->label.empty()) {
      s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" fill=\"#444\" font-size=\"10\">{}</text>\n", cx + 7,
                       label_position(cx + 7, cy - 6), html_escape(p->label));
    }
  }
  // Legend.
  const double lx = left + pw - 170, ly = top + 10;
  if (spec.legend) {
    s += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"162\" height=\"54\" fill=\"#ffffff\" fill-opacity=\"0.85\" "
                     "stroke=\"#ccc\"/>\n", lx, ly);
    s += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"5\" fill=\"#d62728\"/><text x=\"{:.1f}\" y=\"{:.1f}\">Pareto front</text>\n",
                     lx + 12, ly + 13, lx + 24, ly + 17);
    s += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4.5\" fill=\"#fff\" stroke=\"#1f77b4\" stroke-width=\"1.5\"/>"
                     "<text x=\"{:.1f}\" y=\"{:.1f}\">dominated setting</text>\n", lx + 12, ly + 29, lx + 24, ly + 33);
    s += fmt::format("<path d=\"M{:.1f},{:.1f} l5,5 l-5,5 l-5,-5 z\" fill=\"#2ca02c\"/><text x=\"{:.1f}\" y=\"{:.1f}\">reference</text>\n",
                     lx + 12, ly + 40, lx + 24, ly + 49);
  }
  if (hidden > 0) {
    s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" fill=\"#a00\">{} point(s) without finite values not shown</text>\n",
                     left, spec.height - 2.0, hidden);
  }
  s += "</svg>\n";
  return s;
}

}  // namespace sylva::bench
