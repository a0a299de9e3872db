// SPDX-License-Identifier: Apache-2.0
#pragma once
// Content hashes of a sweep's inputs: a task records the hash of every file it
// reads, so a task run against changed inputs fails instead of mixing runs.
#include <cstdint>
#include <string>
#include <string_view>

namespace gnssemu::cli::sweep {

/// 64-bit FNV-1a of bytes (not cryptographic: it detects edits, not attacks).
std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t seed = 0xcbf29ce484222325ULL) noexcept;

/// 16 lower-case hex digits.
std::string hex64(std::uint64_t h);

/// hex64 of a file's bytes. Throws gnssemu::Error(path, 0, ...) when it cannot be read.
std::string file_hash(const std::string& path);

/// A whole file's bytes. Throws gnssemu::Error(path, 0, ...) when it cannot be read.
std::string read_file_bytes(const std::string& path);

/// Write bytes to path through path.tmp and a rename, so a crash leaves
/// either the old file or the new one, never half of it. Throws gnssemu::Error.
void write_file_atomic(const std::string& path, std::string_view bytes);

}  // namespace gnssemu::cli::sweep
