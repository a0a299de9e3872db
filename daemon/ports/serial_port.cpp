// SPDX-License-Identifier: Apache-2.0
// Real UART through libserialport: 8N1, no flow control, reopened with
// back-off when the device goes away (USB adapter unplugged). Baud changes
// wait until the bytes already queued have left the line (docs/ports.md).
#include <fcntl.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <libserialport.h>

#include <algorithm>
#include <array>
#include <chrono>

#include <boost/asio/posix/stream_descriptor.hpp>
#include <boost/asio/steady_timer.hpp>
#include <spdlog/spdlog.h>

#include "core/common/error.hpp"
#include "daemon/ports/input_budget.hpp"
#include "daemon/ports/port_impl.hpp"

namespace gnssemu::daemon::detail {
namespace {

namespace asio = boost::asio;
using namespace std::chrono_literals;

constexpr auto kFirstRetry = 500ms;
constexpr auto kMaxRetry = 5s;
constexpr auto kRepeatWarning = 60s;  // while a device stays absent
constexpr auto kDrainPoll = 2ms;
constexpr auto kDrainGiveUp = 5s;     // switch anyway after this long

std::string sp_text(sp_return r) {
  if (r == SP_ERR_FAIL) {
    char* msg = sp_last_error_message();
    std::string s = msg != nullptr ? msg : "failed";
    sp_free_error_message(msg);
    return s;
  }
  switch (r) {
    case SP_ERR_ARG: return "invalid argument";
    case SP_ERR_MEM: return "out of memory";
    case SP_ERR_SUPP: return "not supported";
    default: return "error " + std::to_string(static_cast<int>(r));
  }
}

// The device: libserialport for UARTs it knows. libserialport 0.1 refuses
// devices whose real name does not start with "tty" (ptys such as socat's
// /dev/pts/N, some virtual UARTs): those are driven through termios
// directly, with the same 8N1 raw settings.
class Line {
public:
  ~Line() { close(); }
  /// Returns "" or what failed.
  std::string open(const std::string& path, uint32_t baud) {
    sp_return r = sp_get_port_by_name(path.c_str(), &sp_);
    if (r == SP_ERR_ARG) {
      sp_ = nullptr;
      return open_termios(path, baud);
    }
    if (r == SP_OK) r = sp_open(sp_, SP_MODE_READ_WRITE);
    if (r == SP_OK) r = sp_set_baudrate(sp_, static_cast<int>(baud));
    if (r == SP_OK) r = sp_set_bits(sp_, 8);
    if (r == SP_OK) r = sp_set_parity(sp_, SP_PARITY_NONE);
    if (r == SP_OK) r = sp_set_stopbits(sp_, 1);
    if (r == SP_OK) r = sp_set_flowcontrol(sp_, SP_FLOWCONTROL_NONE);
    if (r == SP_OK) r = sp_get_port_handle(sp_, &fd_);
    if (r != SP_OK) {
      const std::string why = sp_text(r);
      close();
      return why;
    }
    ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) | O_NONBLOCK);
    return {};
  }
  void close() noexcept {
    if (sp_ != nullptr) {
      sp_close(sp_);
      sp_free_port(sp_);
      sp_ = nullptr;
    } else if (fd_ >= 0) {
      ::close(fd_);
    }
    fd_ = -1;
  }
  bool set_baud(uint32_t baud) noexcept {
    if (sp_ != nullptr) return sp_set_baudrate(sp_, static_cast<int>(baud)) == SP_OK;
    termios tio{};
    if (::tcgetattr(fd_, &tio) != 0) return false;
    ::cfsetispeed(&tio, baud_constant(baud));
    ::cfsetospeed(&tio, baud_constant(baud));
    return ::tcsetattr(fd_, TCSANOW, &tio) == 0;
  }
  /// Bytes in the driver's output queue (TIOCOUTQ).
  int output_waiting() const noexcept {
    if (sp_ != nullptr) return sp_output_waiting(sp_);
    int n = 0;
    return ::ioctl(fd_, TIOCOUTQ, &n) == 0 ? n : 0;
  }
  /// Wait for the last bytes to leave the UART (tcdrain).
  void drain() noexcept {
    if (sp_ != nullptr) {
      sp_drain(sp_);
    } else {
      ::tcdrain(fd_);
    }
  }
  int fd() const noexcept { return fd_; }
  bool is_open() const noexcept { return fd_ >= 0; }
  bool via_libserialport() const noexcept { return sp_ != nullptr; }

private:
  std::string open_termios(const std::string& path, uint32_t baud) {
    fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0) return errno_text();
    termios tio{};
    if (::tcgetattr(fd_, &tio) != 0) {
      const std::string why = "not a terminal: " + errno_text();
      close();
      return why;
    }
    ::cfmakeraw(&tio);
    tio.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | PARENB | CRTSCTS | CSIZE);
    tio.c_cflag |= CS8 | CLOCAL | CREAD;
    tio.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
    ::cfsetispeed(&tio, baud_constant(baud));
    ::cfsetospeed(&tio, baud_constant(baud));
    if (::tcsetattr(fd_, TCSANOW, &tio) != 0) {
      const std::string why = "tcsetattr: " + errno_text();
      close();
      return why;
    }
    return {};
  }

  sp_port* sp_ = nullptr;
  int fd_ = -1;
};

class SerialPort final : public OutputPort {
public:
  SerialPort(const config::OutputPortConfig& cfg, const config::SerialPortConfig& serial, asio::io_context& io)
      : OutputPort(cfg), device_(serial.device), sd_(io), retry_timer_(io), drain_timer_(io), pacer_(io), baud_(cfg.baud) {
    queue_.reserve(kMaxQueuedBytes);
    held_.reserve(kMaxQueuedBytes);
  }

  ~SerialPort() override {
    stopped_ = true;
    close_device();
  }

  void start(PortListener* listener) override {
    listener_ = listener;
    try_open();
  }

  void set_baud_after_drain(uint32_t baud_bps) noexcept override {
    if (baud_bps == 0) return;
    pending_baud_ = baud_bps;
    drain_started_ = std::chrono::steady_clock::now();
    if (!line_.is_open()) {
      apply_pending_baud();  // nothing on the line: the next open uses it
      return;
    }
    poll_drain();
  }
  uint32_t baud() const noexcept override { return baud_; }

  std::string describe() const override {
    return device_ + " (serial " + std::to_string(baud_) + " 8N1" + (!line_.is_open() ? ", not open yet)" : ")");
  }

protected:
  void deliver(int /*source*/, std::string_view data, std::span<const std::size_t> /*ends*/, bool epoch) noexcept override {
    if (!line_.is_open()) {
      if (epoch) ++stats_.epochs_dropped;
      return;
    }
    // While a baud switch waits for the line to drain, new output is held
    // and goes out at the new rate.
    std::string& q = pending_baud_ != 0 ? held_ : queue_;
    if (q.size() + data.size() > kMaxQueuedBytes) {
      if (epoch) ++stats_.epochs_dropped;
      return;
    }
    q.append(data);
    epoch ? ++stats_.epochs_written : ++stats_.replies_written;
    if (pending_baud_ == 0) flush();
  }

private:
  void try_open() {
    if (stopped_) return;
    const std::string why = line_.open(device_, baud_);
    if (!why.empty()) {
      fail("cannot open: " + why);
      return;
    }
    boost::system::error_code ec;
    sd_.assign(line_.fd(), ec);
    if (failures_ > 0) {
      ++stats_.reopens;
      spdlog::info("output {}: {} open again after {} failed attempt(s)", config_.name, device_, failures_);
    } else {
      spdlog::debug("output {}: {} open via {}", config_.name, device_,
                    line_.via_libserialport() ? "libserialport" : "termios (not a UART libserialport knows)");
    }
    failures_ = 0;
    retry_delay_ = kFirstRetry;
    read();
  }

  // Logged at a limited rate: the first failure, then once a minute.
  void fail(const std::string& what) {
    const auto now = std::chrono::steady_clock::now();
    if (failures_ == 0 || now - last_warning_ >= kRepeatWarning) {
      spdlog::warn("output {}: {} {}; retrying every {} s at most ({} attempts so far)", config_.name, device_,
                   what, std::chrono::duration<double>(kMaxRetry).count(), failures_ + 1);
      last_warning_ = now;
    }
    ++failures_;
    const bool was_open = line_.is_open();
    close_device();
    if (stopped_) return;
    // Whatever the decoder holds belongs to the old connection.
    if (was_open && listener_ != nullptr) listener_->on_source_closed(0);
    retry_timer_.expires_after(retry_delay_);
    retry_delay_ = std::min<std::chrono::steady_clock::duration>(retry_delay_ * 2, kMaxRetry);
    retry_timer_.async_wait([this](const boost::system::error_code& ec) {
      if (!ec) try_open();
    });
  }

  void close_device() noexcept {
    boost::system::error_code ec;
    sd_.cancel(ec);
    if (sd_.is_open()) sd_.release();  // Line owns the fd
    line_.close();
    queue_.clear();
    held_.clear();
    // A switch waiting for the drain: nothing is left to drain, so the next
    // open uses the new rate (the host asked for it before the line went).
    drain_timer_.cancel();
    if (pending_baud_ != 0) {
      baud_ = pending_baud_;
      pending_baud_ = 0;
      ++stats_.baud_changes;
    }
    writing_ = false;
    ++generation_;
  }

  void read() {
    const uint64_t gen = generation_;
    sd_.async_read_some(asio::buffer(rx_), [this, gen](const boost::system::error_code& ec, std::size_t n) {
      if (ec == asio::error::operation_aborted || gen != generation_ || stopped_) return;
      if (ec || n == 0) {
        fail("read failed (" + (ec ? ec.message() : std::string("end of file")) + ")");
        return;
      }
      stats_.bytes_from_reader += n;
      if (listener_ != nullptr) listener_->on_port_input(0, {rx_.data(), n});
      pacer_.next(n, [this, gen] {
        if (gen == generation_ && !stopped_) read();
      });
    });
  }

  void flush() noexcept {
    if (writing_ || queue_.empty() || !line_.is_open()) return;
    const ssize_t n = ::write(sd_.native_handle(), queue_.data(), queue_.size());
    if (n > 0) {
      stats_.bytes_written += static_cast<uint64_t>(n);
      queue_.erase(0, static_cast<std::size_t>(n));
    } else if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) {
      fail("write failed (" + errno_text() + ")");
      return;
    }
    if (queue_.empty()) return;
    writing_ = true;
    const uint64_t gen = generation_;
    sd_.async_wait(asio::posix::stream_descriptor::wait_write, [this, gen](const boost::system::error_code& ec) {
      if (ec == asio::error::operation_aborted || gen != generation_ || stopped_) return;
      writing_ = false;
      if (!ec) flush();
    });
  }

  // Switch when our queue is empty and the driver's output queue has left
  // the line (TIOCOUTQ, then tcdrain for the last bytes in the UART).
  void poll_drain() noexcept {
    if (pending_baud_ == 0) return;
    const bool timed_out = std::chrono::steady_clock::now() - drain_started_ > kDrainGiveUp;
    if (!line_.is_open() || (queue_.empty() && line_.output_waiting() == 0) || timed_out) {
      if (line_.is_open() && !timed_out) line_.drain();
      apply_pending_baud();
      return;
    }
    drain_timer_.expires_after(kDrainPoll);
    drain_timer_.async_wait([this](const boost::system::error_code& ec) {
      if (!ec) poll_drain();
    });
  }

  void apply_pending_baud() noexcept {
    const uint32_t b = pending_baud_;
    pending_baud_ = 0;
    if (line_.is_open() && !line_.set_baud(b)) {
      spdlog::warn("output {}: cannot set {} baud", config_.name, b);
      queue_.append(held_);  // goes out at the old rate rather than never
      held_.clear();
      flush();
      return;
    }
    spdlog::info("output {}: line now {} baud (was {})", config_.name, b, baud_);
    baud_ = b;
    ++stats_.baud_changes;
    queue_.append(held_);
    held_.clear();
    flush();
  }

  std::string device_;  ///< path of the serial device
  asio::posix::stream_descriptor sd_;
  asio::steady_timer retry_timer_;
  asio::steady_timer drain_timer_;
  InputPacer pacer_;
  Line line_;
  uint32_t baud_;
  uint32_t pending_baud_ = 0;
  std::chrono::steady_clock::time_point drain_started_;
  std::string queue_;  // accepted, not yet written to the driver
  std::string held_;   // produced while a baud switch waits
  bool writing_ = false;
  bool stopped_ = false;
  uint64_t generation_ = 0;  // invalidates handlers of a closed device
  uint64_t failures_ = 0;
  std::chrono::steady_clock::duration retry_delay_ = kFirstRetry;
  std::chrono::steady_clock::time_point last_warning_;
  PortListener* listener_ = nullptr;
  std::array<uint8_t, 1024> rx_{};
};

}  // namespace

std::unique_ptr<OutputPort> make_port(const config::OutputPortConfig& cfg, const config::SerialPortConfig& serial,
                                      asio::io_context& io) {
  return std::make_unique<SerialPort>(cfg, serial, io);
}

}  // namespace gnssemu::daemon::detail

namespace gnssemu::daemon {

void validate_port(const config::OutputPortConfig& port, const config::SerialPortConfig& serial) {
  const std::string who = "output '" + port.name + "'";
  if (serial.device.empty() || serial.device.front() != '/') throw Error(who + ": serial device must be an absolute path");
  struct stat st{};
  // Absent is fine (unplugged adapter: the port retries); a plain file is a mistake.
  if (::stat(serial.device.c_str(), &st) == 0 && (S_ISREG(st.st_mode) || S_ISDIR(st.st_mode))) {
    throw Error(serial.device, 0, who + ": is a regular file or folder, not a serial device");
  }
  if (port.baud == 0) throw Error(who + ": a serial port needs a baud rate");
}

}  // namespace gnssemu::daemon
