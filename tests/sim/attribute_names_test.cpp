// The one table of attribute names (io/attribute_names.h): the names the tools write, each read as
// one attribute only. Each reader's own test reads every name of it (io_*_test.cpp).
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "sim/io/attribute_names.h"

using namespace spume::io;

namespace {

std::vector<std::string> names_of(AttributeRole role) {
  std::vector<std::string> out;
  for (const std::string_view n : attribute_names(role)) out.emplace_back(n);
  return out;
}

}  // namespace

// What the tools write, as documented in README.md's format table: Houdini v (and vel), partio and
// SPlisHSPlasH velocity and id, ParaView Velocity and ID, Mantaflow particles_velocity.
TEST(AttributeNames, HoldTheNamesTheToolsWriteInOrderOfPreference) {
  EXPECT_EQ(names_of(AttributeRole::Velocity),
            (std::vector<std::string>{"v", "vel", "velocity", "Velocity", "particles_velocity"}));
  EXPECT_EQ(names_of(AttributeRole::Id), (std::vector<std::string>{"id", "ids", "ID"}));
  EXPECT_EQ(names_of(AttributeRole::Mass), (std::vector<std::string>{"mass"}));
  EXPECT_EQ(attribute_names_text(AttributeRole::Id), "id, ids or ID");
}

TEST(AttributeNames, EachNameBelongsToOneRoleAndKnowsItsPlace) {
  std::set<std::string> seen;
  for (const AttributeRole role : {AttributeRole::Velocity, AttributeRole::Id, AttributeRole::Mass}) {
    const auto names = attribute_names(role);
    for (size_t i = 0; i < names.size(); ++i) {
      EXPECT_TRUE(seen.insert(std::string(names[i])).second) << names[i];
      EXPECT_EQ(attribute_role(names[i]), role) << names[i];
      EXPECT_EQ(attribute_preference(names[i]), i) << names[i];
    }
  }
  EXPECT_FALSE(attribute_role("P").has_value());
  EXPECT_FALSE(attribute_role("V").has_value());  // exact names: case counts
}

TEST(AttributeNames, VelocityComponentsAreSpeltBothWays) {
  EXPECT_EQ(velocity_component("v", false, 0), "vx");
  EXPECT_EQ(velocity_component("velocity", true, 2), "velocity_z");
}
