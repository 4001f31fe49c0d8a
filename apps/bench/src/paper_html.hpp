#pragma once
// paper.html of `sylva-bench --paper` (GL-free): per thesis table the thesis's numbers beside
// Sylva's (the cells of paper_report.hpp's grid), a shape plot (each quantity divided by its first
// row, thesis and Sylva on one chart: the comparison that holds across a 2010 GPU and this
// machine), and, where the table has an image-quality dimension, each run row's error-against-time
// plot. Self-contained: inline SVG, links to the rows' sweep reports.

#include "paper_report.hpp"

#include <string>
#include <vector>

namespace sylva::bench {

std::string paper_html(const std::string& thesis, const std::vector<PaperOutcome>& outcomes, CostMetric cost,
                       const MachineInfo& machine, const std::string& gl_renderer);

}  // namespace sylva::bench
