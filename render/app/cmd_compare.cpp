// spume compare: image regression over frame sequences (or two images), with a report for people
// (report.html) and for scripts (summary.csv, summary.json). Exit 0 when every frame passes, 1 when
// one fails, 2 when there is no verdict (the command cannot run as typed, or its report cannot be
// written).
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "render/app/cli/cli_args.h"
#include "render/app/commands.h"
#include "render/app/compare/compare_report.h"
#include "render/app/compare/summary_files.h"
#include "render/app/compare/threshold_args.h"
#include "sim/core/messages.h"
#include "sim/core/parallel.h"
#include "sim/core/progress.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using namespace compare;

std::vector<cli::OptionSpec> compare_options() {
  return {{"out", "DIR", "report.html, summary.csv, summary.json, thumbs/ and diff/"},
          {"fail", "LEVELS", "a pixel fails over this difference (0-255, N or N/255; default 1)"},
          {"failpercent", "P", "a frame fails when over P% of its pixels fail (default 0.02)"},
          {"hardfail", "LEVELS", "a frame fails when any pixel differs by more (default 3)"},
          {"frames", "SPEC", "numbered frames only: 7, 0-99, 0-99:2, 1-3,5,10-20"},
          {"scale", "N", "difference images show |reference - new| x N (default 16)"},
          {"threads", "N", "worker threads (one per core; results do not depend on it)"},
          cli::quiet_option()};
}

// The worst failing frames, one line each, then one line for the whole comparison.
void print_summary(const std::vector<FrameResult>& results, const CompareOptions& o) {
  const Overall all = summarize(results);
  size_t shown = 0;
  for (size_t i : worst_first(results)) {
    const FrameResult& r = results[i];
    if (r.passed()) break;
    if (++shown > 20) {
      std::printf("... and %zu more failing frames (summary.csv lists every frame)\n", all.failed - 20);
      break;
    }
    std::printf("FAIL %s: %s\n", r.pair.label.c_str(), r.reason.c_str());
  }
  std::printf("compare: %s, %zu frame%s: %zu fail, %zu pass (%zu identical)", all.pass() ? "PASS" : "FAIL", all.frames,
              all.frames == 1 ? "" : "s", all.failed, all.passed, all.identical);
  if (all.worst) {
    const FrameResult& w = results[*all.worst];
    const std::string psnr = w.stats.identical() ? "infinite" : format_fixed(w.stats.psnr_db(), 2) + " dB";
    std::printf("; worst compared %s: %s%% of pixels over %d/255, max %d/255, PSNR %s, SSIM %s", w.pair.label.c_str(),
                format_fixed(w.stats.over_fail_percent(), 4).c_str(), o.thresholds.fail, w.stats.max_diff, psnr.c_str(),
                w.ssim.defined ? format_fixed(w.ssim.mean, 5).c_str() : "n/a");
  }
  std::printf("\n");
}

// The report folder is created and written to before any frame is compared, so that a folder that
// cannot take the report fails at once, as the usage error it is (exit 2), never as "frames differ".
void check_report_folder(const fs::path& out) {
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw UsageError(str("--out ", out.string(), ": cannot create the report folder (", ec.message(), ")"));
  if (!fs::is_directory(out, ec)) throw UsageError(str("--out ", out.string(), ": is a file, not a folder"));
  const fs::path probe = out / str(".spume_compare_probe_", ::getpid());
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0)
    throw UsageError(str("--out ", out.string(), ": cannot write in the report folder (", std::strerror(errno), ")"));
  ::close(fd);
  fs::remove(probe, ec);
}

int compare_frames(const cli::ParsedArgs& args) {
  CompareOptions opts;
  if (args.positional.size() != 2)
    throw UsageError(str("expected REFERENCE and NEW, got ", args.positional.size(), " argument",
                         args.positional.size() == 1 ? "" : "s"));
  if (auto v = args.value("fail")) opts.thresholds.fail = parse_level(*v, "--fail");
  if (auto v = args.value("hardfail")) opts.thresholds.hardfail = parse_level(*v, "--hardfail");
  if (auto v = args.value("failpercent")) opts.thresholds.failpercent = parse_percent(*v, "--failpercent");
  if (auto v = args.value("scale")) opts.diff_scale = cli::parse_int(*v, "--scale", 1, 255);
  if (auto v = args.value("threads")) set_thread_count(cli::parse_int(*v, "--threads", 1, 1024));
  if (auto v = args.value("out")) {
    if (v->empty()) throw UsageError("--out: the folder name is empty");
    opts.out = fs::path(*v);
  }
  const FrameSet set = resolve_frames(args.positional[0], args.positional[1], args.value("frames"));
  if (opts.out) check_report_folder(*opts.out);
  const bool quiet = args.has("quiet");
  for (const std::string& note : set.notes)
    if (messages::is_warning(note)) messages::warning(note);
    else messages::note("compare: " + note);
  Progress progress("compare", set.frames.size(), quiet);
  std::vector<FrameResult> results;
  try {
    results = compare_and_report(set, opts, [&](size_t done) { progress.update(done); });
  } catch (const Error& e) {
    // Exit 1 means "frames differ" to a CI gate; a comparison that could not finish (a report that
    // could not be written, a disk that filled up) is not a verdict.
    std::fprintf(stderr, "spume compare: error: %s (no verdict)\n", e.what());
    return cli::kExitUsage;
  }
  progress.finish();
  print_summary(results, opts);
  if (opts.out) std::printf("Saved: %s\n", (*opts.out / "report.html").string().c_str());
  return summarize(results).pass() ? 0 : 1;
}

}  // namespace

Command cmd_compare() {
  cli::CommandSpec spec;
  spec.name = "compare";
  spec.forms = {"REFERENCE NEW [options]"};
  spec.summary = "image regression of two frame sequences (or images): report.html, summary.csv/json";
  spec.options = compare_options();
  spec.max_operands = 2;
  spec.notes = {"REFERENCE, NEW: two PNG files, two folders of PNG frames (matched by file name; a scene's output",
                "folder means its frames/), or frame patterns such as out/wave/frames/%04d.png (matched by number).",
                "A frame fails when more than --failpercent of its pixels differ by more than --fail, when any pixel",
                "differs by more than --hardfail, or when it is missing, unreadable or of another size.",
                "Exit status: 0 every frame passes, 1 a frame fails, 2 no verdict: a usage error, or a report folder (--out)",
                "that cannot be created or written."};
  return {spec, compare_frames};
}

}  // namespace spume
