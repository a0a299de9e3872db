// Damaged configs: every outcome is a Config or a gnssemu::Error that names
// t.toml and a line inside the text; nothing else escapes.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "test_helpers.hpp"

namespace gnssemu::config::test {
namespace {

TEST(ConfigMutations, OnlyLocatedErrors) {
  std::ifstream in(kSource + "/config/default.toml");
  std::ostringstream s;
  s << in.rdbuf();
  const std::string original = s.str();
  // Relative nav path must resolve: parse against the config/ folder.
  const std::string dir = kSource + "/config";
  const std::string alphabet = "=[]\"'.,#\n 0123456789-+eE_abcxyz{}";
  std::mt19937_64 rng(12345);
  int loaded = 0;
  int errors = 0;
  for (int iter = 0; iter < 3000; ++iter) {
    std::string text = original;
    const int edits = 1 + static_cast<int>(rng() % 3);
    for (int k = 0; k < edits; ++k) {
      const std::size_t pos = rng() % text.size();
      switch (rng() % 3) {
        case 0: text.erase(pos, 1 + rng() % 4); break;
        case 1: text.insert(pos, 1, alphabet[rng() % alphabet.size()]); break;
        default: text[pos] = alphabet[rng() % alphabet.size()]; break;
      }
    }
    const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
    try {
      parse_config(text, "t.toml", dir);
      ++loaded;
    } catch (const Error& e) {
      ++errors;
      ASSERT_EQ(e.file(), "t.toml") << e.what();
      ASSERT_LE(e.line(), lines) << e.what() << "\n" << text;
      ASSERT_EQ(std::string(e.what()).rfind("t.toml", 0), 0u);
    }
  }
  // Most single-character damage is caught; comments and values absorb some.
  EXPECT_GT(errors, 1000);
  EXPECT_GT(loaded, 100);
}

}  // namespace
}  // namespace gnssemu::config::test
