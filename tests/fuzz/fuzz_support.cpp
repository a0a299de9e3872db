// SPDX-License-Identifier: Apache-2.0
#include "fuzz_support.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace gnssemu::fuzz {

void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz oracle: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

void expect_names_file(const Error& e, const std::string& file) {
  if (e.file() != file) fail("gnssemu::Error without the file name: '" + std::string(e.what()) + "'");
}

ScratchDir::ScratchDir() {
  const char* tmp = std::getenv("TMPDIR");
  std::string templ = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/gnssemu-fuzz-XXXXXX";
  if (mkdtemp(templ.data()) == nullptr) fail("cannot create a scratch folder " + templ);
  dir_ = templ;
}

ScratchDir::~ScratchDir() {
  std::error_code ec;
  std::filesystem::remove_all(dir_, ec);
}

const std::string& ScratchFile::write(std::string_view bytes) {
  std::ofstream out(path_, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) fail("cannot write " + path_);
  return path_;
}

}  // namespace gnssemu::fuzz
