// SPDX-License-Identifier: Apache-2.0
// Pseudo-terminal with a stable symlink to its slave side (docs/daemon.md).
#include <fcntl.h>
#include <grp.h>
#include <pty.h>
#include <sys/stat.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <filesystem>

#include <boost/asio/posix/stream_descriptor.hpp>

#include "core/common/error.hpp"
#include "daemon/ports/input_budget.hpp"
#include "daemon/ports/port_impl.hpp"

namespace gnssemu::daemon::detail {
namespace {

namespace fs = std::filesystem;
namespace asio = boost::asio;

void set_nonblocking(int fd) {
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags < 0 || ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) throw Error("fcntl(O_NONBLOCK): " + errno_text());
}

// A serial device on Debian is root:dialout 0660, and gpsd (user gpsd, in
// dialout) opens its devices as that group. The slave of a pty is ours:tty
// 0620; when this process is in dialout (the systemd unit's
// SupplementaryGroups), it is handed to dialout 0660 so such a reader can
// open it as it would a serial port.
void share_with_dialout(int fd) {
  const group* g = ::getgrnam("dialout");
  if (g == nullptr) return;
  bool member = ::getegid() == g->gr_gid;
  std::array<gid_t, 256> groups{};
  const int n = ::getgroups(static_cast<int>(groups.size()), groups.data());
  for (int i = 0; i < n && !member; ++i) member = groups[static_cast<std::size_t>(i)] == g->gr_gid;
  if (!member) return;
  if (::fchown(fd, static_cast<uid_t>(-1), g->gr_gid) == 0) ::fchmod(fd, 0660);
}

// The slave stays open here too, so a reader may come and go without the pty
// vanishing. Input the reader writes arrives on the master.
class PtyPort final : public OutputPort {
public:
  PtyPort(const config::OutputPortConfig& cfg, const config::PtyPortConfig& pty, asio::io_context& io)
      : OutputPort(cfg), pty_(pty), master_sd_(io), pacer_(io) {
    std::array<char, 128> name{};
    int master = -1;
    if (::openpty(&master, &slave_, name.data(), nullptr, nullptr) != 0) {
      throw Error(pty_.path, 0, "output '" + cfg.name + "': openpty failed: " + errno_text());
    }
    master_sd_.assign(master);
    slave_name_ = name.data();
    termios tio{};
    ::tcgetattr(slave_, &tio);
    ::cfmakeraw(&tio);
    ::tcsetattr(slave_, TCSANOW, &tio);
    ::fcntl(master, F_SETFD, FD_CLOEXEC);
    ::fcntl(slave_, F_SETFD, FD_CLOEXEC);
    set_nonblocking(master);
    set_nonblocking(slave_);
    share_with_dialout(slave_);
    record_baud(cfg.baud);
    make_symlink();
  }

  ~PtyPort() override {
    std::error_code ec;
    if (linked_ && fs::is_symlink(fs::symlink_status(pty_.path, ec)) &&
        fs::read_symlink(pty_.path, ec) == slave_name_) {
      fs::remove(pty_.path, ec);
    }
    boost::system::error_code bec;
    master_sd_.close(bec);
    if (slave_ >= 0) ::close(slave_);
  }

  void start(PortListener* listener) override {
    listener_ = listener;
    read();
  }

  // A pty has no line: the rate is recorded in the termios (stty shows it),
  // once the bytes written before are out of our hands (they are: writes are
  // synchronous).
  void set_baud_after_drain(uint32_t baud_bps) noexcept override {
    record_baud(baud_bps);
    ++stats_.baud_changes;
  }
  uint32_t baud() const noexcept override { return baud_; }

  std::string describe() const override { return pty_.path + " (pty " + slave_name_ + ")"; }
  int readers() const noexcept override { return reader_active_ ? 1 : 0; }

protected:
  void deliver(int /*source*/, std::string_view data, std::span<const std::size_t> /*ends*/, bool epoch) noexcept override {
    const int master = master_sd_.native_handle();
    int backlog = 0;
    if (epoch && ::ioctl(slave_, FIONREAD, &backlog) == 0) {
      if (backlog == 0) unread_epochs_ = 0;
      // Nobody has read a byte for kPtyReaderGone_s (or the queue is longer
      // than a tty's read buffer): a reader that opens now must get this
      // epoch, not a burst of old ones. A reader that stalls for less keeps
      // its epochs, as the kernel's tty buffer keeps them on a serial port.
      const auto now = std::chrono::steady_clock::now();
      reader_active_ = backlog < backlog_after_write_;
      if (backlog == 0 || reader_active_) last_read_ = now;
      const bool gone = backlog > 0 && now - last_read_ >= std::chrono::duration<double>(kPtyReaderGone_s);
      if (gone || backlog > kPtyMaxBacklogBytes) {
        ::tcflush(slave_, TCIFLUSH);
        stats_.epochs_dropped += unread_epochs_;
        unread_epochs_ = 0;
        backlog = 0;
      }
    }
    const ssize_t n = ::write(master, data.data(), data.size());
    if (n == static_cast<ssize_t>(data.size())) {
      stats_.bytes_written += static_cast<uint64_t>(n);
      if (epoch) backlog_after_write_ = backlog + static_cast<int>(n);
      if (epoch) {
        ++stats_.epochs_written;
        ++unread_epochs_;
      } else {
        ++stats_.replies_written;
      }
      return;
    }
    if (n > 0) {
      // Partial write: the queue is full; drop what is queued (including the
      // torn message) so the reader never sees half an epoch followed by more.
      ::tcflush(slave_, TCIFLUSH);
      stats_.epochs_dropped += unread_epochs_ + (epoch ? 1 : 0);
      unread_epochs_ = 0;
      return;
    }
    if (epoch) ++stats_.epochs_dropped;
  }

private:
  void record_baud(uint32_t baud_bps) noexcept {
    termios tio{};
    if (::tcgetattr(slave_, &tio) != 0) return;
    ::cfsetispeed(&tio, baud_constant(baud_bps));
    ::cfsetospeed(&tio, baud_constant(baud_bps));
    ::tcsetattr(slave_, TCSANOW, &tio);
    baud_ = baud_bps;
  }

  void read() {
    master_sd_.async_read_some(asio::buffer(rx_), [this](const boost::system::error_code& ec, std::size_t n) {
      if (ec == asio::error::operation_aborted) return;
      if (ec) {
        // EIO while no reader has the slave open cannot happen (we hold it);
        // anything else: stop reading input, output continues.
        return;
      }
      stats_.bytes_from_reader += n;
      if (listener_ != nullptr) listener_->on_port_input(0, {rx_.data(), n});
      pacer_.next(n, [this] { read(); });
    });
  }

  void make_symlink() {
    const fs::path link(pty_.path);
    std::error_code ec;
    if (link.has_parent_path()) fs::create_directories(link.parent_path(), ec);
    if (ec) throw Error(pty_.path, 0, "output '" + config_.name + "': cannot create folder: " + ec.message());
    // Atomic replace of a stale symlink: link a temporary name, rename over.
    const fs::path tmp = link.string() + ".tmp." + std::to_string(::getpid());
    fs::remove(tmp, ec);
    fs::create_symlink(slave_name_, tmp, ec);
    if (ec) throw Error(pty_.path, 0, "output '" + config_.name + "': cannot create symlink: " + ec.message());
    fs::rename(tmp, link, ec);
    if (ec) {
      fs::remove(tmp, ec);
      throw Error(pty_.path, 0, "output '" + config_.name + "': cannot place symlink");
    }
    linked_ = true;
  }

  config::PtyPortConfig pty_;
  asio::posix::stream_descriptor master_sd_;
  InputPacer pacer_;
  int slave_ = -1;
  std::string slave_name_;
  bool linked_ = false;
  uint64_t unread_epochs_ = 0;
  int backlog_after_write_ = 0;  ///< unread bytes right after the last epoch was written
  bool reader_active_ = false;   ///< the reader drained some of the last epoch
  /// When the reader last drained something (or the queue was empty).
  std::chrono::steady_clock::time_point last_read_ = std::chrono::steady_clock::now();
  uint32_t baud_ = 0;
  PortListener* listener_ = nullptr;
  std::array<uint8_t, 1024> rx_{};
};

class FilePort final : public OutputPort {
public:
  FilePort(const config::OutputPortConfig& cfg, const config::FilePortConfig& file) : OutputPort(cfg), file_(file) {
    fd_ = ::open(file_.path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NONBLOCK, 0644);
    if (fd_ < 0) throw Error(file_.path, 0, "output '" + cfg.name + "': cannot open: " + errno_text());
  }
  ~FilePort() override {
    if (fd_ >= 0) ::close(fd_);
  }
  std::string describe() const override { return file_.path + " (file)"; }

protected:
  void deliver(int /*source*/, std::string_view data, std::span<const std::size_t> /*ends*/, bool epoch) noexcept override {
    const ssize_t n = ::write(fd_, data.data(), data.size());
    if (n == static_cast<ssize_t>(data.size())) {
      stats_.bytes_written += static_cast<uint64_t>(n);
      ++(epoch ? stats_.epochs_written : stats_.replies_written);
    } else if (epoch) {
      ++stats_.epochs_dropped;
    }
  }

private:
  config::FilePortConfig file_;
  int fd_ = -1;
};

}  // namespace

std::unique_ptr<OutputPort> make_port(const config::OutputPortConfig& cfg, const config::PtyPortConfig& pty,
                                      asio::io_context& io) {
  return std::make_unique<PtyPort>(cfg, pty, io);
}

std::unique_ptr<OutputPort> make_port(const config::OutputPortConfig& cfg, const config::FilePortConfig& file,
                                      asio::io_context& /*io*/) {
  return std::make_unique<FilePort>(cfg, file);
}

}  // namespace gnssemu::daemon::detail

namespace gnssemu::daemon {

void validate_port(const config::OutputPortConfig& port, const config::PtyPortConfig& pty) {
  const std::string who = "output '" + port.name + "'";
  if (pty.path.empty()) throw Error(who + ": empty path");
  struct stat st{};
  if (::lstat(pty.path.c_str(), &st) == 0 && !S_ISLNK(st.st_mode)) {
    throw Error(pty.path, 0, who + ": path exists and is not a symlink; refusing to replace it");
  }
}

void validate_port(const config::OutputPortConfig& port, const config::FilePortConfig& file) {
  if (file.path.empty()) throw Error("output '" + port.name + "': empty path");
}

}  // namespace gnssemu::daemon
