#pragma once
// OUT/<scene>/stats.csv: one row per diffuse frame (counts by type, emission, losses, milliseconds per
// simulator stage and for the cache's encoding and writing). A continued run keeps the earlier run's
// rows up to the frame it continues from; rows of an older column layout are not mixed with today's.
#include <filesystem>
#include <optional>
#include <string>

#include "sim/diffuse/simulator.h"

namespace spume {

class DiffuseStatsCsv {
 public:
  // `continued_from`: the frame a continued run starts after, whose earlier rows (up to it) are kept.
  DiffuseStatsCsv(std::filesystem::path path, std::optional<int> continued_from);
  void add(const FrameStats& stats, double time, double io_ms);
  void write() const;  // atomically, the whole file

 private:
  std::filesystem::path path_;
  std::string text_;
};

}  // namespace spume
