// apps/paper/paper.h — the whole evaluation of "Polygon Laplacian Made Simple" (section 5: Tables 1-6,
// Figure 9, the negative off-diagonal ratios of section 5.5 and Figure 7/8-style pictures) with
// every Laplacian of operators/registry/laplacians.h, run on the paper's meshes (../shared/data, set-up as
// its README describes). `polydec paper` (apps/cli/paper.cpp) writes what this returns.
//
// Results are JSON: table ("table1" ... "table6", "figure9", "figure7") -> mesh (the paper's name,
// e.g. "REGULAR SPHERE") -> method -> value. Method keys are operator names ("ours", "aw11:0.5"),
// with "-unlumped" appended where the Galerkin mass replaces the lumped one. Table 5 values are
// objects of timings in ms and ratios to "ours" measured in the same run. The paper's printed
// values and the authors' program's values sit under "paper" and "authors_program" in the same
// shape, so the report and the tests compare like with like.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>

namespace polydec {

struct PaperOptions {
  std::string data_dir = "../shared/data";  // the paper's meshes
  std::string out_dir;                      // pictures and plots go here (nothing is written when empty)
  bool quick = false;     // skip FINE SPHERE and HEX SPHERE (the two big meshes), Table 5, and
                          // use coarser Poisson grids: for tests (seconds instead of minutes)
  bool timings = true;    // Table 5 (ignored when quick)
  bool pictures = true;   // Figure 7/8-style PNGs and the Figure 9 plots (needs out_dir)
  int timing_repeats = 3; // Table 5: median of this many runs
  // Called before each step with the fraction done in [0, 1) and what comes next, and once
  // with 1 at the end.
  std::function<void(double fraction, const std::string& step)> progress;
};

// Runs the evaluation; "step_times_ms" holds each step's wall time (its progress label as key).
// Throws FileError when a mesh of data_dir is missing or unreadable.
nlohmann::json reproduce_paper(const PaperOptions& options);

// The report as Markdown: every table with our value, every baseline, and the paper's printed
// value side by side, the deviation from the paper, and the set-up of each experiment.
// `results` is what reproduce_paper returned.
std::string paper_report_markdown(const nlohmann::json& results);

// The values printed in the paper (Tables 1-6, section 5.5's ratios) and those the authors'
// published program prints on ../shared/data (for "ours"), in the results' shape.
nlohmann::json paper_printed_values();
nlohmann::json authors_program_values();

}  // namespace polydec
