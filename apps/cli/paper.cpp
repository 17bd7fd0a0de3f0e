// apps/cli/paper.cpp — `polydec paper --data DIR --out DIR`: the paper's whole evaluation (Tables
// 1-6, Figure 9, Figures 7/8-style pictures) with every Laplacian; writes report.md, results.json
// (with the phases' and each step's times) and the pictures, with a progress bar on stderr.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>

#include "polydec/apps/cli/command.h"
#include "polydec/apps/pictures/image.h"
#include "polydec/apps/paper/paper.h"
#include "polydec/dec/io/mesh_io.h"

namespace polydec::cli::paper_command {
namespace {

struct Options {
  std::string data = "../shared/data", out = "paper-out", report_from;
  bool quick = false, no_timings = false, no_pictures = false, json = false, quiet = false;
  int repeats = 3;
};

// A one-line bar redrawn in place on a terminal; one line per step otherwise (logs stay readable).
class ProgressBar {
 public:
  ProgressBar() : tty_(isatty(fileno(stderr)) != 0), start_(std::chrono::steady_clock::now()) {}
  void operator()(double fraction, const std::string& step) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const int width = 30, filled = int(fraction * width + 0.5);
    const std::string bar = std::string(filled, '#') + std::string(width - filled, '.');
    const std::string line = fmt::format("[{}] {:3.0f}% {:6.1f} s  {}", bar, 100 * fraction, s, step);
    if (tty_)
      fmt::print(stderr, "\r{:<110.110}{}", line, fraction >= 1 ? "\n" : "");
    else
      fmt::print(stderr, "{}\n", line);
    std::fflush(stderr);
  }

 private:
  bool tty_;
  std::chrono::steady_clock::time_point start_;
};

void run(const Options& o) {
  if (!o.report_from.empty()) {  // only re-render the report of an earlier run
    std::ifstream in(o.report_from);
    if (!in) throw FileError(o.report_from, 0, -1, "cannot open file");
    const nlohmann::json results = nlohmann::json::parse(in, nullptr, false);
    if (results.is_discarded() || !results.contains("paper"))
      throw FileError(o.report_from, 0, -1, "not a results.json of polydec paper");
    std::filesystem::create_directories(o.out);
    write_file_atomically(o.out + "/report.md", paper_report_markdown(results));
    fmt::print("wrote {}/report.md\n", o.out);
    return;
  }
  if (!std::filesystem::is_directory(o.data))
    throw UsageError(fmt::format("--data {}: no such folder (the paper's meshes, e.g. ../shared/data)", o.data));
  if (o.repeats < 1 || o.repeats > 100) throw UsageError("--repeats must be in [1, 100]");
  PaperOptions p;
  p.data_dir = o.data;
  p.out_dir = o.out;
  p.quick = o.quick;
  p.timings = !o.no_timings;
  p.pictures = !o.no_pictures;
  p.timing_repeats = o.repeats;
  ProgressBar bar;
  if (!o.quiet) p.progress = std::ref(bar);
  PhaseTimer timer;
  nlohmann::json results = timer.time("evaluation", [&] { return reproduce_paper(p); });
  // The phases so far (results.json itself is written after them).
  timer.time("write", [&] { write_file_atomically(o.out + "/report.md", paper_report_markdown(results)); });
  results["times_ms"] = timer.json();
  write_file_atomically(o.out + "/results.json", results.dump(2) + "\n");
  if (o.json) {
    print_json(results);
    return;
  }
  fmt::print("wrote {0}/report.md, {0}/results.json{1}\n", o.out,
             o.no_pictures ? "" : ", figure7-geodesics.png, figure8-geodesics.png, figure9*.svg/png");
}

const RegisterCommand reg(
    "paper", "The paper's whole evaluation (Tables 1-6, Figure 9, pictures) with every Laplacian",
    [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      app.add_option("--data", o->data, "folder with the paper's meshes (default ../shared/data)");
      app.add_option("--out", o->out, "output folder for report.md, results.json and pictures (default paper-out)");
      app.add_flag("--quick", o->quick, "leave out HEX/FINE SPHERE and Table 5, coarse Poisson grids (seconds)");
      app.add_flag("--no-timings", o->no_timings, "leave out Table 5");
      app.add_flag("--no-pictures", o->no_pictures, "write no pictures or plots");
      app.add_option("--repeats", o->repeats,
                     "Table 5: this many interleaved rounds, medians reported (default 3)");
      app.add_flag("--quiet", o->quiet,
                   "no progress lines on stderr (they never go to stdout, --json or not)");
      app.add_flag("--json", o->json, "also print results.json on stdout");
      app.add_option("--report-from", o->report_from, "only write report.md from an earlier run's results.json");
      app.callback([o] { run(*o); });
    });

}  // namespace
}  // namespace polydec::cli::paper_command
