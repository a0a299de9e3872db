// SPDX-License-Identifier: Apache-2.0
#pragma once
// Include rules between the project's folders: each folder is a layer that
// may include its own headers and those of the layers it uses (and theirs);
// third-party headers may be confined to some folders. Checked as text, so a
// rule holds for every file, whatever the build links.
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace gnssemu::layering {

/// One folder of the project and what its files may include.
struct Layer {
  std::string name;                  ///< unique, e.g. "orbit"
  std::string folder;                ///< from the project root, e.g. "core/orbit"
  std::vector<std::string> uses;     ///< names of the layers below it; their own uses come along
  std::vector<std::string> headers;  ///< single headers of other layers it may include, e.g. "core/receiver/fix.hpp"
};

/// A family of third-party headers and the folders that may include it.
struct ExternalRule {
  std::string prefix;                ///< start of the include path, e.g. "boost/"
  std::vector<std::string> only_in;  ///< folders from the project root, e.g. "daemon"
};

/// One include of one file that the rules would reject, allowed on purpose.
struct Exception {
  std::string file;     ///< from the project root, e.g. "core/scene/mesh.cpp"
  std::string include;  ///< the include path as written, e.g. "toml++/toml.h"
  std::string why;      ///< why it is allowed, kept with the table
};

struct Rules {
  std::vector<Layer> layers;
  std::vector<ExternalRule> externals;
  std::vector<Exception> exceptions;
  std::vector<std::string> skipped;  ///< folders not scanned (test data)
};

/// One #include directive of a source text.
struct Include {
  int line = 0;       ///< 1-based
  std::string path;   ///< as written between the quotes or angle brackets
  bool angled = false;
};

/// The #include directives of a C++ text, outside /* */ comments.
std::vector<Include> includes_of(std::string_view text);

/// One include that breaks a rule.
struct Violation {
  std::string file;  ///< from the project root
  int line = 0;      ///< 1-based; 0 for the file as a whole
  std::string include;  ///< as written, empty for the file as a whole
  bool angled = false;  ///< written <include>
  std::string reason;
};

/// "file:line: #include <include>: reason".
std::string to_string(const Violation& v);

class LayerChecker {
public:
  /// Throws std::invalid_argument when a layer uses an unknown name, two
  /// layers share a name or a folder, or the uses form a cycle.
  explicit LayerChecker(Rules rules);

  /// Violations of the includes in text, the contents of file (a path from
  /// the project root with '/' separators).
  std::vector<Violation> check(const std::string& file, std::string_view text) const;

  /// Every C++ file (.hpp .cpp .h .cc .inc) below root's layer folders,
  /// checked; also a file in no layer, and an exception that matches no
  /// include, are violations.
  std::vector<Violation> check_tree(const std::filesystem::path& root) const;

private:
  /// The layer whose folder is the longest prefix of path, or nullptr.
  const Layer* layer_of(std::string_view path) const;
  bool project_path(std::string_view include) const;
  bool excepted(const std::string& file, const std::string& include) const;

  Rules rules_;
  std::map<std::string, std::set<std::string>> allowed_;  ///< layer name -> layer folders and headers it may include
  std::set<std::string> roots_;                           ///< first components of the layer folders
};

}  // namespace gnssemu::layering
