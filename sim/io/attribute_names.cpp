#include "sim/io/attribute_names.h"

#include <array>
#include <cstdint>

namespace spume::io {
namespace {

// v, vel: Houdini; velocity: partio and SPlisHSPlasH; Velocity: ParaView; particles_velocity: Mantaflow.
constexpr std::array<std::string_view, 5> kVelocity = {"v", "vel", "velocity", "Velocity", "particles_velocity"};
// id: Houdini, partio, SPlisHSPlasH; ids, ID: VTK writers.
constexpr std::array<std::string_view, 3> kId = {"id", "ids", "ID"};
constexpr std::array<std::string_view, 1> kMass = {"mass"};

constexpr AttributeRole kRoles[] = {AttributeRole::Velocity, AttributeRole::Id, AttributeRole::Mass};

}  // namespace

std::span<const std::string_view> attribute_names(AttributeRole role) {
  switch (role) {
    case AttributeRole::Velocity: return kVelocity;
    case AttributeRole::Id: return kId;
    case AttributeRole::Mass: return kMass;
  }
  return {};
}

std::optional<AttributeRole> attribute_role(std::string_view name) {
  for (const AttributeRole role : kRoles)
    for (const std::string_view n : attribute_names(role))
      if (n == name) return role;
  return std::nullopt;
}

size_t attribute_preference(std::string_view name) {
  for (const AttributeRole role : kRoles) {
    const auto names = attribute_names(role);
    for (size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return i;
  }
  return SIZE_MAX;
}

const char* attribute_role_text(AttributeRole role) {
  switch (role) {
    case AttributeRole::Velocity: return "a velocity";
    case AttributeRole::Id: return "the particle id";
    case AttributeRole::Mass: return "the mass";
  }
  return "";
}

std::string attribute_names_text(AttributeRole role) {
  const auto names = attribute_names(role);
  std::string text;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i > 0) text += i + 1 == names.size() ? " or " : ", ";
    text += names[i];
  }
  return text;
}

std::string velocity_component(std::string_view name, bool underscore, int axis) {
  return std::string(name) + (underscore ? "_" : "") + "xyz"[axis];
}

}  // namespace spume::io
