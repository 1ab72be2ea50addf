// MemoryRoom: a count is refused when its growth beyond what the stage holds needs more than is
// available.
#include <gtest/gtest.h>

#include "sim/core/error.h"
#include "sim/core/memory_room.h"

namespace spume {
namespace {

std::string refusal(MemoryRoom& room, uint64_t count) {
  try {
    room.check(count, "frame 7");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

MemoryRoom::Available fixed(double bytes) {
  return [bytes] { return std::optional<double>(bytes); };
}

TEST(MemoryRoom, OnlyTheGrowthBeyondWhatIsHeldMustFit) {
  // 100 bytes a particle, 1e9 bytes available: 5M fits (5e8), 12M fits after it (7e8 more), 25M does
  // not (1.3e9 more), and after that refusal 20M still fits (8e8 more than the 12M held).
  int asked = 0;
  MemoryRoom room("the stage", "particles", 100.0, "do less", [&] {
    ++asked;
    return std::optional<double>(1e9);
  });
  EXPECT_EQ(refusal(room, 5'000'000), "");
  EXPECT_EQ(refusal(room, 12'000'000), "");
  const std::string message = refusal(room, 25'000'000);
  EXPECT_NE(message.find("frame 7: the stage cannot hold 25.0M particles"), std::string::npos) << message;
  EXPECT_NE(message.find("they need 2.3 GiB, 1.2 GiB more than it holds"), std::string::npos) << message;
  EXPECT_NE(message.find("and 954 MiB is available"), std::string::npos) << message;  // 1e9 bytes
  EXPECT_NE(message.find("do less"), std::string::npos) << message;
  EXPECT_EQ(refusal(room, 20'000'000), "");
  // Counts within the largest that passed are not checked again.
  const int before = asked;
  EXPECT_EQ(refusal(room, 3'000'000), "");
  EXPECT_EQ(asked, before);
}

TEST(MemoryRoom, WhatTheStageAlreadyHoldsCounts) {
  // A restart: 3.7e8 bytes of particles already held, 2e8 available; 5M particles at 100 bytes (5e8)
  // need 1.3e8 more and fit, where with nothing held they would not.
  MemoryRoom restarted("the stage", "particles", 100.0, "", fixed(2e8)), fresh("the stage", "particles", 100.0, "", fixed(2e8));
  restarted.holding(3.7e8);
  EXPECT_EQ(refusal(restarted, 5'000'000), "");
  EXPECT_NE(refusal(fresh, 5'000'000), "");
  // Told twice (particles replaced), it holds the larger, not the sum: 8e8 would need 4.3e8 more.
  MemoryRoom replaced("the stage", "particles", 100.0, "", fixed(2e8));
  replaced.holding(3.7e8);
  replaced.holding(3.7e8);
  EXPECT_NE(refusal(replaced, 8'000'000), "");
}

TEST(MemoryRoom, UnknownAvailableMemoryRefusesNothing) {
  MemoryRoom room("the stage", "particles", 1e6, "", [] { return std::optional<double>(); });
  EXPECT_EQ(refusal(room, 1'000'000'000), "");
}

TEST(MemoryRoom, ThisMachineReportsItsMemory) {
  const std::optional<double> available = available_memory_bytes();
  ASSERT_TRUE(available.has_value());  // Linux: /proc/meminfo
  EXPECT_GT(*available, 1e6);
}

}  // namespace
}  // namespace spume
