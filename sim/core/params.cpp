#include "sim/core/params.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sim/core/error.h"

namespace spume {

ParamReader::ParamReader(std::shared_ptr<ParamDocument> doc, std::string path)
    : doc_(std::move(doc)), path_(std::move(path)) {}

ParamReader ParamReader::from_json(Json root, std::string source) {
  auto doc = std::make_shared<ParamDocument>();
  doc->root = std::move(root);
  doc->source = std::move(source);
  if (!doc->root.is_object()) fail(doc->source, ": the scene must be a JSON object, found ", doc->root.type_name());
  return ParamReader(doc, "");
}

const Json& ParamReader::object() const {
  static const Json empty = Json::object();
  if (path_.empty()) return doc_->root;
  const Json::json_pointer pointer(path_);
  if (!doc_->root.contains(pointer)) return empty;
  const Json& node = doc_->root.at(pointer);
  return node.is_object() ? node : empty;
}

const Json* ParamReader::find(const std::string& key) const {
  doc_->asked.insert(path_of(key));
  const Json& obj = object();
  auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

Json ParamReader::raw(const std::string& key) const {
  const Json& obj = object();
  auto it = obj.find(key);
  return it == obj.end() ? Json() : *it;
}

bool ParamReader::has(const std::string& key) const { return find(key) != nullptr; }

namespace {

Json used_json(double v) { return v; }
Json used_json(long v) { return v; }
Json used_json(bool v) { return v; }
Json used_json(const std::string& v) { return v; }
Json used_json(const Vec3f& v) { return Json::array({v.x(), v.y(), v.z()}); }
Json used_json(const std::pair<double, double>& v) { return Json::array({v.first, v.second}); }

// `used` laid over `written`: objects key by key, arrays element by element, values replaced; so a
// part written but not read as a value (an object only tested for presence) stays as written.
void lay_over(Json& written, const Json& used) {
  if (written.is_object() && used.is_object()) {
    for (const auto& [key, value] : used.items()) lay_over(written[key], value);
  } else if (written.is_array() && used.is_array()) {
    for (size_t i = 0; i < used.size(); ++i) {
      if (i < written.size()) lay_over(written[i], used[i]);
      else written.push_back(used[i]);
    }
  } else if (!used.is_null()) {
    written = used;
  }
}

}  // namespace

template <typename T>
T ParamReader::note(const std::string& key, T value) const {
  try {
    doc_->used[Json::json_pointer(path_of(key))] = used_json(value);
  } catch (const Json::exception&) {
    // A key read both as a value and as an object: its record stays as written (effective()).
  }
  return value;
}

Json ParamReader::effective(const std::string& key) const {
  Json out = raw(key);
  const Json::json_pointer pointer(path_of(key));
  if (doc_->used.contains(pointer)) lay_over(out, doc_->used.at(pointer));
  return out;
}

// For a key that is absent (usually: required and missing), the present key of the same object that
// looks like a typo of it: nobody asked for it, and it is not a key asked for anywhere else either
// (so "max" is never offered for a missing "min"). One edit per three letters at most.
std::string ParamReader::near_miss_hint(const std::string& key) const {
  std::set<std::string> known_names;
  for (const auto& asked : doc_->asked) known_names.insert(asked.substr(asked.rfind('/') + 1));
  std::string best;
  size_t best_distance = std::max<size_t>(1, key.size() / 3) + 1;
  const Json& obj = object();
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    if (doc_->asked.count(path_of(it.key())) || known_names.count(it.key())) continue;
    if (const size_t d = edit_distance(key, it.key()); d < best_distance) best_distance = d, best = it.key();
  }
  return best.empty() ? "" : str(" (did you mean \"", best, "\"? it is not a known key)");
}

void ParamReader::fail_at(const std::string& key, const std::string& message) const {
  const bool absent = !object().contains(key);
  fail(doc_->source, ": ", path_of(key), ": ", message, absent ? near_miss_hint(key) : std::string());
}

std::optional<double> ParamReader::optional_number(const std::string& key) const {
  const Json* v = find(key);
  if (!v) return std::nullopt;
  if (!v->is_number()) fail_at(key, str("expected a number, found ", v->dump()));
  const double d = v->get<double>();
  if (!std::isfinite(d)) fail_at(key, str("expected a finite number, found ", d));
  // Numbers are stored as 32-bit floats in most places (positions, rates, thresholds): one beyond
  // that range would become infinity there and silently break the run.
  if (std::abs(d) > double(std::numeric_limits<float>::max()))
    fail_at(key, str("value ", d, " is too large: every number must fit a 32-bit float (at most about 3.4e38)"));
  return note(key, d);
}

double ParamReader::number(const std::string& key, double fallback) const {
  if (const std::optional<double> v = optional_number(key)) return *v;
  return note(key, fallback);
}

long ParamReader::integer_in(const std::string& key, long fallback, long lo, long hi) const {
  const Json* v = find(key);
  if (!v) return note(key, fallback);
  if (!v->is_number_integer()) fail_at(key, str("expected a whole number, found ", v->dump()));
  const long i = v->get<long>();
  if (i < lo || i > hi) fail_at(key, str("value ", i, " is out of range; allowed ", lo, " to ", hi));
  return note(key, i);
}

bool ParamReader::boolean(const std::string& key, bool fallback) const {
  const Json* v = find(key);
  if (!v) return note(key, fallback);
  if (!v->is_boolean()) fail_at(key, str("expected true or false, found ", v->dump()));
  return note(key, v->get<bool>());
}

std::optional<std::string> ParamReader::optional_text(const std::string& key) const {
  const Json* v = find(key);
  if (!v) return std::nullopt;
  if (!v->is_string()) fail_at(key, str("expected a string, found ", v->dump()));
  return note(key, v->get<std::string>());
}

std::string ParamReader::text(const std::string& key, const std::string& fallback) const {
  if (std::optional<std::string> v = optional_text(key)) return *v;
  return note(key, fallback);
}

std::string ParamReader::choice(const std::string& key, const std::string& fallback,
                                const std::vector<std::string>& allowed) const {
  const std::string v = text(key, fallback);
  if (std::find(allowed.begin(), allowed.end(), v) != allowed.end()) return v;
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
  fail_at(key, str("\"", v, "\" is not a choice; allowed: ", list));
}

std::optional<Vec3f> ParamReader::optional_vec3(const std::string& key) const {
  const Json* v = find(key);
  if (!v) return std::nullopt;
  if (!v->is_array() || v->size() != 3 || !std::all_of(v->begin(), v->end(), [](const Json& e) { return e.is_number(); }))
    fail_at(key, str("expected [x, y, z] numbers, found ", v->dump()));
  Vec3f out((*v)[0].get<float>(), (*v)[1].get<float>(), (*v)[2].get<float>());
  if (!finite(out)) fail_at(key, str("expected finite numbers, found ", v->dump()));
  return note(key, out);
}

Vec3f ParamReader::vec3(const std::string& key, const Vec3f& fallback) const {
  if (const std::optional<Vec3f> v = optional_vec3(key)) return *v;
  return note(key, fallback);
}

std::pair<double, double> ParamReader::range(const std::string& key, std::pair<double, double> fallback) const {
  const Json* v = find(key);
  if (!v) return note(key, fallback);
  if (!v->is_array() || v->size() != 2 || !(*v)[0].is_number() || !(*v)[1].is_number())
    fail_at(key, str("expected [min, max], found ", v->dump()));
  const double lo = (*v)[0].get<double>(), hi = (*v)[1].get<double>();
  if (!std::isfinite(lo) || !std::isfinite(hi)) fail_at(key, str("expected finite numbers, found ", v->dump()));
  if (std::abs(lo) > double(std::numeric_limits<float>::max()) || std::abs(hi) > double(std::numeric_limits<float>::max()))
    fail_at(key, str("values ", v->dump(), " are too large: every number must fit a 32-bit float (at most about 3.4e38)"));
  // Compared as stored (32-bit floats): values closer than that resolves would divide by zero.
  if (!(float(lo) < float(hi)))
    fail_at(key, str("min ", lo, " must be below max ", hi, " (the clamp divides by max - min)"));
  return note(key, std::make_pair(lo, hi));
}

ParamReader ParamReader::child(const std::string& key) const {
  const Json* v = find(key);
  if (v && !v->is_object()) fail_at(key, str("expected an object {...}, found ", v->dump()));
  return ParamReader(doc_, path_of(key));
}

namespace {

// "missing: the fluid particle radius r (...), in m; it is required"
std::string missing_message(const KeySpec& k) {
  const char* shape = k.type == KeyType::Vec3 ? " [x, y, z]" : k.type == KeyType::Range ? " [min, max]" : "";
  return str("missing: ", k.doc, shape, *k.unit ? str(", in ", k.unit) : std::string(), "; it is required");
}

}  // namespace

std::string ParamReader::declared_path() const {
  std::string out;
  size_t at = 1;
  while (at <= path_.size() && !path_.empty()) {
    const size_t next = std::min(path_.find('/', at), path_.size());
    const std::string part = path_.substr(at, next - at);
    if (!part.empty() && part.find_first_not_of("0123456789") == std::string::npos) out += "[]";
    else out += (out.empty() ? "" : ".") + part;
    at = next + 1;
  }
  return out;
}

std::string ParamReader::declared_key(const KeySpec& k) const {
  // A document may hold an object alone (a "render" object read on its own): its keys' paths end the
  // declared ones.
  const std::string name = k.name(), here = declared_path();
  const std::string full = here.empty() ? name : here + "." + name, declared = k.path;
  const bool ends = declared.size() > full.size() && declared.compare(declared.size() - full.size(), full.size(), full) == 0 &&
                    declared[declared.size() - full.size() - 1] == '.';
  if (declared != full && !ends)
    throw std::logic_error(str("key ", k.path, " read at ", here.empty() ? "the root" : here));
  return name;
}

void ParamReader::check_in_range(const KeySpec& k, const std::string& key, double v) const {
  if (const std::string why = out_of_range(k, v); !why.empty()) fail_at(key, why);
}

double ParamReader::number(const KeySpec& k, double r, double mass_ratio) const {
  const std::string key = declared_key(k);
  const std::optional<double> v = optional_number(key);
  if (!v) {
    if (!k.has_value()) fail_at(key, missing_message(k));
    return note(key, scaled_default(k, 0, r, mass_ratio));
  }
  check_in_range(k, key, *v);
  return *v;
}

long ParamReader::integer(const KeySpec& k) const {
  const std::string key = declared_key(k);
  const Json* v = find(key);
  if (!v) {
    if (!k.has_value()) fail_at(key, missing_message(k));
    return note(key, long(k.value[0]));
  }
  if (!v->is_number_integer()) fail_at(key, str("expected a whole number, found ", v->dump()));
  const long i = v->get<long>();
  check_in_range(k, key, double(i));
  return note(key, i);
}

bool ParamReader::boolean(const KeySpec& k) const { return boolean(declared_key(k), k.value[0] != 0.0); }

std::string ParamReader::choice(const KeySpec& k) const {
  std::vector<std::string> allowed;
  const std::string list = k.choices;
  for (size_t at = 0; at <= list.size();) {
    const size_t bar = std::min(list.find('|', at), list.size());
    allowed.push_back(list.substr(at, bar - at));
    at = bar + 1;
  }
  return choice(declared_key(k), allowed.front(), allowed);
}

std::optional<Vec3f> ParamReader::optional_vec3(const KeySpec& k) const {
  const std::string key = declared_key(k);
  const std::optional<Vec3f> v = optional_vec3(key);
  if (v)
    for (int a = 0; a < 3; ++a) check_in_range(k, key, double((*v)[a]));
  return v;
}

Vec3f ParamReader::vec3(const KeySpec& k) const {
  if (const std::optional<Vec3f> v = optional_vec3(k)) return *v;
  if (!k.has_value()) fail_at(k.name(), missing_message(k));
  return note(declared_key(k), declared_vec3<Vec3f>(k));
}

std::pair<double, double> ParamReader::range(const KeySpec& k, double r, double mass_ratio) const {
  const std::string key = declared_key(k);
  if (!has(key)) {
    if (!k.has_value()) fail_at(key, missing_message(k));
    return note(key, std::make_pair(scaled_default(k, 0, r, mass_ratio), scaled_default(k, 1, r, mass_ratio)));
  }
  const auto v = range(key, {0.0, 1.0});
  check_in_range(k, key, v.first);
  check_in_range(k, key, v.second);
  return v;
}

std::vector<ParamReader> ParamReader::array_of_objects(const std::string& key) const {
  const Json* v = find(key);
  std::vector<ParamReader> out;
  if (!v) return out;
  if (!v->is_array()) fail_at(key, str("expected an array [...], found ", v->type_name()));
  for (size_t i = 0; i < v->size(); ++i) {
    if (!(*v)[i].is_object()) fail_at(key, str("element ", i, " must be an object, found ", (*v)[i].dump()));
    out.emplace_back(doc_, path_of(key) + "/" + std::to_string(i));
  }
  return out;
}

size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1] ? 1 : 0)});
      diag = up;
    }
  }
  return row[b.size()];
}

namespace {

// Collect the paths of keys in `node` that nobody asked for (objects nobody asked for are reported
// whole; array elements are reported when their parent array was asked for as an array of objects).
void collect_unknown(const Json& node, const std::string& path, const std::set<std::string>& asked,
                     std::vector<std::string>& unknown) {
  if (node.is_object()) {
    for (auto it = node.begin(); it != node.end(); ++it) {
      const std::string p = path + "/" + it.key();
      if (!asked.count(p)) {
        unknown.push_back(p);
        continue;
      }
      collect_unknown(*it, p, asked, unknown);
    }
  } else if (node.is_array()) {
    for (size_t i = 0; i < node.size(); ++i)
      if (node[i].is_object()) collect_unknown(node[i], path + "/" + std::to_string(i), asked, unknown);
  }
}

std::string suggestion_for(const std::string& path, const std::set<std::string>& asked) {
  const auto slash = path.rfind('/');
  const std::string parent = path.substr(0, slash), key = path.substr(slash + 1);
  std::string best;
  size_t best_distance = SIZE_MAX;
  for (const auto& a : asked) {
    const auto s = a.rfind('/');
    if (a.substr(0, s) != parent) continue;
    const size_t d = edit_distance(key, a.substr(s + 1));
    if (d < best_distance) best_distance = d, best = a.substr(s + 1);
  }
  if (best.empty() || best_distance > std::max<size_t>(3, key.size() / 2)) return "";
  return str(" (did you mean \"", best, "\"?)");
}

}  // namespace

void ParamReader::reject_unknown_keys() const {
  std::vector<std::string> unknown;
  collect_unknown(doc_->root, "", doc_->asked, unknown);
  if (unknown.empty()) return;
  std::string message = str(doc_->source, ": unknown key", unknown.size() > 1 ? "s" : "", ":");
  for (const auto& u : unknown) message += str("\n  ", u, suggestion_for(u, doc_->asked));
  fail(message);
}

Json parse_json_text(const std::string& text, const std::string& source) {
  try {
    return Json::parse(text, nullptr, true, /*ignore_comments=*/true);
  } catch (const Json::parse_error& e) {
    // e.byte is the offset of the error; turn it into a line number for the message.
    const size_t upto = std::min<size_t>(e.byte, text.size());
    const long line = 1 + std::count(text.begin(), text.begin() + long(upto), '\n');
    fail(source, ":", line, ": not valid JSON: ", e.what());
  } catch (const Json::exception& e) {  // valid syntax the parser cannot hold, e.g. a number like 1e400
    fail(source, ": JSON value out of range: ", e.what());
  }
}

void apply_override(Json& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    fail("--set ", assignment, ": expected key.path=value, e.g. --set diffuse.k_ta=2000");
  const std::string path = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  Json value;
  try {
    value = Json::parse(text);
  } catch (const Json::parse_error&) {
    value = text;  // a bare word is a string
  } catch (const Json::exception& e) {  // valid syntax the parser cannot hold, e.g. 1e400
    fail("--set ", assignment, ": the value cannot be read (", e.what(), ")");
  }
  Json* node = &root;
  size_t start = 0;
  while (true) {
    const auto dot = path.find('.', start);
    const std::string key = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (key.empty()) fail("--set ", assignment, ": empty key in path \"", path, "\"");
    if (!node->is_object()) fail("--set ", assignment, ": \"", key, "\" is below a value that is not an object");
    if (dot == std::string::npos) {
      (*node)[key] = value;
      return;
    }
    node = &(*node)[key];
    if (node->is_null()) *node = Json::object();
    start = dot + 1;
  }
}

}  // namespace spume
