// spume compare: image regression over frame sequences (or two images), with a report for people
// (report.html) and for scripts (summary.csv, summary.json). Exit 0 when every frame passes, 1 when
// one fails, 2 when the command cannot run as typed.
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli_args.h"
#include "commands.h"
#include "compare/compare_report.h"
#include "compare/summary_files.h"
#include "compare/threshold_args.h"
#include "core/parallel.h"
#include "core/progress.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using namespace compare;

constexpr const char* kUsage =
    "usage: spume compare REFERENCE NEW [options]\n"
    "  REFERENCE, NEW: two PNG files, two folders of PNG frames (matched by file name; a scene's output\n"
    "  folder means its frames/), or frame patterns such as out/wave/frames/%04d.png (matched by number).\n"
    "  A frame fails when more than --failpercent of its pixels differ by more than --fail, when any pixel\n"
    "  differs by more than --hardfail, or when it is missing, unreadable or of another size.\n"
    "  Exit status: 0 every frame passes, 1 a frame fails, 2 usage error.\n";

std::vector<cli::OptionSpec> compare_options() {
  // Padded so that the help texts line up in the listing ("  --NAME ARG  help").
  return {{"out", true, false, "DIR          report.html, summary.csv, summary.json, thumbs/ and diff/"},
          {"fail", true, false, "LEVELS      a pixel fails over this difference (0-255, N or N/255; default 1)"},
          {"failpercent", true, false, "P    a frame fails when over P% of its pixels fail (default 0.02)"},
          {"hardfail", true, false, "LEVELS  a frame fails when any pixel differs by more (default 3)"},
          {"frames", true, false, "SPEC      numbered frames only: 7, 0-99, 0-99:2, 1-3,5,10-20"},
          {"scale", true, false, "N          difference images show |reference - new| x N (default 16)"},
          {"threads", true, false, "N        worker threads (one per core; results do not depend on it)"},
          {"quiet", false, false, "           no progress on stderr"}};
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

}  // namespace

int command_compare(const std::vector<std::string>& raw) {
  const std::vector<cli::OptionSpec> options = compare_options();
  if (raw.empty()) {
    std::fprintf(stderr, "%s%s\n", kUsage, cli::usage_lines(options).c_str());
    return 2;
  }
  cli::ParsedArgs args;
  CompareOptions opts;
  FrameSet set;
  try {
    args = cli::parse(raw, options, "compare");
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
    set = resolve_frames(args.positional[0], args.positional[1], args.value("frames"));
  } catch (const Error& e) {
    std::string message = e.what();
    const std::string prefix = "spume compare: ";  // the option parser names the command itself
    if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
    std::fprintf(stderr, "%s%s\n%s", prefix.c_str(), message.c_str(), kUsage);
    return 2;
  }
  const bool quiet = args.has("quiet");
  if (!quiet)
    for (const std::string& note : set.notes) std::fprintf(stderr, "compare: %s\n", note.c_str());
  Progress progress("compare", set.frames.size(), quiet);
  const std::vector<FrameResult> results =
      compare_and_report(set, opts, [&](size_t done) { progress.update(done); });
  progress.finish();
  print_summary(results, opts);
  if (opts.out) std::printf("Saved: %s\n", (*opts.out / "report.html").string().c_str());
  return summarize(results).pass() ? 0 : 1;
}

}  // namespace spume
