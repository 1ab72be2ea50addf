#pragma once
// Progress of a long run on stderr: "simulate: frame 12/240  3.1 frames/s  eta 1m13s". On a terminal
// one line is rewritten in place; otherwise (farms, logs) each update (one per frame) is its own line
// "LABEL: frame DONE/TOTAL  R frames/s  eta T  NOTE", so other programs can parse it. Quiet
// reporters print nothing; nor does any under --quiet (core/messages.h).
//
// Items that take minutes (a frame of a big fluid) report from inside with `partial`:
// "LABEL: frame DONE+1/TOTAL in progress  NOTE", at most once a second on a terminal and once every
// 10 s otherwise (so a farm log grows by a line per 10 s, not per solver step).
#include <string>

#include "sim/core/stopwatch.h"

namespace spume {

class Progress {
 public:
  // `partial_interval` (s): the least time between lines of `partial`; negative: 1 s on a terminal,
  // 10 s otherwise.
  Progress(std::string label, size_t total, bool quiet, double partial_interval = -1.0);
  ~Progress();
  void update(size_t done, const std::string& note = "");  // `done` items of `total` are finished
  // Item done + 1 is under way; `note` says how far. Cheap when throttled: call it as often as you like.
  void partial(size_t done, const std::string& note);
  // Whether partial(...) would print now (build an expensive note only then).
  bool partial_due() const;
  void finish(const std::string& note = "");
  // A routine line between progress updates, unless quiet (messages::note). Warnings go to
  // messages::warning, which no quiet silences.
  void note(const std::string& line);

 private:
  std::string label_;
  size_t total_;
  bool quiet_, terminal_;
  double partial_interval_;
  Stopwatch since_start_, since_line_;
  void print(const std::string& line);
};

// Minimum seconds between `partial` lines: on a terminal, and in logs and pipes.
constexpr double kPartialIntervalTerminal = 1.0;
constexpr double kPartialIntervalLog = 10.0;

std::string format_duration(double seconds);  // "1h02m", "3m05s", "12.4s"

}  // namespace spume
