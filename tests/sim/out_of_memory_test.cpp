// Running out of memory said as an Error (sim/core/out_of_memory.h), and the masses a run cannot weigh a
// particle with (sim/core/unusable_masses.h).
#include <gtest/gtest.h>

#include <new>
#include <string>

#include "sim/core/out_of_memory.h"
#include "sim/core/unusable_masses.h"
#include "tests/support/error_of.h"
#include "tests/support/text.h"

namespace spume {
namespace {

using testing::contains;

TEST(OutOfMemory, SizesAreSaidInTheUnitThatFits) {
  EXPECT_EQ(byte_size_text(0), "0 bytes");
  EXPECT_EQ(byte_size_text(1), "1 byte");
  EXPECT_EQ(byte_size_text(1023), "1023 bytes");
  EXPECT_EQ(byte_size_text(1024), "1.0 KiB");
  EXPECT_EQ(byte_size_text(1536), "1.5 KiB");
  EXPECT_EQ(byte_size_text(uint64_t(300) << 20), "300 MiB");
  EXPECT_EQ(byte_size_text(uint64_t(2) << 30), "2.0 GiB");
  EXPECT_EQ(byte_size_text(1'200'000'000), "1.1 GiB");  // 1.2e9 / 2^30 = 1.118
}

// A bad_alloc inside `allocating` becomes an Error naming what and how much; other errors pass as they are.
TEST(OutOfMemory, AllocatingNamesWhatAndHowMuch) {
  const std::string message = testing::error_of([] { allocating("reading f.ply", uint64_t(3) << 30, []() -> int { throw std::bad_alloc(); }); });
  EXPECT_EQ(message.rfind("out of memory reading f.ply (3.0 GiB)", 0), 0u) << message;
  EXPECT_EQ(testing::error_of([] { allocating("x", 1, [] { fail("f.ply: corrupt"); }); }), "f.ply: corrupt");
  EXPECT_EQ(allocating("x", 1, [] { return 7; }), 7);
}

// Without a size given, the size of the last allocation that failed is said, once.
TEST(OutOfMemory, TheLastFailedAllocationIsSaidWhenNoSizeIsGiven) {
  record_failed_allocation(uint64_t(5) << 20);
  const std::string first = out_of_memory_message("simulating");
  EXPECT_EQ(first.rfind("out of memory simulating (an allocation of 5.0 MiB failed)", 0), 0u) << first;
  const std::string second = out_of_memory_message("simulating");
  EXPECT_FALSE(contains(second, "an allocation of")) << second;
}

TEST(UnusableMasses, CountsAndRangesTheMassesThatAreNotPositive) {
  EXPECT_EQ(unusable_masses({}).count, 0u);
  EXPECT_EQ(unusable_masses({0.064f, 1.0f}).describe(2), "");
  const UnusableMasses u = unusable_masses({-1.0f, 0.064f, 0.0f, -1.0f});
  EXPECT_EQ(u.count, 3u);
  EXPECT_EQ(u.lo, -1.0f);
  EXPECT_EQ(u.hi, 0.0f);
  EXPECT_EQ(u.describe(4), "3 of 4 masses are not > 0 (-1 .. 0 kg)");
  EXPECT_EQ(unusable_masses({-1.0f, 2.0f}).describe(2), "1 of 2 masses is not > 0 (-1 kg)");
  EXPECT_FALSE(usable_mass(-1.0f));
  EXPECT_FALSE(usable_mass(0.0f));
  EXPECT_TRUE(usable_mass(1e-9f));
}

}  // namespace
}  // namespace spume
