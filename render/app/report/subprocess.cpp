#include "render/app/report/subprocess.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>

extern char** environ;

namespace spume::report {

ProcessResult run_process(const std::vector<std::string>& args) {
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
  std::vector<std::string> copies = args;
  std::vector<char*> argv;
  for (auto& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int error = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
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
  // 127: the child could not exec (older glibc reports it this way instead of through posix_spawnp).
  if (r.exit_code == 127) r.started = false, r.start_error = "could not be executed";
  std::rewind(capture);
  char buffer[4096];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, capture)) > 0) r.output.append(buffer, n);
  std::fclose(capture);
  return r;
}

}  // namespace spume::report
