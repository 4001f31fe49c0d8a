#pragma once
// Error-against-time scatter plot as inline SVG (GL-free), for the HTML report.
//
// Linear axes with "nice" ticks (1, 2, 5 x 10^k) that include every finite point; points whose
// coordinates are not finite are left out and counted in a note under the plot. Pareto-front
// points are filled and joined by a staircase line (the best error reachable for a given time
// budget); the reference render is a diamond. Every point carries a <title> tooltip.

#include <string>
#include <vector>

namespace sylva::bench {

struct PlotPoint {
  double x = 0.0;
  double y = 0.0;
  std::string label;    // drawn next to the point (e.g. "s003")
  std::string tooltip;  // full text on hover
  bool front = false;
  bool reference = false;
};

struct PlotSpec {
  std::string x_title;
  std::string y_title;
  int width = 760;   // pixels
  int height = 440;
  bool log_x = false;  // logarithmic x axis (points with x <= 0 are then not drawn)
  bool legend = true;  // the Pareto / dominated / reference legend (plots without a front omit it)
};

// Whether costs spread over more than a factor of 10 (a log axis then keeps the cheap settings
// apart when the reference is much slower).
bool wants_log_axis(const std::vector<double>& values);

// Ticks 1, 2, 5 x 10^k covering [lo, hi] (both > 0) for a log axis.
std::vector<double> log_ticks(double lo, double hi);

// Ticks covering [lo, hi] with about `target` steps; lo == hi gets a small range around it.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

std::string scatter_svg(const std::vector<PlotPoint>& points, const PlotSpec& spec);

// Escapes & < > " ' for HTML / SVG text and attributes.
std::string html_escape(const std::string& text);

}  // namespace sylva::bench
