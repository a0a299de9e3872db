// SPDX-License-Identifier: Apache-2.0
#include "core/common/line_source.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "core/common/error.hpp"

namespace gnssemu::text {

namespace {
constexpr std::size_t kChunk = 1 << 16;
}

/// Where the bytes come from: a gzip/plain file through zlib, or a stream.
class LineSource::Input {
public:
  virtual ~Input() = default;
  /// Up to n bytes into dst; 0 at the end. Throws gnssemu::Error on errors.
  virtual std::size_t read(char* dst, std::size_t n) = 0;
};

namespace {

class GzInput final : public LineSource::Input {
public:
  explicit GzInput(const std::string& path) : path_(path), f_(gzopen(path.c_str(), "rb")) {
    if (f_ == nullptr) throw Error(path, 0, std::string("cannot open: ") + std::strerror(errno));
  }
  ~GzInput() override { gzclose(f_); }
  GzInput(const GzInput&) = delete;
  GzInput& operator=(const GzInput&) = delete;

  std::size_t read(char* dst, std::size_t n) override {
    const int got = gzread(f_, dst, static_cast<unsigned>(n));
    if (got < 0) {
      int code = 0;
      throw Error(path_, 0, std::string("read error: ") + gzerror(f_, &code));
    }
    return static_cast<std::size_t>(got);
  }

private:
  std::string path_;
  gzFile f_;
};

class StreamInput final : public LineSource::Input {
public:
  StreamInput(std::istream& in, const std::string& name) : in_(in), name_(name) {}
  std::size_t read(char* dst, std::size_t n) override {
    in_.read(dst, static_cast<std::streamsize>(n));
    if (in_.bad()) throw Error(name_, 0, "read error");
    return static_cast<std::size_t>(in_.gcount());
  }

private:
  std::istream& in_;
  std::string name_;
};

}  // namespace

LineSource::LineSource(const std::string& path, LineLimits limits)
    : name_(path), limits_(limits), input_(std::make_unique<GzInput>(path)) {}

LineSource::LineSource(std::istream& in, std::string name, LineLimits limits)
    : name_(std::move(name)), limits_(limits) {
  input_ = std::make_unique<StreamInput>(in, name_);
}

LineSource::~LineSource() = default;

bool LineSource::fill() {
  if (eof_) return false;
  buf_.erase(0, pos_);
  pos_ = 0;
  const std::size_t old = buf_.size();
  buf_.resize(old + kChunk);
  const std::size_t got = input_->read(buf_.data() + old, kChunk);
  buf_.resize(old + got);
  total_ += got;
  if (total_ > limits_.max_bytes) {
    throw Error(name_, number_ + 1,
                "file longer than " + std::to_string(limits_.max_bytes >> 20) + " MiB: not a file of this kind");
  }
  if (got == 0) eof_ = true;
  return got > 0;
}

bool LineSource::next(Line& line) {
  std::size_t scanned = pos_;  // bytes of buf_ already searched for LF
  for (;;) {
    const auto end = std::find(buf_.begin() + static_cast<std::ptrdiff_t>(scanned), buf_.end(), '\n');
    const std::size_t lf = static_cast<std::size_t>(end - buf_.begin());
    const std::size_t len = lf - pos_;
    if (len > limits_.max_line_bytes + 1) {  // +1: a CR before the LF
      throw Error(name_, number_ + 1,
                  "line longer than " + std::to_string(limits_.max_line_bytes) + " bytes: not a file of this kind");
    }
    if (end != buf_.end()) {
      line.text.assign(buf_, pos_, len);
      pos_ = lf + 1;
      break;
    }
    scanned = buf_.size() - pos_;  // where the search resumes once fill() has moved the unread bytes to the front
    if (!fill()) {
      if (pos_ >= buf_.size()) return false;
      line.text.assign(buf_, pos_, std::string::npos);  // last line without LF
      pos_ = buf_.size();
      break;
    }
  }
  if (!line.text.empty() && line.text.back() == '\r') line.text.pop_back();
  if (line.text.size() > limits_.max_line_bytes) {
    throw Error(name_, number_ + 1,
                "line longer than " + std::to_string(limits_.max_line_bytes) + " bytes: not a file of this kind");
  }
  line.number = ++number_;
  return true;
}

}  // namespace gnssemu::text
