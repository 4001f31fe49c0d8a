#pragma once
// `sylva-bench --paper`: runs each table of paper_tables.hpp through the scene module (one sweep
// per table row: the row's settings fixed, one setting per column, the table's reference) and
// writes the side-by-side report (paper_report.hpp). Needs a current GL context.

#include "runner.hpp"

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>

namespace sylva::bench {

struct PaperRunOptions {
  std::string which;                       // 000 .. 004 or all
  bool quick = false;                      // first row of each table, 256x144, 2 frames
  std::vector<std::string> tables;         // only these tables (paper_table_matches); empty = all
  std::filesystem::path out;               // DIR: each thesis writes DIR/paper-<thesis>/
  std::function<void(RunSpec&)> customise; // the command line's --frames, --size, --set ... (may be empty)
  bool embed_images = true;
  std::string gl_renderer, gl_version;
};

// Exit code: 0 every table ran (or is documented as not reproducible yet), 1 a table failed,
// 3 a thesis has no tables in this build.
int run_paper(const PaperRunOptions& options, std::ostream& out, std::ostream& err);

}  // namespace sylva::bench
