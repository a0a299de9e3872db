// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/sweep/plan/input_hash.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/common/error.hpp"

namespace gnssemu::cli::sweep {

std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t seed) noexcept {
  constexpr std::uint64_t kPrime = 0x100000001b3ULL;
  std::uint64_t h = seed;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= kPrime;
  }
  return h;
}

std::string hex64(std::uint64_t h) { return fmt::format("{:016x}", h); }

std::string read_file_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error(path, 0, "cannot be read");
  std::ostringstream s;
  s << f.rdbuf();
  if (f.bad()) throw Error(path, 0, "read failed");
  return std::move(s).str();
}

std::string file_hash(const std::string& path) { return hex64(fnv1a64(read_file_bytes(path))); }

void write_file_atomic(const std::string& path, std::string_view bytes) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw Error(tmp, 0, "cannot open for writing");
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    f.close();
    if (!f) throw Error(tmp, 0, "write failed");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw Error(path, 0, "cannot rename " + tmp + ": " + ec.message());
}

}  // namespace gnssemu::cli::sweep
