// SPDX-License-Identifier: Apache-2.0
#include "include_rules.hpp"

#include <algorithm>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

namespace gnssemu::layering {

namespace {

/// True when path is folder itself or lies below it.
bool under(std::string_view path, std::string_view folder) {
  if (path.substr(0, folder.size()) != folder) return false;
  return path.size() == folder.size() || path[folder.size()] == '/';
}

std::string_view first_component(std::string_view path) { return path.substr(0, path.find('/')); }

bool cpp_file(const std::filesystem::path& p) {
  const std::string ext = p.extension().string();
  return ext == ".hpp" || ext == ".cpp" || ext == ".h" || ext == ".cc" || ext == ".inc";
}

}  // namespace

std::vector<Include> includes_of(std::string_view text) {
  std::vector<Include> out;
  bool in_comment = false;
  int number = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++number;
    // Drop what lies inside /* */ comments (not inside string literals:
    // an include line holds none before its path).
    std::string code;
    for (std::size_t i = 0; i < line.size(); ++i) {
      if (in_comment) {
        if (line.substr(i, 2) == "*/") {
          in_comment = false;
          ++i;
        }
      } else if (line.substr(i, 2) == "/*") {
        in_comment = true;
        ++i;
      } else if (line.substr(i, 2) == "//") {
        break;
      } else {
        code += line[i];
      }
    }
    std::string_view c = code;
    const auto skip_blanks = [&c] {
      const std::size_t b = c.find_first_not_of(" \t");
      c.remove_prefix(b == std::string_view::npos ? c.size() : b);
    };
    skip_blanks();
    if (c.empty() || c.front() != '#') continue;
    c.remove_prefix(1);
    skip_blanks();
    if (c.substr(0, 7) != "include") continue;
    c.remove_prefix(7);
    skip_blanks();
    if (c.empty() || (c.front() != '"' && c.front() != '<')) continue;
    const char close = c.front() == '"' ? '"' : '>';
    const std::size_t stop = c.find(close, 1);
    if (stop == std::string_view::npos) continue;
    out.push_back({number, std::string(c.substr(1, stop - 1)), close == '>'});
  }
  return out;
}

std::string to_string(const Violation& v) {
  std::ostringstream s;
  s << v.file << ':' << v.line << ": ";
  if (!v.include.empty()) s << "#include " << (v.angled ? '<' : '"') << v.include << (v.angled ? '>' : '"') << ": ";
  s << v.reason;
  return s.str();
}

LayerChecker::LayerChecker(Rules rules) : rules_(std::move(rules)) {
  std::map<std::string, const Layer*> by_name;
  std::set<std::string> folders;
  for (const Layer& l : rules_.layers) {
    if (!by_name.emplace(l.name, &l).second) throw std::invalid_argument("two layers named '" + l.name + "'");
    if (!folders.insert(l.folder).second) throw std::invalid_argument("two layers in folder '" + l.folder + "'");
    roots_.insert(std::string(first_component(l.folder)));
  }
  // Depth-first over the uses; a layer met again on the current path is a cycle.
  std::set<std::string> on_path;
  const std::function<const std::set<std::string>&(const Layer&)> allowed = [&](const Layer& l)
      -> const std::set<std::string>& {
    if (const auto it = allowed_.find(l.name); it != allowed_.end()) return it->second;
    if (!on_path.insert(l.name).second) throw std::invalid_argument("layers form a cycle through '" + l.name + "'");
    std::set<std::string> a{l.folder};
    a.insert(l.headers.begin(), l.headers.end());
    for (const std::string& u : l.uses) {
      const auto it = by_name.find(u);
      if (it == by_name.end()) throw std::invalid_argument("layer '" + l.name + "' uses unknown layer '" + u + "'");
      const std::set<std::string>& below = allowed(*it->second);
      a.insert(below.begin(), below.end());
    }
    on_path.erase(l.name);
    return allowed_[l.name] = std::move(a);
  };
  for (const Layer& l : rules_.layers) allowed(l);
}

const Layer* LayerChecker::layer_of(std::string_view path) const {
  const Layer* best = nullptr;
  for (const Layer& l : rules_.layers) {
    if (under(path, l.folder) && (best == nullptr || l.folder.size() > best->folder.size())) best = &l;
  }
  return best;
}

bool LayerChecker::project_path(std::string_view include) const {
  return include.find('/') != std::string_view::npos && roots_.count(std::string(first_component(include))) > 0;
}

bool LayerChecker::excepted(const std::string& file, const std::string& include) const {
  return std::any_of(rules_.exceptions.begin(), rules_.exceptions.end(),
                     [&](const Exception& e) { return e.file == file && e.include == include; });
}

std::vector<Violation> LayerChecker::check(const std::string& file, std::string_view text) const {
  std::vector<Violation> out;
  const Layer* own = layer_of(file);
  if (own == nullptr) {
    out.push_back({file, 0, "", false, "the file lies in no layer: add its folder to the layer table"});
    return out;
  }
  const std::set<std::string>& allowed = allowed_.at(own->name);
  for (const Include& inc : includes_of(text)) {
    if (excepted(file, inc.path)) continue;
    if (inc.path.find("..") != std::string::npos) {
      out.push_back({file, inc.line, inc.path, inc.angled,
                     "relative path: include project headers by their path from the root"});
      continue;
    }
    if (project_path(inc.path)) {
      const Layer* target = layer_of(inc.path);
      const bool ok = std::any_of(allowed.begin(), allowed.end(),
                                  [&](const std::string& a) { return under(inc.path, a); });
      if (target == nullptr) {
        out.push_back({file, inc.line, inc.path, inc.angled, "the header lies in no layer"});
      } else if (!ok) {
        out.push_back({file, inc.line, inc.path, inc.angled,
                       "layer '" + own->name + "' may not include layer '" + target->name +
                           "' (not below it in the layer table)"});
      }
      continue;
    }
    for (const ExternalRule& r : rules_.externals) {
      if (inc.path.compare(0, r.prefix.size(), r.prefix) != 0) continue;
      const bool ok = std::any_of(r.only_in.begin(), r.only_in.end(),
                                  [&](const std::string& f) { return under(file, f); });
      if (!ok) {
        std::string where;
        for (const std::string& f : r.only_in) where += (where.empty() ? "" : ", ") + f;
        out.push_back({file, inc.line, inc.path, inc.angled, "headers under '" + r.prefix + "' belong in " + where + " only"});
      }
    }
  }
  return out;
}

std::vector<Violation> LayerChecker::check_tree(const std::filesystem::path& root) const {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  for (const std::string& r : roots_) {
    if (!fs::is_directory(root / r)) continue;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(root / r)) {
      if (!e.is_regular_file() || !cpp_file(e.path())) continue;
      const std::string rel = fs::relative(e.path(), root).generic_string();
      const bool skip = std::any_of(rules_.skipped.begin(), rules_.skipped.end(),
                                    [&](const std::string& s) { return under(rel, s); });
      if (!skip) files.push_back(rel);
    }
  }
  std::sort(files.begin(), files.end());
  std::vector<Violation> out;
  std::set<std::pair<std::string, std::string>> used;
  for (const std::string& f : files) {
    std::ifstream in(root / f, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    for (Violation& v : check(f, text.str())) out.push_back(std::move(v));
    for (const Include& inc : includes_of(text.str())) {
      if (excepted(f, inc.path)) used.emplace(f, inc.path);
    }
  }
  for (const Exception& e : rules_.exceptions) {
    if (used.count({e.file, e.include}) == 0) {
      out.push_back({e.file, 0, e.include, false, "an exception in the layer table matches no include: remove it"});
    }
  }
  return out;
}

}  // namespace gnssemu::layering
