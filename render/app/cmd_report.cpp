// spume report: error against run time for the renderer, the diffuse integrators, the fluid solver and
// the surface reconstruction, plus the stability table, as OUT/report/ (CSV + PNG per study, report.md).
#include <algorithm>
#include <cstdio>

#include "render/app/cli/cli_args.h"
#include "render/app/commands.h"
#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/core/stopwatch.h"
#include "render/app/report/report_writer.h"
#include "render/app/report/study.h"

namespace spume {
namespace {

struct StudyEntry {
  const char* name;
  report::StudyResult (*run)(const report::StudyContext&);
};

// Run and report order: render, diffuse, fluid, surface, stability (each study is independent).
constexpr StudyEntry kStudies[] = {{"render", report::study_render},
                                   {"diffuse", report::study_diffuse},
                                   {"fluid", report::study_fluid},
                                   {"surface", report::study_surface},
                                   {"stability", report::study_stability}};

std::string allowed_studies() {
  std::string s;
  for (const auto& e : kStudies) {
    if (!s.empty()) s += ',';
    s += e.name;
  }
  return s;
}

std::vector<std::string> parse_only(const std::string& text) {
  std::vector<std::string> names;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = text.find(',', start);
    const std::string name = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const bool known = std::any_of(std::begin(kStudies), std::end(kStudies),
                                   [&](const StudyEntry& e) { return name == e.name; });
    if (!known)
      cli::usage_fail("--only: \"", name, "\" is not a study; allowed: ", allowed_studies(), " (comma-separated)");
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return names;
}

int report_command(const cli::ParsedArgs& args) {
  std::vector<std::string> selected;
  if (auto only = args.value("only")) selected = parse_only(*only);
  else
    for (const auto& e : kStudies) selected.push_back(e.name);
  if (args.has("threads")) set_thread_count(cli::parse_int(*args.value("threads"), "--threads", 1, 1024));

  report::StudyContext context;
  context.scene_path = args.positional.empty() ? "scenes/wave.json" : args.positional[0];
  context.out_root = args.value("out").value_or("out");
  context.quick = args.has("quick");
  context.quiet = args.has("quiet");
  std::error_code ec;
  context.exe_dir = std::filesystem::read_symlink("/proc/self/exe", ec).parent_path();
  const bool needs_scene = std::any_of(selected.begin(), selected.end(),
                                       [](const std::string& s) { return s == "render" || s == "diffuse"; });
  if (needs_scene && !std::filesystem::is_regular_file(context.scene_path))
    fail(context.scene_path.string(), ": no such scene file (the render and diffuse studies need one)");
  context.progress = [quiet = context.quiet](const std::string& line) {
    if (!quiet) std::fprintf(stderr, "report: %s\n", line.c_str()), std::fflush(stderr);
  };

  const std::filesystem::path dir = context.out_root / "report";
  const Stopwatch start;
  std::vector<report::StudyResult> results;
  for (const auto& entry : kStudies) {
    if (std::find(selected.begin(), selected.end(), entry.name) == selected.end()) continue;
    context.progress(str("study ", entry.name, " ..."));
    const Stopwatch t0;
    report::StudyResult result = with_context(str("study ", entry.name), [&] { return entry.run(context); });
    result.seconds = t0.seconds();
    report::write_study_files(result, dir);
    context.progress(str("study ", entry.name, " done in ", report::num(result.seconds, 3), " s -> ",
                         (dir / (result.key + ".csv")).string()));
    results.push_back(std::move(result));
  }
  report::ReportHeader header;
  header.scene = context.scene_path.string();
  header.quick = context.quick;
  header.threads = thread_count();
  header.seconds = start.seconds();
  header.command = "spume report";
  for (const auto& a : args.raw) header.command += " " + a;
  report::write_report_markdown(header, results, dir);
  if (!context.quiet) std::printf("Saved: %s\n", (dir / "report.md").string().c_str());
  return 0;
}

}  // namespace

Command cmd_report() {
  cli::CommandSpec spec;
  spec.name = "report";
  spec.forms = {"[SCENE.json] [options]"};
  spec.summary = "error against run time of each method, and the stability table -> OUT/report/";
  spec.notes = {"SCENE.json (default scenes/wave.json) is the scene of the render and diffuse studies"};
  spec.options = {
      {"quick", "", "smaller problems and fewer settings (on 2 cores: under 3 minutes against 4 for all)"},
      {"only", "LIST", "studies to run, comma-separated: " + allowed_studies() + " (default: all)"},
      {"out", "DIR", "output root (default out/): the report goes to DIR/report/, scene caches to DIR/<scene>/"},
      {"threads", "N", "worker threads (default: one per core)"},
      cli::quiet_option(),
  };
  spec.runs_without_arguments = true;  // the whole report on the default scene
  return {spec, report_command};
}

}  // namespace spume
