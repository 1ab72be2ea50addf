#pragma once
// The scripts of a Slurm farm render, as text (`spume farm slurm` writes them to OUT/<scene>/farm/):
//   simulate.sbatch  one job: `spume simulate` (left out when the caches are current)
//   render.sbatch    an array job: task i runs `spume render --frames CHUNK_i`
//   submit.sh        submits both, the array with --dependency=afterok on the simulation job
//                    (cancelled if that fails), and prints the job ids. Running it again
//                    resumes (frames on disk are skipped).
// Paths and arguments are single-quoted for the shell; values that go into #SBATCH lines (which
// sbatch reads without a shell) are checked instead.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace spume::farm {

struct SlurmFarm {
  std::string scene_name;                      // for job names
  std::vector<std::string> simulate_command;   // argv; empty: no simulation job
  std::vector<std::string> render_command;     // argv without --frames
  std::vector<std::string> chunks;             // frame specs, one array task each
  std::filesystem::path farm_dir;              // absolute: the scripts and logs/
  std::filesystem::path work_dir;              // absolute: the jobs' working directory
  std::string partition;                       // empty: the cluster's default
  int cpus_per_task = 0;                       // 0: the cluster's default
  int max_running = 0;                         // array tasks running at once; 0: no limit
  std::vector<std::string> sbatch_options;     // more #SBATCH lines, e.g. "--time=1:00:00"
};

struct SlurmScripts {
  std::string simulate;  // empty when there is no simulation job
  std::string render;
  std::string submit;
};

// Throws Error naming the option (--partition, --sbatch, ...) when a value cannot go into a script.
SlurmScripts make_slurm_scripts(const SlurmFarm& farm);

// `text` as one shell word: single-quoted, with embedded single quotes as '\''.
std::string shell_quote(std::string_view text);

}  // namespace spume::farm
