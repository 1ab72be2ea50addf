#pragma once
// The names every particle reader (classic BGEO, Houdini's geometry, OpenVDB points, legacy VTK, VTK
// XML, PLY) accepts for each point attribute spume uses: the names SPlisHSPlasH, Houdini, Blender's
// Mantaflow and ParaView write. One table, so a format or an alias is added in one place. Where a file
// holds more than one name of an attribute, the first in the table's order is read.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace spume::io {

enum class AttributeRole { Velocity, Id, Mass };

// The names of `role`, in order of preference.
std::span<const std::string_view> attribute_names(AttributeRole role);

// The role a name is read as (exact, case included); nullopt for names spume does not use.
std::optional<AttributeRole> attribute_role(std::string_view name);

// Its place in its role's names (0 is preferred); for readers that meet the names in the file's order.
size_t attribute_preference(std::string_view name);

// "a velocity", "the particle id", "the mass": for messages.
const char* attribute_role_text(AttributeRole role);

// The names of `role` for messages: "v, vel, velocity, Velocity or particles_velocity".
std::string attribute_names_text(AttributeRole role);

// Formats that store a vector as three scalar properties (PLY): the velocity's components for one of
// its names, as `<name>x` or `<name>_x` spell them ("vx", "velocity_x").
std::string velocity_component(std::string_view name, bool underscore, int axis);

}  // namespace spume::io
