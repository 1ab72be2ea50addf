#include "sim/core/progress.h"

#include <cstdio>
#include <unistd.h>

#include "sim/core/error.h"
#include "sim/core/messages.h"

namespace spume {

std::string format_duration(double seconds) {
  char buffer[32];
  if (seconds < 60) std::snprintf(buffer, sizeof buffer, "%.1fs", seconds);
  else if (seconds < 3600) std::snprintf(buffer, sizeof buffer, "%dm%02ds", int(seconds) / 60, int(seconds) % 60);
  else std::snprintf(buffer, sizeof buffer, "%dh%02dm", int(seconds) / 3600, (int(seconds) / 60) % 60);
  return buffer;
}

Progress::Progress(std::string label, size_t total, bool quiet, double partial_interval)
    : label_(std::move(label)), total_(total), quiet_(quiet), terminal_(::isatty(2) == 1),
      partial_interval_(partial_interval >= 0.0 ? partial_interval
                        : terminal_        ? kPartialIntervalTerminal
                                           : kPartialIntervalLog) {}

Progress::~Progress() { messages::end_progress_line(); }

void Progress::update(size_t done, const std::string& note) {
  if (quiet_) return;
  // Not throttled: off a terminal (farm logs, pipes) every frame gets its own line, so a log says
  // which frame a job reached.
  const double elapsed = since_start_.seconds();
  const double rate = elapsed > 0 ? double(done) / elapsed : 0.0;
  std::string line = str(label_, ": frame ", done, "/", total_);
  if (done > 0) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "  %.2f frames/s", rate);
    line += buffer;
    line += "  eta " + format_duration(rate > 0 ? double(total_ - done) / rate : 0.0);
  }
  if (!note.empty()) line += "  " + note;
  print(line);
}

bool Progress::partial_due() const {
  if (quiet_) return false;
  return since_line_.seconds() >= partial_interval_;
}

void Progress::partial(size_t done, const std::string& note) {
  if (!partial_due()) return;
  print(str(label_, ": frame ", done + 1, "/", total_, " in progress  ", note));
}

void Progress::print(const std::string& line) {
  messages::progress_line(line, terminal_);
  since_line_.restart();
}

void Progress::finish(const std::string& note) {
  if (quiet_) return;
  const double elapsed = since_start_.seconds();
  messages::end_progress_line();
  messages::progress_line(str(label_, ": ", total_, " frames in ", format_duration(elapsed), note.empty() ? "" : "  ", note),
                          false);
}

void Progress::note(const std::string& line) {
  if (quiet_) return;
  messages::note(line);
  since_line_.restart();
}

}  // namespace spume
