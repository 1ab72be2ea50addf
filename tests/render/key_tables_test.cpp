// Every key declared once: the key tables of sim/keys/KEYS.md are the declarations' (regenerate them
// with `spume keys --markdown`), every group's table is there, and the declarations hold together.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "sim/core/error.h"
#include "sim/core/params.h"
#include "render/keys/key_catalog.h"

namespace spume {
namespace {

std::string keys_document() {
  std::ifstream in(std::string(SPUME_SOURCE_DIR) + "/sim/keys/KEYS.md");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(KeyTables, TheKeysDocumentShowsEveryGroupExactlyAsDeclared) {
  const std::string text = keys_document();
  ASSERT_FALSE(text.empty());
  for (const KeyGroup& g : key_groups()) {
    const std::string open = std::string("<!-- keys: ") + g.name + " -->\n", close = "<!-- /keys -->";
    const size_t at = text.find(open);
    ASSERT_NE(at, std::string::npos) << "sim/keys/KEYS.md has no table for " << g.name;
    const size_t end = text.find(close, at);
    ASSERT_NE(end, std::string::npos) << g.name;
    EXPECT_EQ(text.substr(at + open.size(), end - at - open.size()), key_table_markdown(g))
        << "sim/keys/KEYS.md's table of " << g.name
        << " differs from the declarations: run `build/spume keys --markdown`";
  }
}

TEST(KeyTables, DeclarationsAreUniqueAndConsistent) {
  std::set<std::string> paths;
  for (const KeyGroup& g : key_groups()) {
    for (const KeySpec* k : g.keys) {
      EXPECT_TRUE(paths.insert(k->path).second) << k->path << " declared twice";
      EXPECT_FALSE(std::string(k->doc).empty()) << k->path;
      const bool numeric = k->type == KeyType::Number || k->type == KeyType::Integer || k->type == KeyType::Vec3 ||
                           k->type == KeyType::Colour || k->type == KeyType::Range || k->type == KeyType::Size;
      if (numeric) {
        EXPECT_TRUE(k->has_value() || *k->default_text) << k->path << ": no default and no word on it";
        EXPECT_NE(k->lo_bound, Bound::Unset) << k->path << ": a number needs a range";
        EXPECT_NE(k->hi_bound, Bound::Unset) << k->path << ": a number needs a range";
        // The default lies in the range (at r0 for scaled keys).
        const int n = k->type == KeyType::Vec3 || k->type == KeyType::Colour ? 3
                      : k->type == KeyType::Range || k->type == KeyType::Size ? 2 : 1;
        if (k->has_value()) {
          for (int i = 0; i < n; ++i) {
            EXPECT_EQ(out_of_range(*k, scaled_default(*k, i, kDefaultsReferenceRadius)), "") << k->path << "[" << i << "]";
          }
        }
      }
      if (k->type == KeyType::Choice) {
        EXPECT_NE(std::string(k->choices).find('|'), std::string::npos) << k->path;
      }
    }
  }
}

TEST(KeyTables, ReadingADeclaredKeyChecksItsRangeAndNamesIt) {
  const ParamReader root = ParamReader::from_json(Json::parse(R"({"render": {"alpha": -1}})"), "s.json");
  const KeySpec* alpha = nullptr;
  for (const KeyGroup& g : key_groups())
    for (const KeySpec* k : g.keys)
      if (std::string(k->path) == "render.alpha") alpha = k;
  ASSERT_NE(alpha, nullptr);
  try {
    root.child("render").number(*alpha);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "s.json: /render/alpha: value -1 is out of range; allowed [0, 1e+09]");
  }
  // Read at the wrong place, a declaration is a bug, not a user's error.
  EXPECT_THROW(root.child("diffuse").number(*alpha), std::logic_error);
}

}  // namespace
}  // namespace spume
