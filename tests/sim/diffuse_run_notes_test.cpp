// What the diffuse stage says about particles the domain deleted: spray that fell over a tank's rim
// to the ground beside it is summed in a note, never warned about; a frame that loses over 1% of its
// emission anywhere else is warned about, with the count of those alone.
#include <gtest/gtest.h>

#include "sim/core/messages.h"
#include "sim/stage/diffuse_run_notes.h"

namespace spume {
namespace {

class DiffuseRunNotesDomain : public ::testing::Test {
 protected:
  void SetUp() override { messages::reset(), messages::set_quiet(true); }
  void TearDown() override { messages::reset(); }

  static FrameStats frame(int index, uint64_t generated, uint64_t removed, uint64_t landed) {
    FrameStats s;
    s.frame = index, s.generated = generated, s.removed = removed, s.landed = landed;
    return s;
  }
};

TEST_F(DiffuseRunNotesDomain, SprayLandedBesideATankIsNoWarning) {
  SimScene scene;
  Progress progress("simulate test", 3, true);
  DiffuseRunNotes notes(scene, progress, 3, true);
  notes.simulated(frame(1, 1000, 300, 300), true, 2, true);  // 30% of the emission, all on the ground
  notes.simulated(frame(2, 1000, 12, 2), false, 3, true);    // 1.0% in the air: not over 1%
  EXPECT_TRUE(messages::warnings().empty());
}

TEST_F(DiffuseRunNotesDomain, ParticlesLostInTheAirAreWarnedWithTheirOwnCount) {
  SimScene scene;
  Progress progress("simulate test", 2, true);
  DiffuseRunNotes notes(scene, progress, 2, true);
  notes.simulated(frame(7, 1000, 40, 25), true, 8, true);  // 15 in the air: 1.5%
  const auto warnings = messages::warnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("frame 7 removed 15 diffuse particles outside the domain, 1.5% of the 1000 emitted"),
            std::string::npos)
      << warnings[0];
}

}  // namespace
}  // namespace spume
