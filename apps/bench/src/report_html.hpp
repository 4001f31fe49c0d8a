#pragma once
// The self-contained HTML report (GL-free): run and machine facts, the error-against-time plot
// (inline SVG, Pareto front marked), one table row per setting (<tr class="setting">; the
// reference row has class "reference"), and per setting the rendered frame with the largest
// error next to the reference frame and their difference heat map.
//
// Images are referenced through `image_src`, which maps a path relative to the output folder to
// what goes into src="...": the bench passes a function returning data: URIs (so the file is
// self-contained), tests may pass the path unchanged.

#include "results.hpp"

#include <functional>
#include <string>

namespace sylva::bench {

using ImageSource = std::function<std::string(const std::string& relative_path)>;

std::string render_report_html(const BenchReport& report, const ImageSource& image_src);

// The start of a bench HTML page up to <body>: the title (escaped) and the reports' common style
// (page, tables, left-aligned cells "l") followed by `extra_css` rules.
std::string html_page_start(const std::string& title, const std::string& extra_css);

// The plot alone (also used by tests and the README).
std::string report_plot_svg(const BenchReport& report);

}  // namespace sylva::bench
