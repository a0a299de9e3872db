// SPDX-License-Identifier: Apache-2.0
// PLY polygon files (Greg Turk, "The PLY Polygon File Format", 1994):
// header, then elements in header order; ascii or binary (either endianness).
#include <algorithm>
#include <bit>
#include <charconv>
#include <cstdio>
#include <cerrno>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/common/error.hpp"
#include "core/scene/mesh.hpp"

namespace gnssemu::scene {

namespace {

// Elements per PLY element line at most (vertex indices are 32-bit).
constexpr int64_t kMaxElementCount = 2'000'000'000;

std::string fmt_number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

enum class Type { kI8, kU8, kI16, kU16, kI32, kU32, kF32, kF64, kBad };

Type type_of(const std::string& s) {
  if (s == "char" || s == "int8") return Type::kI8;
  if (s == "uchar" || s == "uint8") return Type::kU8;
  if (s == "short" || s == "int16") return Type::kI16;
  if (s == "ushort" || s == "uint16") return Type::kU16;
  if (s == "int" || s == "int32") return Type::kI32;
  if (s == "uint" || s == "uint32") return Type::kU32;
  if (s == "float" || s == "float32") return Type::kF32;
  if (s == "double" || s == "float64") return Type::kF64;
  return Type::kBad;
}

int size_of(Type t) {
  switch (t) {
    case Type::kI8: case Type::kU8: return 1;
    case Type::kI16: case Type::kU16: return 2;
    case Type::kI32: case Type::kU32: case Type::kF32: return 4;
    case Type::kF64: return 8;
    case Type::kBad: break;
  }
  return 0;
}

struct Property {
  std::string name;
  Type type = Type::kBad;
  bool list = false;
  Type count_type = Type::kBad;
};

struct Element {
  std::string name;
  int64_t count = 0;
  std::vector<Property> props;
  int header_line = 0;
};

enum class Format { kAscii, kLittle, kBig };

class Body {
public:
  Body(std::istream& in, const std::string& path, Format f, int line) : in_(in), path_(path), format_(f), line_(line) {}

  // Reads one value; where names what is being read (for truncation errors).
  double read(Type t, const std::string& where) {
    if (format_ == Format::kAscii) return read_ascii(where);
    unsigned char b[8];
    const int n = size_of(t);
    in_.read(reinterpret_cast<char*>(b), n);
    if (in_.gcount() != n) throw Error(path_, 0, "binary body truncated in " + where);
    const bool swap = (format_ == Format::kBig) != (std::endian::native == std::endian::big);
    if (swap) std::reverse(b, b + n);
    switch (t) {
      case Type::kI8: return static_cast<int8_t>(b[0]);
      case Type::kU8: return b[0];
      case Type::kI16: { int16_t v; std::memcpy(&v, b, 2); return v; }
      case Type::kU16: { uint16_t v; std::memcpy(&v, b, 2); return v; }
      case Type::kI32: { int32_t v; std::memcpy(&v, b, 4); return v; }
      case Type::kU32: { uint32_t v; std::memcpy(&v, b, 4); return v; }
      case Type::kF32: { float v; std::memcpy(&v, b, 4); return v; }
      case Type::kF64: { double v; std::memcpy(&v, b, 8); return v; }
      case Type::kBad: break;
    }
    return 0.0;
  }
  // Ascii: one element per line.
  void next_element(const Element& e, int64_t i) {
    if (format_ != Format::kAscii) return;
    if (!std::getline(in_, text_)) {
      throw Error(path_, line_, "ASCII body ends before element " + e.name + " " + std::to_string(i) + " of " +
                                    std::to_string(e.count));
    }
    ++line_;
    tokens_.clear();
    tokens_.str(text_);
  }
  int line() const { return format_ == Format::kAscii ? line_ : 0; }

private:
  double read_ascii(const std::string& where) {
    std::string tok;
    if (!(tokens_ >> tok)) throw Error(path_, line_, "missing value in " + where);
    if (tok == "nan" || tok == "-nan" || tok == "inf" || tok == "-inf") return std::numeric_limits<double>::quiet_NaN();
    // strtod, not stod: an underflowing value (1e-320) is a valid number
    // (subnormal or 0), only overflow is out of range (infinite).
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(tok.c_str(), &end);
    if (end != tok.c_str() + tok.size() || tok.empty() || std::isspace(static_cast<unsigned char>(tok[0]))) {
      throw Error(path_, line_, "'" + tok + "' is not a number in " + where);
    }
    if (errno == ERANGE && std::fabs(v) > 1.0) return std::numeric_limits<double>::infinity();
    return v;
  }

  std::istream& in_;
  const std::string& path_;
  Format format_;
  int line_;
  std::string text_;
  std::istringstream tokens_;
};

}  // namespace

Mesh read_ply(const std::string& path, const Placement& placement) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, 0, "cannot open mesh file");
  std::string line;
  int line_no = 0;
  auto header_line = [&]() -> std::istringstream {
    if (!std::getline(in, line)) throw Error(path, line_no, "PLY header ends before end_header");
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return std::istringstream(line);
  };
  if (header_line().str() != "ply") throw Error(path, 1, "not a PLY file (first line must be 'ply')");
  Format format = Format::kAscii;
  bool have_format = false;
  std::vector<Element> elements;
  for (;;) {
    std::istringstream ls = header_line();
    std::string kw;
    ls >> kw;
    if (kw == "end_header") break;
    if (kw == "comment" || kw == "obj_info" || kw.empty()) continue;
    if (kw == "format") {
      std::string f, v;
      ls >> f >> v;
      if (f == "ascii") format = Format::kAscii;
      else if (f == "binary_little_endian") format = Format::kLittle;
      else if (f == "binary_big_endian") format = Format::kBig;
      else throw Error(path, line_no, "unknown PLY format '" + f + "'");
      if (v != "1.0") throw Error(path, line_no, "unsupported PLY version '" + v + "' (1.0 expected)");
      have_format = true;
    } else if (kw == "element") {
      Element e;
      std::string count_text, rest;
      ls >> e.name >> count_text;
      const char* end = count_text.data() + count_text.size();
      const auto r = std::from_chars(count_text.data(), end, e.count);
      if (!ls || e.name.empty() || r.ec != std::errc() || r.ptr != end || e.count < 0 || (ls >> rest)) {
        throw Error(path, line_no, "bad element line '" + line + "' (element NAME COUNT, COUNT a non-negative integer)");
      }
      if (e.count > kMaxElementCount) {
        throw Error(path, line_no, "element " + e.name + " count " + count_text + " is larger than " +
                                       std::to_string(kMaxElementCount));
      }
      e.header_line = line_no;
      elements.push_back(std::move(e));
    } else if (kw == "property") {
      if (elements.empty()) throw Error(path, line_no, "property before any element");
      Property p;
      std::string t;
      ls >> t;
      if (t == "list") {
        std::string ct, it;
        ls >> ct >> it >> p.name;
        p.list = true;
        p.count_type = type_of(ct);
        p.type = type_of(it);
        if (p.count_type == Type::kBad || p.type == Type::kBad || p.count_type == Type::kF32 ||
            p.count_type == Type::kF64) {
          throw Error(path, line_no, "bad list property types '" + ct + " " + it + "'");
        }
      } else {
        p.type = type_of(t);
        ls >> p.name;
        if (p.type == Type::kBad) throw Error(path, line_no, "unknown property type '" + t + "'");
      }
      if (p.name.empty()) throw Error(path, line_no, "property without a name");
      elements.back().props.push_back(p);
    } else {
      throw Error(path, line_no, "unknown PLY header keyword '" + kw + "'");
    }
  }
  if (!have_format) throw Error(path, line_no, "PLY header has no format line");
  for (const Element& e : elements) {
    // Items without properties take no bytes: a huge count would only spin.
    if (e.count > 0 && e.props.empty()) {
      throw Error(path, e.header_line, "element " + e.name + " has " + std::to_string(e.count) + " items but no property lines");
    }
  }

  MeshBuilder b(path, placement);
  Body body(in, path, format, line_no);
  std::vector<int64_t> face;
  bool have_vertices = false;
  for (const Element& e : elements) {
    int ix = -1, iy = -1, iz = -1, iface = -1;
    for (std::size_t k = 0; k < e.props.size(); ++k) {
      const Property& p = e.props[k];
      const int ki = static_cast<int>(k);
      if (e.name == "vertex" && !p.list) {
        if (p.name == "x") ix = ki;
        if (p.name == "y") iy = ki;
        if (p.name == "z") iz = ki;
      }
      if (e.name == "face" && p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) iface = ki;
    }
    if (e.name == "vertex" && (ix < 0 || iy < 0 || iz < 0)) {
      throw Error(path, e.header_line, "element vertex needs properties x, y and z");
    }
    if (e.name == "face" && iface < 0) throw Error(path, e.header_line, "element face needs a vertex_indices list");
    if (e.name == "face" && !have_vertices) throw Error(path, e.header_line, "element face before element vertex");
    if (e.name == "vertex") have_vertices = true;
    for (int64_t i = 0; i < e.count; ++i) {
      body.next_element(e, i);
      const std::string where = "element " + e.name + " " + std::to_string(i);
      double xyz[3] = {0.0, 0.0, 0.0};
      for (std::size_t k = 0; k < e.props.size(); ++k) {
        const Property& p = e.props[k];
        const int ki = static_cast<int>(k);
        if (p.list) {
          const double n = body.read(p.count_type, where);
          if (!(n >= 0.0) || n > 1.0e6) throw Error(path, body.line(), "bad list length in " + where);
          const auto count = static_cast<int64_t>(n);
          if (ki == iface) face.clear();
          for (int64_t j = 0; j < count; ++j) {
            const double v = body.read(p.type, where);
            if (ki != iface) continue;
            // Integers only, within what a vertex count can reach (the
            // float-to-int64 conversion is undefined beyond 9.2e18).
            if (!std::isfinite(v) || v != std::floor(v) || std::fabs(v) > 4.0e9) {
              throw Error(path, body.line(), "vertex index " + fmt_number(v) + " in " + where + " is not an integer index");
            }
            face.push_back(static_cast<int64_t>(v));
          }
        } else {
          const double v = body.read(p.type, where);
          if (ki == ix) xyz[0] = v;
          if (ki == iy) xyz[1] = v;
          if (ki == iz) xyz[2] = v;
        }
      }
      if (e.name == "vertex") b.add_vertex(xyz[0], xyz[1], xyz[2], body.line());
      if (e.name == "face") b.add_face_checked(face.data(), static_cast<int>(face.size()), body.line());
    }
  }
  return std::move(b).finish();
}

}  // namespace gnssemu::scene
