#include <gtest/gtest.h>

#include "sim/scene/scene_name.h"

using namespace spume;

TEST(SceneName, UsableNamesAreLettersDigitsAndUnderscoreDashDot) {
  for (const char* name : {"wave", "dam_break-2", "v1.5", "A"}) EXPECT_TRUE(is_usable_scene_name(name)) << name;
  for (const char* name : {"", ".hidden", "my fluid", "a/b", "x\ty", "caf\xc3\xa9", "$F"})
    EXPECT_FALSE(is_usable_scene_name(name)) << name;
}

TEST(SceneName, UnusableTextIsMadeUsable) {
  EXPECT_EQ(usable_scene_name("my fluid "), "my_fluid");         // a pattern's stem before %04d
  EXPECT_EQ(usable_scene_name("  two   spaces"), "two_spaces");  // a run of others is one '_'
  EXPECT_EQ(usable_scene_name(".hidden-"), "hidden");
  EXPECT_EQ(usable_scene_name("a/b:c"), "a_b_c");
  EXPECT_EQ(usable_scene_name("caf\xc3\xa9 au lait"), "caf_au_lait");
  EXPECT_EQ(usable_scene_name("wave"), "wave");
  EXPECT_EQ(usable_scene_name(" ._- "), "");
  for (const char* text : {"my fluid ", "  two   spaces", ".hidden-", "a/b:c"})
    EXPECT_TRUE(is_usable_scene_name(usable_scene_name(text))) << text;
}
