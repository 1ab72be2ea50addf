// Slurm scripts of a farm render: the #SBATCH lines (array range, partition, throttle), the
// dependency of the array on the simulation job, and shell quoting, checked by running the scripts
// through bash with the commands replaced by printf.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "sim/core/error.h"
#include "render/app/farm/slurm_script.h"
#include "tests/support/error_of.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text.h"

namespace spume::farm {
namespace {

namespace fs = std::filesystem;
using testing::error_of;

SlurmFarm example() {
  SlurmFarm farm;
  farm.scene_name = "wave";
  farm.simulate_command = {"/opt/spume", "simulate", "/data/wave.json"};
  farm.render_command = {"/opt/spume", "render", "/data/wave.json", "--out", "/data/out"};
  farm.chunks = {"0-9", "10-19", "20-24"};
  farm.farm_dir = "/data/out/wave/farm";
  farm.work_dir = "/data";
  return farm;
}

using spume::testing::contains;

// Runs `script` with bash (environment assignments first) and returns its stdout.
std::string run_bash(const std::string& script, const std::string& environment = "") {
  const testing::TempDir temp("slurm_script");
  const fs::path file = temp.write("script.sh", script);
  return testing::run_command(environment + " bash " + file.string() + " 2>&1").output;
}

TEST(SlurmScripts, ArrayHasOneTaskPerChunk) {
  const SlurmScripts s = make_slurm_scripts(example());
  EXPECT_TRUE(contains(s.render, "\n#SBATCH --array=0-2\n")) << s.render;
  EXPECT_TRUE(contains(s.render, "#SBATCH --job-name=spume-render-wave\n")) << s.render;
  EXPECT_TRUE(contains(s.render, "'0-9'  # task 0\n  '10-19'  # task 1\n  '20-24'  # task 2\n")) << s.render;
  EXPECT_TRUE(contains(s.render, "--frames \"${chunks[$SLURM_ARRAY_TASK_ID]}\"")) << s.render;
}

TEST(SlurmScripts, PartitionThrottleCpusAndExtraOptionsGoToBothJobs) {
  SlurmFarm farm = example();
  farm.partition = "gpu,long";
  farm.max_running = 4;
  farm.cpus_per_task = 8;
  farm.sbatch_options = {"--time=2:00:00", "--account=fx"};
  const SlurmScripts s = make_slurm_scripts(farm);
  EXPECT_TRUE(contains(s.render, "#SBATCH --array=0-2%4\n")) << s.render;
  for (const std::string& script : {s.render, s.simulate}) {
    EXPECT_TRUE(contains(script, "#SBATCH --partition=gpu,long\n")) << script;
    EXPECT_TRUE(contains(script, "#SBATCH --cpus-per-task=8\n")) << script;
    EXPECT_TRUE(contains(script, "#SBATCH --time=2:00:00\n#SBATCH --account=fx\n")) << script;
  }
}

TEST(SlurmScripts, NoPartitionLineByDefault) {
  const SlurmScripts s = make_slurm_scripts(example());
  EXPECT_FALSE(contains(s.render, "--partition")) << s.render;
  EXPECT_FALSE(contains(s.simulate, "--partition")) << s.simulate;
}

TEST(SlurmScripts, ArrayWaitsForTheSimulationJob) {
  const SlurmScripts s = make_slurm_scripts(example());
  EXPECT_TRUE(contains(s.simulate, "#SBATCH --job-name=spume-simulate-wave\n")) << s.simulate;
  EXPECT_TRUE(contains(s.simulate, "exec '/opt/spume' 'simulate' '/data/wave.json'\n")) << s.simulate;
  EXPECT_TRUE(contains(s.submit, "simulation=$(sbatch --parsable")) << s.submit;
  EXPECT_TRUE(contains(s.submit, "--dependency=afterok:$simulation ")) << s.submit;
  EXPECT_LT(s.submit.find("simulate.sbatch"), s.submit.find("render.sbatch")) << s.submit;
}

TEST(SlurmScripts, CurrentCachesMeanNoSimulationJobAndNoDependency) {
  SlurmFarm farm = example();
  farm.simulate_command.clear();
  const SlurmScripts s = make_slurm_scripts(farm);
  EXPECT_TRUE(s.simulate.empty());
  EXPECT_FALSE(contains(s.submit, "dependency")) << s.submit;
  EXPECT_FALSE(contains(s.submit, "simulate.sbatch")) << s.submit;
  EXPECT_TRUE(contains(s.submit, "render.sbatch")) << s.submit;
}

TEST(SlurmScripts, ShellQuotingSurvivesSpacesQuotesAndDollars) {
  for (const std::string text : {"plain", "a b", "it's", "$HOME `id` \"x\" \\n", "", "''"}) {
    EXPECT_EQ(run_bash("printf '%s' " + shell_quote(text)), text) << shell_quote(text);
  }
}

TEST(SlurmScripts, ArrayTaskRunsItsChunkWithEveryArgumentIntact) {
  SlurmFarm farm = example();
  farm.render_command = {"printf", "[%s]\\n", "/my data/it's.json", "--set", "render.seed=$RANDOM"};
  const SlurmScripts s = make_slurm_scripts(farm);
  EXPECT_EQ(run_bash(s.render, "SLURM_ARRAY_TASK_ID=1"),
            "[/my data/it's.json]\n[--set]\n[render.seed=$RANDOM]\n[--frames]\n[10-19]\n");
  EXPECT_EQ(run_bash(s.render, "SLURM_ARRAY_TASK_ID=2"),
            "[/my data/it's.json]\n[--set]\n[render.seed=$RANDOM]\n[--frames]\n[20-24]\n");
}

TEST(SlurmScripts, SubmitScriptPassesQuotedPathsToSbatch) {
  SlurmFarm farm = example();
  farm.farm_dir = "/tmp/spume farm's test";
  farm.work_dir = "/tmp/work dir";
  const SlurmScripts s = make_slurm_scripts(farm);
  // A fake sbatch prints its arguments one per line and a job id.
  const testing::TempDir fake_bin;
  const fs::path& bin = fake_bin.path;
  std::ofstream(bin / "sbatch") << "#!/bin/bash\nprintf '<%s>\\n' \"$@\" >&2\necho 42\n";
  fs::permissions(bin / "sbatch", fs::perms::owner_all);
  const std::string out = run_bash(s.submit, "PATH='" + bin.string() + ":'\"$PATH\"");
  fs::remove_all(farm.farm_dir);
  EXPECT_TRUE(contains(out, "<--chdir=/tmp/work dir>\n")) << out;
  EXPECT_TRUE(contains(out, "<--output=/tmp/spume farm's test/logs/simulate_%j.log>\n")) << out;
  EXPECT_TRUE(contains(out, "</tmp/spume farm's test/simulate.sbatch>\n")) << out;
  EXPECT_TRUE(contains(out, "<--dependency=afterok:42>\n<--kill-on-invalid-dep=yes>\n")) << out;
  EXPECT_TRUE(contains(out, "<--output=/tmp/spume farm's test/logs/render_%A_%a.log>\n")) << out;
  EXPECT_TRUE(contains(out, "Submitted simulation job 42\n")) << out;
  EXPECT_TRUE(contains(out, "Submitted render array job 42 (3 tasks, after job 42)\n")) << out;
}

TEST(SlurmScripts, ScriptsAreValidBash) {
  const SlurmScripts s = make_slurm_scripts(example());
  for (const std::string& script : {s.simulate, s.render, s.submit}) {
    const testing::TempDir temp;
    const fs::path file = temp.write("script.sh", script);
    EXPECT_EQ(testing::run_command("bash -n " + file.string()).status, 0) << script;
  }
}

TEST(SlurmScripts, BadValuesAreErrorsNamingTheOption) {
  SlurmFarm farm = example();
  auto error = [&] { return error_of([&] { make_slurm_scripts(farm); }); };
  farm.partition = "gpu\n#SBATCH --x";
  std::string e = error();
  EXPECT_TRUE(contains(e, "--partition")) << e;
  EXPECT_TRUE(contains(e, "letters, digits")) << e;
  farm = example();
  farm.sbatch_options = {"time=1:00"};
  e = error();
  EXPECT_TRUE(contains(e, "--sbatch") && contains(e, "time=1:00")) << e;
  farm.sbatch_options = {"--time=1\n--mem=1G"};
  EXPECT_TRUE(contains(error(), "one option per --sbatch")) << error();
  farm = example();
  farm.chunks.clear();
  EXPECT_TRUE(contains(error(), "no frames")) << error();
}

TEST(SlurmScripts, JobNamesKeepToSafeCharacters) {
  SlurmFarm farm = example();
  farm.scene_name = "my wave;rm";
  const SlurmScripts s = make_slurm_scripts(farm);
  EXPECT_TRUE(contains(s.render, "#SBATCH --job-name=spume-render-my_wave_rm\n")) << s.render;
}

}  // namespace
}  // namespace spume::farm
