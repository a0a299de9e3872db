// SPDX-License-Identifier: Apache-2.0
#pragma once
// Shared pieces of the fuzz targets (docs/robustness.md): an input splitter,
// the oracle that turns a broken promise into a crash libFuzzer reports, and
// a scratch file for readers that take a path.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "core/common/error.hpp"

namespace gnssemu::fuzz {

/// Stops the run with what was broken: libFuzzer saves the input as a crash
/// artifact, the replay tests fail.
[[noreturn]] void fail(const std::string& what);

/// Oracle: when ok is false, fail(what).
inline void expect(bool ok, const char* what) {
  if (!ok) fail(what);
}

/// The contract of every file reader (DESIGN.md §3): a load-time error names
/// the file it read. A gnssemu::Error without it is a finding.
void expect_names_file(const Error& e, const std::string& file);

/// Splits one fuzz input: payload bytes from the front, control values
/// (choices, lengths) from the back, so a raw seed file (a recorded log, a
/// RINEX file) is mostly fed as it is and the tail steers the harness.
class InputSplitter {
public:
  InputSplitter(const std::uint8_t* data, std::size_t size) noexcept : data_(data), size_(size) {}

  std::size_t remaining() const noexcept { return size_; }

  /// A control byte from the back; 0 when the input is used up.
  std::uint8_t control() noexcept {
    if (size_ == 0) return 0;
    --size_;
    return data_[size_];
  }
  /// A control value in [lo, hi] (hi - lo < 65536).
  int control_in(int lo, int hi) noexcept {
    const unsigned span = static_cast<unsigned>(hi - lo) + 1u;
    unsigned v = control();
    if (span > 256u) v = v << 8 | control();
    return lo + static_cast<int>(v % span);
  }
  /// Up to n payload bytes from the front.
  std::string_view take(std::size_t n) noexcept {
    if (n > size_) n = size_;
    const std::string_view out(reinterpret_cast<const char*>(data_), n);
    data_ += n;
    size_ -= n;
    return out;
  }

private:
  const std::uint8_t* data_;
  std::size_t size_;
};

/// A private scratch folder under TMPDIR (else /tmp), removed with the object.
class ScratchDir {
public:
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::string& path() const noexcept { return dir_; }

private:
  std::string dir_;
};

/// A file in a scratch folder that a reader taking a path can open.
class ScratchFile {
public:
  /// suffix: the extension readers dispatch on (".ply", ".toml").
  explicit ScratchFile(const std::string& suffix) : path_(dir_.path() + "/input" + suffix) {}

  /// Replace the file's content with bytes; returns the path.
  const std::string& write(std::string_view bytes);
  const std::string& path() const noexcept { return path_; }

private:
  ScratchDir dir_;
  std::string path_;
};

}  // namespace gnssemu::fuzz

/// The libFuzzer entry point every target defines.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
