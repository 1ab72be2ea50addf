#pragma once
// One declaration per scene key: where it is in the JSON, its type and unit, its default (absolute,
// a multiple of the particle radius r, or carried to r by Froude similarity from r0 = 0.02 m), the
// range it may take, and one line of doc. The readers read through these (core/params.h), the range
// checks come from them, `spume keys` prints them and the tables of sim/keys/KEYS.md come from them
// (tests/render/key_tables_test.cpp fails when the two differ). No default or range is written elsewhere.
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace spume {

enum class KeyType {
  Number,   // a JSON number, stored as float unless the doc says otherwise
  Integer,  // a whole number
  Boolean,
  Text,     // a string
  Choice,   // one of `choices`
  Vec3,     // [x, y, z]
  Colour,   // linear RGB [r, g, b]
  Range,    // [min, max] with min < max
  Size,     // [width, height], whole numbers
  Object,   // {...}: its keys are declared under it
  List,     // [...] of objects: its entries' keys are declared as path[].key
};

// How a numeric default follows the particle radius r (r0 = 0.02 m, s = r / r0).
enum class Scaling {
  Absolute,  // as written
  Radius,    // value x r
  Velocity,  // Froude: x sqrt(s)
  Time,      // Froude: x sqrt(s)
  Rate,      // Froude: / sqrt(s)
  Energy,    // Froude: x (particle mass / reference mass) x s
};

enum class Bound { Unset, Closed, Open };

inline constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();
// r0, m: the float 0.02f spume has always scaled from (as a double 0.02 the derived defaults move by
// one float ulp, and every cache with them).
inline constexpr double kDefaultsReferenceRadius = double(0.02f);

struct KeySpec {
  const char* path;          // "diffuse.k_ta", "solids[].motion.amplitude"
  KeyType type = KeyType::Number;
  const char* unit = "";     // SI: "m", "1/s", "m/s^2"; "" dimensionless
  std::array<double, 3> value{kNoValue, kNoValue, kNoValue};  // scalar: [0]; Range: [0], [1]; Vec3: all
  Scaling scaling = Scaling::Absolute;
  double lo = kNoValue, hi = kNoValue;  // allowed values (each component of a Vec3 or Range)
  Bound lo_bound = Bound::Unset, hi_bound = Bound::Unset;
  const char* choices = "";  // Choice: "exact|euler_cromer" (the default first); Text: the default
  const char* default_text = "";  // when there is no numeric default: "required", "the file's stem", ...
  const char* doc = "";

  std::string name() const;  // the last component: "k_ta"
  bool has_value() const { return !std::isnan(value[0]); }
};

// The default as a reader uses it: value[i] carried to radius r (`mass_ratio` = the particle's mass
// over a water particle of radius r0, for Scaling::Energy).
double scaled_default(const KeySpec& k, int i, double r, double mass_ratio = 1.0);

// The declared default value[i] as a float, for struct defaults (the readers scale and check it).
constexpr float declared_float(const KeySpec& k, int i = 0) { return float(k.value[size_t(i)]); }

// The declared default of a Vec3 or Colour key as a 3-vector V (Vec3f), for struct defaults; a
// template so the declarations need no vector type.
template <class V>
V declared_vec3(const KeySpec& k) {
  return V(float(k.value[0]), float(k.value[1]), float(k.value[2]));
}

// For people: the default ("300 at r0, / sqrt(r/r0)", "0.3 r", "[2, 8]", "required"), the allowed
// range ("[0, 1e7]", "> 0", "exact, euler_cromer").
std::string default_description(const KeySpec& k);
std::string range_description(const KeySpec& k);

// "" when v is within the declared range (and finite), else "value V is out of range; allowed R".
std::string out_of_range(const KeySpec& k, double v);

}  // namespace spume
