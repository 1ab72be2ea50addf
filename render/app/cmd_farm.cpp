// spume farm chunks and spume farm slurm: render frame chunks on many machines sharing the output
// folder, by GNU parallel or scripts (one frame spec per line), or by a Slurm array job after a
// simulation job.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "render/app/cli/cli_args.h"
#include "render/app/commands.h"
#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "render/app/farm/farm_plan.h"
#include "render/app/farm/slurm_script.h"
#include "sim/stage/simulate_scene.h"
#include "render/stage/render_stage.h"
#include "render/app/scene/scene_args.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

std::vector<cli::OptionSpec> farm_options(bool slurm) {
  std::vector<cli::OptionSpec> options = scene_command_options();
  options.push_back({"frames", "SPEC", "frames to render (default: all): 7, 0-99, 0-99:2, 1-3,5,10-20"});
  options.push_back({"chunk", "N", "frames per chunk (required)"});
  if (slurm) {
    options.push_back({"partition", "P", "Slurm partition of both jobs (default: the cluster's)"});
    options.push_back({"max-running", "N", "at most N array tasks at once (--array=...%N)"});
    options.push_back({"sbatch", "OPTION", "one more #SBATCH line for both jobs, e.g. --sbatch=--time=2:00:00", true});
    options.push_back({"submit", "", "submit the jobs now (bash OUT/<scene>/farm/submit.sh)"});
  }
  return options;
}

struct Plan {
  SceneSetup setup;
  std::vector<std::string> chunks;
  int frames = 0;
};

// Loads the scene and splits its frames into chunks. Tasks never delete frames: each renders the
// frames of its chunk whose records do not match (stage/render_stage.h).
Plan plan(const cli::ParsedArgs& args) {
  // The command line is checked whole before the scene is read.
  const auto chunk = args.value("chunk");
  if (!chunk) cli::usage_fail("--chunk N (frames per chunk) is required");
  const int chunk_size = cli::parse_int(*chunk, "--chunk", 1, 1 << 30);
  if (auto spec = args.value("frames")) cli::check_frame_spec(*spec, "--frames");
  Plan p;
  p.setup = load_scene_setup(args);
  std::vector<int> frames = scene_frames(p.setup.sim);
  if (auto spec = args.value("frames")) frames = farm::select_frames(*spec, frames);
  p.frames = int(frames.size());
  p.chunks = farm::chunk_specs(frames, chunk_size);
  return p;
}

int farm_chunks(const cli::ParsedArgs& args) {
  for (const std::string& chunk : plan(args).chunks) std::printf("%s\n", chunk.c_str());
  return 0;
}

// The scene options the jobs repeat, with paths made absolute (the jobs also run in this directory).
std::vector<std::string> scene_arguments(const cli::ParsedArgs& args, const SceneSetup& setup) {
  std::vector<std::string> argv;
  if (!args.positional.empty()) argv.push_back(fs::absolute(args.positional[0]).lexically_normal().string());
  for (const char* option : {"fluid", "radius", "fps", "tank", "threads"})
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

int farm_slurm(const cli::ParsedArgs& args) {
  std::optional<int> max_running;
  if (auto n = args.value("max-running")) max_running = cli::parse_int(*n, "--max-running", 1, 1 << 20);
  const Plan p = plan(args);
  const SceneSetup& setup = p.setup;

  farm::SlurmFarm farm;
  farm.scene_name = setup.sim.name;
  farm.chunks = p.chunks;
  farm.farm_dir = fs::absolute(setup.out_root / setup.sim.name / "farm").lexically_normal();
  farm.work_dir = fs::current_path();
  farm.partition = args.value("partition").value_or("");
  if (auto threads = args.value("threads")) farm.cpus_per_task = cli::parse_int(*threads, "--threads", 1, 1024);
  if (max_running) farm.max_running = *max_running;
  farm.sbatch_options = args.all("sbatch");
  // The nodes run this very binary: the output folder and the build are on the shared file system.
  const std::string spume = fs::read_symlink("/proc/self/exe").string();
  const std::vector<std::string> scene = scene_arguments(args, setup);
  farm.render_command = {spume, "render"};
  farm.render_command.insert(farm.render_command.end(), scene.begin(), scene.end());
  DiffuseStageOptions current;
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

Command cmd_farm_chunks() {
  cli::CommandSpec spec;
  spec.name = "farm chunks";
  spec.forms = scene_command_forms("--chunk N");
  spec.summary = "the render's frames in chunks, one frame spec per line, for GNU parallel or scripts";
  spec.options = farm_options(false);
  spec.notes = {"example: spume farm chunks SCENE.json --chunk 10 | parallel spume render SCENE.json --frames {}"};
  return {spec, farm_chunks};
}

Command cmd_farm_slurm() {
  cli::CommandSpec spec;
  spec.name = "farm slurm";
  spec.forms = scene_command_forms("--chunk N");
  spec.summary = "a Slurm array job rendering the chunks, after a simulation job if needed";
  spec.notes = {"writes OUT/<scene>/farm/{simulate.sbatch,render.sbatch,submit.sh}; --submit runs submit.sh"};
  spec.options = farm_options(true);
  return {spec, farm_slurm};
}

}  // namespace spume
