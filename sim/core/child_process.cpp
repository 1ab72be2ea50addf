#include "sim/core/child_process.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>

extern char** environ;

namespace spume {
namespace {

// This process's environment with `changes` ("NAME=value") added or put in place of the same names.
std::vector<std::string> environment_with(const std::vector<std::string>& changes) {
  std::vector<std::string> entries;
  auto name_of = [](const std::string& entry) { return entry.substr(0, entry.find('=')); };
  for (char** e = environ; e && *e; ++e) {
    const std::string entry = *e;
    bool replaced = false;
    for (const std::string& change : changes) replaced |= name_of(change) == name_of(entry);
    if (!replaced) entries.push_back(entry);
  }
  entries.insert(entries.end(), changes.begin(), changes.end());
  return entries;
}

std::vector<char*> pointers_to(std::vector<std::string>& strings) {
  std::vector<char*> pointers;
  for (std::string& s : strings) pointers.push_back(s.data());
  pointers.push_back(nullptr);
  return pointers;
}

}  // namespace

ProcessResult run_process(const std::vector<std::string>& args, const std::vector<std::string>& environment) {
  ProcessResult r;
  // Output goes to an anonymous temporary file, not a pipe: no deadlock however much is written.
  std::FILE* capture = std::tmpfile();
  if (!capture) {
    r.start_error = std::strerror(errno);
    return r;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fileno(capture), STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, fileno(capture), STDERR_FILENO);
  std::vector<std::string> arg_copies = args;
  std::vector<std::string> env_entries = environment_with(environment);
  const std::vector<char*> argv = pointers_to(arg_copies), envp = pointers_to(env_entries);
  pid_t pid = 0;
  const int error = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) {
    r.start_error = std::strerror(error);
    std::fclose(capture);
    return r;
  }
  r.started = true;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  // 127: the child could not exec (older glibc reports it this way instead of through posix_spawnp).
  if (r.exit_code == 127) r.started = false, r.start_error = "could not be executed";
  std::rewind(capture);
  char buffer[4096];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, capture)) > 0) r.output.append(buffer, n);
  std::fclose(capture);
  return r;
}

}  // namespace spume
