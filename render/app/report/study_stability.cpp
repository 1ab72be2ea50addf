// Study 5: the stability suite (tests/stability, ctest label `stability`) run as it is built, one row
// per case. The cases are the suite's own GoogleTest binary, run with JSON output and parsed, so the
// report and ctest can never disagree about a case. The slow *Full* cases (label stability-full) are
// left out, as in the default ctest run.
#include <chrono>
#include <fstream>
#include <unistd.h>

#include "sim/core/error.h"
#include "sim/core/params.h"
#include "render/app/report/study.h"
#include "sim/core/child_process.h"

namespace spume::report {
namespace {

std::filesystem::path suite_binary(const StudyContext& c) {
  for (const auto& candidate : {c.exe_dir / "tests" / "spume_stability_tests", c.exe_dir / "spume_stability_tests"})
    if (std::filesystem::is_regular_file(candidate)) return candidate;
  fail("the stability suite is not built next to spume (looked for ", (c.exe_dir / "tests" / "spume_stability_tests").string(),
       "): build it with `cmake --build build --target spume_stability_tests`, or leave the study out with --only");
}

std::string first_line(const std::string& text) {
  const auto end = text.find('\n');
  std::string line = text.substr(0, end);
  return line.size() > 160 ? line.substr(0, 157) + "..." : line;
}

}  // namespace

StudyResult study_stability(const StudyContext& c) {
  StudyResult r;
  r.key = "stability";
  r.title = "5. Stability suite: pass or fail per case";
  r.measures =
      "Every case of the stability suite (extreme and unreasonable inputs: degenerate fluids, huge time steps, "
      "stiff drag, emission budgets, bad files, solver limits; tests/stability, ctest label `stability`) is run from "
      "the suite's own binary and tabulated";
  r.measures += c.quick ? "; --quick leaves out the slow *Full* cases (label stability-full)"
                        : ", the slow *Full* cases (label stability-full) included";
  const std::filesystem::path binary = suite_binary(c);
  const std::filesystem::path json =
      std::filesystem::temp_directory_path() / str("spume_report_stability_", getpid(), ".json");
  c.progress(str("stability: running ", binary.string()));
  const ProcessResult run =
      run_process({binary.string(), c.quick ? "--gtest_filter=-*Full*" : "--gtest_filter=*",
                   "--gtest_output=json:" + json.string()});
  if (!run.started) fail(binary.string(), ": could not be run: ", run.start_error);
  Json doc;
  try {
    std::ifstream in(json);
    if (!in) fail(binary.string(), " wrote no results (exit code ", run.exit_code, "):\n", run.output.substr(0, 2000));
    doc = Json::parse(in);
  } catch (const Json::exception& e) {
    fail(json.string(), ": unreadable test results: ", e.what());
  }
  std::error_code ec;
  std::filesystem::remove(json, ec);

  r.table.columns = {"suite", "case", "result", "seconds", "first failure"};
  int passed = 0, failed = 0;
  double total = 0.0;
  std::vector<std::string> failing;
  Series pass_times{"passed", {}, false, false, "dark-green"}, fail_times{"failed", {}, false, false, "red"};
  int index = 0;
  for (const Json& suite : doc.at("testsuites")) {
    for (const Json& test : suite.at("testsuite")) {
      if (test.value("status", "RUN") != "RUN") continue;  // disabled
      const bool ok = !test.contains("failures") || test.at("failures").empty();
      const double seconds = std::stod(test.value("time", "0s"));
      std::string failure;
      if (!ok) failure = first_line(test.at("failures").at(0).value("failure", ""));
      const std::string name = suite.value("name", "") + "." + test.value("name", "");
      r.table.add_row({suite.value("name", ""), test.value("name", ""), ok ? "pass" : "FAIL", num(seconds, 3), failure});
      (ok ? pass_times : fail_times).points.push_back({double(++index), std::max(seconds, 1e-3)});
      if (ok) ++passed;
      else ++failed, failing.push_back(name);
      total += seconds;
    }
  }
  if (passed + failed == 0) fail(binary.string(), ": ran no case (exit code ", run.exit_code, ")");
  r.figure.panels = {Panel{"Stability cases: run time and result", "case (row of the table)",
                           "run time (s; under 1 ms shown at 1 ms)", false, true,
                           false, {pass_times, fail_times}}};
  r.reading = str(passed, " of ", passed + failed, " cases pass", failed ? "; failing: " : "", [&] {
    std::string list;
    for (size_t i = 0; i < failing.size(); ++i) list += (i ? ", " : "") + failing[i];
    return list;
  }(), ". The suite ran in ", num(total, 3), " s of test time (the exit code of the suite was ", run.exit_code,
                  "). A failing case is a known bug the suite found, named by its test; the table's last column is the "
                  "first line of its first failed expectation.");
  return r;
}

}  // namespace spume::report
