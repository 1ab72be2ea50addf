// spume farm: render frame chunks on many machines sharing the output folder.
//   spume farm chunks SCENE --chunk N [--frames SPEC]   one frame spec per line (GNU parallel, scripts)
//   spume farm slurm SCENE --chunk N [--frames SPEC] [--partition P] [--submit]
//                                                      Slurm scripts: simulation job, then render array
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "cli_args.h"
#include "commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "farm/farm_plan.h"
#include "farm/slurm_script.h"
#include "pipeline/simulate_scene.h"
#include "render_stage.h"
#include "scene_args.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

constexpr const char* kUsage =
    "usage: spume farm chunks SCENE --chunk N [--frames SPEC] [scene options]\n"
    "         one frame spec per line, e.g. | parallel spume render SCENE --frames {}\n"
    "       spume farm slurm SCENE --chunk N [--frames SPEC] [--partition P] [--submit] [scene options]\n"
    "         writes OUT/<scene>/farm/{simulate.sbatch,render.sbatch,submit.sh}; --submit runs submit.sh\n";

std::vector<cli::OptionSpec> farm_options(bool slurm) {
  std::vector<cli::OptionSpec> options = scene_command_options();
  options.push_back({"frames", true, false, "SPEC      frames to render (default: all): 7, 0-99, 0-99:2, 1-3,5,10-20"});
  options.push_back({"chunk", true, false, "N         frames per chunk (required)"});
  if (slurm) {
    options.push_back({"partition", true, false, "P         Slurm partition of both jobs (default: the cluster's)"});
    options.push_back({"max-running", true, false, "N         at most N array tasks at once (--array=...%N)"});
    options.push_back(
        {"sbatch", true, true, "OPTION    one more #SBATCH line for both jobs, e.g. --sbatch=--time=2:00:00"});
    options.push_back({"submit", false, false, "          submit the jobs now (bash OUT/<scene>/farm/submit.sh)"});
  }
  return options;
}

struct Plan {
  SceneSetup setup;
  std::vector<std::string> chunks;
  int frames = 0;
};

// Loads the scene and splits its frames into chunks. Tasks never delete frames: each renders the
// frames of its chunk whose records do not match (render_stage.h).
Plan plan(const cli::ParsedArgs& args, const std::vector<cli::OptionSpec>& options, const std::string& command) {
  Plan p;
  p.setup = load_scene_setup(args, options, command);
  const auto chunk = args.value("chunk");
  if (!chunk) fail("spume ", command, ": --chunk N (frames per chunk) is required\n", cli::usage_lines(options));
  std::vector<int> frames = scene_frames(p.setup.sim);
  if (auto spec = args.value("frames")) frames = farm::select_frames(*spec, frames);
  p.frames = int(frames.size());
  p.chunks = farm::chunk_specs(frames, cli::parse_int(*chunk, "--chunk", 1, 1 << 30));
  return p;
}

int farm_chunks(const std::vector<std::string>& raw) {
  const auto options = farm_options(false);
  const cli::ParsedArgs args = cli::parse(raw, options, "farm chunks");
  for (const std::string& chunk : plan(args, options, "farm chunks").chunks) std::printf("%s\n", chunk.c_str());
  return 0;
}

// The scene options the jobs repeat, with paths made absolute (the jobs also run in this directory).
std::vector<std::string> scene_arguments(const cli::ParsedArgs& args, const SceneSetup& setup) {
  std::vector<std::string> argv;
  if (!args.positional.empty()) argv.push_back(fs::absolute(args.positional[0]).lexically_normal().string());
  for (const char* option : {"fluid", "radius", "fps", "threads"})
    if (auto value = args.value(option)) argv.insert(argv.end(), {str("--", option), *value});
  argv.insert(argv.end(), {"--out", fs::absolute(setup.out_root).lexically_normal().string()});
  for (const std::string& set : args.all("set")) argv.insert(argv.end(), {"--set", set});
  return argv;
}

bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "";
  for (size_t start = 0; start <= dirs.size();) {
    const size_t colon = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(start, colon - start)) / program;
    if (::access(candidate.c_str(), X_OK) == 0) return true;
    start = colon + 1;
  }
  return false;
}

void write_script(const fs::path& path, const std::string& text) {
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
  fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                  fs::perm_options::add);
  std::printf("Saved: %s\n", path.string().c_str());
}

int farm_slurm(const std::vector<std::string>& raw) {
  const auto options = farm_options(true);
  const cli::ParsedArgs args = cli::parse(raw, options, "farm slurm");
  const Plan p = plan(args, options, "farm slurm");
  const SceneSetup& setup = p.setup;

  farm::SlurmFarm farm;
  farm.scene_name = setup.sim.name;
  farm.chunks = p.chunks;
  farm.farm_dir = fs::absolute(setup.out_root / setup.sim.name / "farm").lexically_normal();
  farm.work_dir = fs::current_path();
  farm.partition = args.value("partition").value_or("");
  if (auto threads = args.value("threads")) farm.cpus_per_task = cli::parse_int(*threads, "--threads", 1, 1024);
  if (auto n = args.value("max-running")) farm.max_running = cli::parse_int(*n, "--max-running", 1, 1 << 20);
  farm.sbatch_options = args.all("sbatch");
  // The nodes run this very binary: the output folder and the build are on the shared file system.
  const std::string spume = fs::read_symlink("/proc/self/exe").string();
  const std::vector<std::string> scene = scene_arguments(args, setup);
  farm.render_command = {spume, "render"};
  farm.render_command.insert(farm.render_command.end(), scene.begin(), scene.end());
  SimulateOptions current;
  current.out_root = setup.out_root;
  const bool simulated = scene_simulation_is_current(setup.sim, current);
  if (!simulated) {
    farm.simulate_command = {spume, "simulate"};
    farm.simulate_command.insert(farm.simulate_command.end(), scene.begin(), scene.end());
  }

  const farm::SlurmScripts scripts = farm::make_slurm_scripts(farm);
  fs::remove(farm.farm_dir / "simulate.sbatch");  // a stale one would suggest a simulation job
  if (!scripts.simulate.empty()) write_script(farm.farm_dir / "simulate.sbatch", scripts.simulate);
  write_script(farm.farm_dir / "render.sbatch", scripts.render);
  const fs::path submit = farm.farm_dir / "submit.sh";
  write_script(submit, scripts.submit);
  if (!setup.quiet)
    std::fprintf(stderr, "farm %s: %d frames in %zu chunks; %s\n", setup.sim.name.c_str(), p.frames,
                 p.chunks.size(), simulated ? "the simulation caches are current: no simulation job"
                                            : "a simulation job runs first, the render array after it (afterok)");
  std::fflush(stdout);
  if (!args.has("submit")) {
    if (!setup.quiet) std::fprintf(stderr, "submit with: bash %s\n", farm::shell_quote(submit.string()).c_str());
    return 0;
  }
  if (!on_path("sbatch"))
    fail("--submit: sbatch is not on PATH (is Slurm installed here?); the scripts are written, submit them with "
         "`bash ", submit.string(), "` on a machine of the cluster");
  const int status = std::system(("bash " + farm::shell_quote(submit.string())).c_str());
  if (status != 0)
    fail("--submit: ", submit.string(), " failed (exit status ", WEXITSTATUS(status), "); see sbatch's message above");
  return 0;
}

}  // namespace

int command_farm(const std::vector<std::string>& args) {
  const std::vector<std::string> rest(args.begin() + (args.empty() ? 0 : 1), args.end());
  if (!args.empty() && args[0] == "chunks") return farm_chunks(rest);
  if (!args.empty() && args[0] == "slurm") return farm_slurm(rest);
  if (args.empty()) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  std::fprintf(stderr, "spume farm: unknown farm \"%s\"; allowed: chunks, slurm\n%s", args[0].c_str(), kUsage);
  return 2;
}

}  // namespace spume
