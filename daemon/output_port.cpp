#include "daemon/output_port.hpp"

#include <fcntl.h>
#include <pty.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/common/error.hpp"

namespace gnssemu::daemon {
namespace {

namespace fs = std::filesystem;

speed_t baud_constant(uint32_t baud) {
  switch (baud) {
    case 4800: return B4800;
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 921600: return B921600;
    default: return B9600;
  }
}

std::string errno_text() { return std::strerror(errno); }

void set_nonblocking(int fd) {
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags < 0 || ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) {
    throw Error("fcntl(O_NONBLOCK): " + errno_text());
  }
}

// Pseudo-terminal with a stable symlink to its slave side. The slave stays
// open here too, so a reader may come and go without the pty vanishing.
class PtyPort final : public OutputPort {
public:
  explicit PtyPort(const config::OutputPortConfig& cfg) : OutputPort(cfg) {
    validate_port(cfg);
    std::array<char, 128> name{};
    if (::openpty(&master_, &slave_, name.data(), nullptr, nullptr) != 0) {
      throw Error(cfg.path, 0, "output '" + cfg.name + "': openpty failed: " + errno_text());
    }
    slave_name_ = name.data();
    termios tio{};
    ::tcgetattr(slave_, &tio);
    ::cfmakeraw(&tio);
    ::cfsetispeed(&tio, baud_constant(cfg.baud));
    ::cfsetospeed(&tio, baud_constant(cfg.baud));
    ::tcsetattr(slave_, TCSANOW, &tio);
    ::fcntl(master_, F_SETFD, FD_CLOEXEC);
    ::fcntl(slave_, F_SETFD, FD_CLOEXEC);
    set_nonblocking(master_);
    set_nonblocking(slave_);
    make_symlink();
  }

  ~PtyPort() override {
    std::error_code ec;
    if (linked_ && fs::is_symlink(fs::symlink_status(config_.path, ec)) &&
        fs::read_symlink(config_.path, ec) == slave_name_) {
      fs::remove(config_.path, ec);
    }
    if (slave_ >= 0) ::close(slave_);
    if (master_ >= 0) ::close(master_);
  }

  void write_epoch(std::string_view data) noexcept override {
    drain_reader_input();
    int backlog = 0;
    if (::ioctl(slave_, FIONREAD, &backlog) == 0) {
      if (backlog == 0) unread_epochs_ = 0;
      if (backlog > kPtyMaxBacklogBytes) {
        // Nobody is reading: discard what is queued so a reader that opens
        // later starts with the current epoch.
        ::tcflush(slave_, TCIFLUSH);
        stats_.epochs_dropped += unread_epochs_;
        unread_epochs_ = 0;
      }
    }
    const ssize_t n = ::write(master_, data.data(), data.size());
    if (n == static_cast<ssize_t>(data.size())) {
      ++stats_.epochs_written;
      ++unread_epochs_;
      stats_.bytes_written += static_cast<uint64_t>(n);
      return;
    }
    if (n > 0) {
      // Partial write: the queue is full; drop what is queued (including the
      // torn sentence) so the reader never sees half an epoch followed by more.
      ::tcflush(slave_, TCIFLUSH);
      stats_.epochs_dropped += unread_epochs_ + 1;
      unread_epochs_ = 0;
      return;
    }
    ++stats_.epochs_dropped;
  }

  std::string describe() const override { return config_.path + " (pty " + slave_name_ + ")"; }

private:
  void make_symlink() {
    const fs::path link(config_.path);
    std::error_code ec;
    if (link.has_parent_path()) fs::create_directories(link.parent_path(), ec);
    if (ec) throw Error(config_.path, 0, "output '" + config_.name + "': cannot create folder: " + ec.message());
    // Atomic replace of a stale symlink: link a temporary name, rename over.
    const fs::path tmp = link.string() + ".tmp." + std::to_string(::getpid());
    fs::remove(tmp, ec);
    fs::create_symlink(slave_name_, tmp, ec);
    if (ec) throw Error(config_.path, 0, "output '" + config_.name + "': cannot create symlink: " + ec.message());
    fs::rename(tmp, link, ec);
    if (ec) {
      fs::remove(tmp, ec);
      throw Error(config_.path, 0, "output '" + config_.name + "': cannot place symlink");
    }
    linked_ = true;
  }

  void drain_reader_input() noexcept {
    std::array<char, 512> buf{};
    for (;;) {
      const ssize_t n = ::read(master_, buf.data(), buf.size());
      if (n <= 0) break;
      stats_.bytes_from_reader += static_cast<uint64_t>(n);
    }
  }

  int master_ = -1;
  int slave_ = -1;
  std::string slave_name_;
  bool linked_ = false;
  uint64_t unread_epochs_ = 0;
};

class FilePort final : public OutputPort {
public:
  explicit FilePort(const config::OutputPortConfig& cfg) : OutputPort(cfg) {
    validate_port(cfg);
    fd_ = ::open(cfg.path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NONBLOCK, 0644);
    if (fd_ < 0) throw Error(cfg.path, 0, "output '" + cfg.name + "': cannot open: " + errno_text());
  }
  ~FilePort() override {
    if (fd_ >= 0) ::close(fd_);
  }
  void write_epoch(std::string_view data) noexcept override {
    const ssize_t n = ::write(fd_, data.data(), data.size());
    if (n == static_cast<ssize_t>(data.size())) {
      ++stats_.epochs_written;
      stats_.bytes_written += static_cast<uint64_t>(n);
    } else {
      ++stats_.epochs_dropped;
    }
  }
  std::string describe() const override { return config_.path + " (file)"; }

private:
  int fd_ = -1;
};

}  // namespace

void validate_port(const config::OutputPortConfig& cfg) {
  if (cfg.path.empty()) throw Error("output '" + cfg.name + "': empty path");
  if (cfg.type == config::PortType::kPty) {
    struct stat st{};
    if (::lstat(cfg.path.c_str(), &st) == 0 && !S_ISLNK(st.st_mode)) {
      throw Error(cfg.path, 0,
                  "output '" + cfg.name + "': path exists and is not a symlink; refusing to replace it");
    }
  }
}

std::unique_ptr<OutputPort> open_port(const config::OutputPortConfig& cfg) {
  if (cfg.type == config::PortType::kPty) return std::make_unique<PtyPort>(cfg);
  return std::make_unique<FilePort>(cfg);
}

}  // namespace gnssemu::daemon
