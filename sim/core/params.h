#pragma once
// Reading a JSON scene into typed values. Every lookup is recorded, so that after all modules have
// read their keys, any key nobody asked for is reported as an error with the closest known key
// (a typo must never pass silently). Errors name the source file and the key path, e.g.
// "wave.json: /diffuse/tau_ta: min 20 must be below max 5".
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/keys/key_spec.h"
#include "sim/core/vec.h"

namespace spume {

using Json = nlohmann::json;

// Shared by all readers of one document.
struct ParamDocument {
  std::string source;            // file name used in messages
  Json root;
  std::set<std::string> asked;   // every key path looked up, present or not
  Json used;                     // every value read, at its key path: as written, or the default taken
};

class ParamReader {
 public:
  // Reads the object at `path` ("" for the root) of the document.
  ParamReader(std::shared_ptr<ParamDocument> doc, std::string path);

  static ParamReader from_json(Json root, std::string source);

  bool has(const std::string& key) const;
  std::string path_of(const std::string& key) const { return path_ + "/" + key; }
  const std::string& source() const { return doc_->source; }

  // Typed getters: default when absent; an error naming the key for wrong types or ranges.
  double number(const std::string& key, double fallback) const;
  long integer_in(const std::string& key, long fallback, long lo, long hi) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string text(const std::string& key, const std::string& fallback) const;
  std::optional<std::string> optional_text(const std::string& key) const;
  std::string choice(const std::string& key, const std::string& fallback,
                     const std::vector<std::string>& allowed) const;
  Vec3f vec3(const std::string& key, const Vec3f& fallback) const;
  std::optional<Vec3f> optional_vec3(const std::string& key) const;
  // [min, max] with min < max (MODEL.md §8.1: equal thresholds would divide by zero).
  std::pair<double, double> range(const std::string& key, std::pair<double, double> fallback) const;

  // Declared keys (keys/key_spec.h): the key is the declaration's last path component (which must be
  // where this reader stands: a mismatch is a bug, thrown as std::logic_error); the default is the
  // declared one, carried to the particle radius `r` for scaled keys (`mass_ratio`: Scaling::Energy);
  // the value must lie in the declared range; a key without a default is required.
  double number(const KeySpec& k, double r = 0.0, double mass_ratio = 1.0) const;
  long integer(const KeySpec& k) const;
  bool boolean(const KeySpec& k) const;
  std::string choice(const KeySpec& k) const;
  Vec3f vec3(const KeySpec& k) const;
  std::optional<Vec3f> optional_vec3(const KeySpec& k) const;  // absent: nullopt (range checked if present)
  std::pair<double, double> range(const KeySpec& k, double r = 0.0, double mass_ratio = 1.0) const;

  ParamReader child(const std::string& key) const;           // {} when absent
  std::vector<ParamReader> array_of_objects(const std::string& key) const;

  // The JSON under `key` as written (null when absent), without recording a lookup: for fingerprints
  // of what produced a cache, never for reading values.
  Json raw(const std::string& key) const;

  // The JSON under `key` with every key read so far at the value the run uses: as written, or the
  // default taken when absent. Records of what made an output compare these, so a key written at
  // its default equals the key left out (`--set diffuse.drag=0.5` is the default drag). Keys written
  // but not read as values stay as written. Null when nothing is there.
  Json effective(const std::string& key) const;

  // Fails with the message prefixed by the source file and this key's path; when `key` is absent, a
  // present unknown key a typo away is suggested ("radus" for a missing "radius").
  [[noreturn]] void fail_at(const std::string& key, const std::string& message) const;

  // This reader's place as a declaration path: "/solids/0/motion" -> "solids[].motion".
  std::string declared_path() const;

  // After every module has read its keys: throws naming every key nobody asked for, with suggestions.
  void reject_unknown_keys() const;

 private:
  const Json* find(const std::string& key) const;  // records the lookup
  // A finite number that fits a float, or nullopt when absent (number() and the declared getters).
  std::optional<double> optional_number(const std::string& key) const;
  // Records the value used for `key` (doc_->used); returns it.
  template <typename T>
  T note(const std::string& key, T value) const;
  // The declaration's key name, checked against this reader's place.
  std::string declared_key(const KeySpec& k) const;
  void check_in_range(const KeySpec& k, const std::string& key, double v) const;
  std::string near_miss_hint(const std::string& key) const;
  const Json& object() const;

  std::shared_ptr<ParamDocument> doc_;
  std::string path_;
};

// Apply a command-line override "a.b.c=value" to a JSON document: the value is parsed as JSON when
// it parses (numbers, booleans, arrays), else taken as a string. Intermediate objects are created.
void apply_override(Json& root, const std::string& assignment);

// Parses JSON text (comments allowed), throwing Error "source:line: not valid JSON: ..." for bad
// syntax and "source: JSON value out of range" for what the parser cannot hold (numbers like 1e400).
Json parse_json_text(const std::string& text, const std::string& source);

// Levenshtein distance, for "did you mean" suggestions.
size_t edit_distance(const std::string& a, const std::string& b);

}  // namespace spume
