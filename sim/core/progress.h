#pragma once
// Progress of a long run on stderr: "simulate: frame 12/240  3.1 frames/s  eta 1m13s". On a terminal
// one line is rewritten in place; otherwise (farms, logs) each update (one per frame) is its own line
// "LABEL: frame DONE/TOTAL  R frames/s  eta T  NOTE", so other programs can parse it. Quiet
// reporters print nothing.
#include <chrono>
#include <string>

namespace spume {

class Progress {
 public:
  Progress(std::string label, size_t total, bool quiet);
  ~Progress();
  void update(size_t done, const std::string& note = "");  // `done` items of `total` are finished
  void finish(const std::string& note = "");
  // A line that must be seen even between progress updates (warnings), unless quiet.
  void message(const std::string& line);

 private:
  std::string label_;
  size_t total_;
  bool quiet_, terminal_, open_line_ = false;
  std::chrono::steady_clock::time_point start_;
};

std::string format_duration(double seconds);  // "1h02m", "3m05s", "12.4s"

}  // namespace spume
