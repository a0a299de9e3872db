// SPDX-License-Identifier: Apache-2.0
// Wavefront OBJ geometry subset (Wavefront "Object Files (.obj)", Appendix B1
// of the Advanced Visualizer manual): v, f, usemtl.
#include <charconv>
#include <limits>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/error.hpp"
#include "core/scene/mesh.hpp"

namespace gnssemu::scene {

namespace {

std::string_view next_token(std::string_view& s) {
  std::size_t b = 0;
  while (b < s.size() && (s[b] == ' ' || s[b] == '\t' || s[b] == '\r')) ++b;
  std::size_t e = b;
  while (e < s.size() && s[e] != ' ' && s[e] != '\t' && s[e] != '\r') ++e;
  const std::string_view tok = s.substr(b, e - b);
  s.remove_prefix(e);
  return tok;
}

bool parse_double(std::string_view tok, double& v) {
  if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
  const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), v);
  if (r.ec == std::errc::result_out_of_range) {
    v = std::numeric_limits<double>::infinity();  // counted as non-finite by the builder
    return true;
  }
  if (r.ec == std::errc() && r.ptr == tok.data() + tok.size()) return true;
  // from_chars does not accept "nan"/"inf" spellings with signs in all libs.
  if (tok == "nan" || tok == "NaN" || tok == "-nan" || tok == "inf" || tok == "-inf") {
    v = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  return false;
}

}  // namespace

Mesh read_obj(const std::string& path, const Placement& placement) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, 0, "cannot open mesh file");
  MeshBuilder b(path, placement);
  std::string line;
  std::vector<int64_t> face;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::string_view s(line);
    const std::string_view kw = next_token(s);
    if (kw == "v") {
      double xyz[3];
      for (double& c : xyz) {
        const std::string_view tok = next_token(s);
        if (tok.empty()) throw Error(path, line_no, "vertex needs x y z");
        if (!parse_double(tok, c)) throw Error(path, line_no, "vertex coordinate '" + std::string(tok) + "' is not a number");
      }
      b.add_vertex(xyz[0], xyz[1], xyz[2], line_no);
    } else if (kw == "f") {
      face.clear();
      const auto nv = static_cast<int64_t>(b.vertex_count());
      for (std::string_view tok = next_token(s); !tok.empty(); tok = next_token(s)) {
        const std::string_view vi = tok.substr(0, tok.find('/'));
        int64_t i = 0;
        const auto r = std::from_chars(vi.data(), vi.data() + vi.size(), i);
        if (r.ec != std::errc() || r.ptr != vi.data() + vi.size() || i == 0) {
          throw Error(path, line_no, "face index '" + std::string(tok) + "' is not a non-zero integer");
        }
        face.push_back(i > 0 ? i - 1 : nv + i);  // negative: relative to the last vertex
      }
      b.add_face_checked(face.data(), static_cast<int>(face.size()), line_no);
    } else if (kw == "usemtl") {
      b.set_material(std::string(next_token(s)));
    }
    // vt, vn, g, o, s, mtllib, l, p, comments: geometry we do not need.
  }
  if (in.bad()) throw Error(path, line_no, "read error");
  return std::move(b).finish();
}

}  // namespace gnssemu::scene
