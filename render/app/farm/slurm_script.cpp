#include "render/app/farm/slurm_script.h"

#include <algorithm>

#include "sim/core/error.h"

namespace spume::farm {
namespace {

bool is_plain(char c, std::string_view extra) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
         extra.find(c) != std::string_view::npos;
}

// Job names show in squeue; anything but letters, digits, '.', '_' and '-' becomes '_'.
std::string job_name(const std::string& kind, const std::string& scene) {
  std::string name = "spume-" + kind + "-" + scene;
  std::replace_if(name.begin(), name.end(), [](char c) { return !is_plain(c, "._-"); }, '_');
  return name;
}

void check_values(const SlurmFarm& farm) {
  if (farm.chunks.empty()) fail("no frames to render");  // main names the command
  for (char c : farm.partition)
    if (!is_plain(c, "._-,"))
      fail("--partition: \"", farm.partition, "\" is not a partition name (letters, digits, '.', '_', '-'; "
           "several separated by ',')");
  for (const std::string& option : farm.sbatch_options) {
    if (option.empty() || option[0] != '-')
      fail("--sbatch: \"", option, "\" is not an sbatch option (e.g. --sbatch=--time=2:00:00)");
    if (option.find_first_of("\n\r") != std::string::npos)
      fail("--sbatch: \"", option, "\" spans several lines; give one option per --sbatch");
  }
}

// The #SBATCH lines both jobs share.
std::string common_header(const SlurmFarm& farm) {
  std::string text;
  if (!farm.partition.empty()) text += "#SBATCH --partition=" + farm.partition + "\n";
  if (farm.cpus_per_task > 0) text += str("#SBATCH --cpus-per-task=", farm.cpus_per_task, "\n");
  for (const std::string& option : farm.sbatch_options) text += "#SBATCH " + option + "\n";
  return text;
}

std::string command_line(const std::vector<std::string>& argv) {
  std::string text;
  for (const std::string& arg : argv) {
    if (!text.empty()) text += ' ';
    text += shell_quote(arg);
  }
  return text;
}

std::string simulate_script(const SlurmFarm& farm) {
  return "#!/bin/bash\n#SBATCH --job-name=" + job_name("simulate", farm.scene_name) + "\n" + common_header(farm) +
         "# The simulation of scene " + farm.scene_name +
         " for the render array (written by `spume farm slurm`).\n"
         "set -euo pipefail\n"
         "exec " + command_line(farm.simulate_command) + "\n";
}

std::string render_script(const SlurmFarm& farm) {
  const int tasks = int(farm.chunks.size());
  std::string array = str("0-", tasks - 1);
  if (farm.max_running > 0) array += str("%", farm.max_running);
  std::string text = "#!/bin/bash\n#SBATCH --job-name=" + job_name("render", farm.scene_name) + "\n" +
                     "#SBATCH --array=" + array + "\n" + common_header(farm) +
                     "# The render of scene " + farm.scene_name + str(" in ", tasks, " chunks") +
                     " (written by `spume farm slurm`).\n"
                     "# Array task i renders chunks[i]; frames already on disk are skipped, so\n"
                     "# submitting again renders only what is missing.\n"
                     "set -euo pipefail\n"
                     "chunks=(\n";
  for (int i = 0; i < tasks; ++i) text += "  " + shell_quote(farm.chunks[size_t(i)]) + str("  # task ", i, "\n");
  text += ")\nexec " + command_line(farm.render_command) + " --frames \"${chunks[$SLURM_ARRAY_TASK_ID]}\"\n";
  return text;
}

std::string submit_script(const SlurmFarm& farm) {
  const std::string sbatch = "sbatch --parsable --chdir=" + shell_quote(farm.work_dir.string());
  std::string text =
      "#!/bin/bash\n"
      "# Submits the farm render of scene " + farm.scene_name +
      " (written by `spume farm slurm`). Run it again to resume:\n"
      "# frames already on disk are skipped.\n"
      "set -euo pipefail\n"
      "farm=" + shell_quote(farm.farm_dir.string()) + "\n"
      "mkdir -p \"$farm/logs\"\n";
  std::string dependency;
  if (!farm.simulate_command.empty()) {
    text += "simulation=$(" + sbatch + " --output=\"$farm/logs/simulate_%j.log\" \"$farm/simulate.sbatch\")\n"
            "simulation=${simulation%%;*}  # --parsable prints JOBID or JOBID;CLUSTER\n"
            "echo \"Submitted simulation job $simulation\"\n";
    // If the simulation fails, the array is cancelled instead of pending forever.
    dependency = " --dependency=afterok:$simulation --kill-on-invalid-dep=yes";
  }
  text += "render=$(" + sbatch + dependency +
          " --output=\"$farm/logs/render_%A_%a.log\" \"$farm/render.sbatch\")\n"
          "render=${render%%;*}\n"
          "echo \"Submitted render array job $render (" + str(farm.chunks.size(), " tasks") +
          (dependency.empty() ? ")\"\n" : ", after job $simulation)\"\n");
  return text;
}

}  // namespace

std::string shell_quote(std::string_view text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

SlurmScripts make_slurm_scripts(const SlurmFarm& farm_in) {
  check_values(farm_in);
  SlurmFarm farm = farm_in;  // the scene name also goes into comments: keep it on one line
  std::replace_if(farm.scene_name.begin(), farm.scene_name.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  SlurmScripts scripts;
  if (!farm.simulate_command.empty()) scripts.simulate = simulate_script(farm);
  scripts.render = render_script(farm);
  scripts.submit = submit_script(farm);
  return scripts;
}

}  // namespace spume::farm
