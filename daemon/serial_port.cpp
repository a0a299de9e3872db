// Real UART through libserialport: 8N1, no flow control, reopened with
// back-off when the device goes away (USB adapter unplugged). Baud changes
// wait until the bytes already queued have left the line (docs/ports.md).
#include <fcntl.h>
#include <unistd.h>

#include <libserialport.h>

#include <algorithm>
#include <array>
#include <chrono>

#include <boost/asio/posix/stream_descriptor.hpp>
#include <boost/asio/steady_timer.hpp>
#include <spdlog/spdlog.h>

#include "core/common/error.hpp"
#include "daemon/port_impl.hpp"

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

class SerialPort final : public OutputPort {
public:
  SerialPort(const config::OutputPortConfig& cfg, asio::io_context& io)
      : OutputPort(cfg), sd_(io), retry_timer_(io), drain_timer_(io), baud_(cfg.baud) {
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
    if (port_ == nullptr) {
      apply_pending_baud();  // nothing on the line: the next open uses it
      return;
    }
    poll_drain();
  }
  uint32_t baud() const noexcept override { return baud_; }

  std::string describe() const override {
    return config_.path + " (serial " + std::to_string(baud_) + " 8N1" + (port_ == nullptr ? ", not open yet)" : ")");
  }

protected:
  void deliver(int /*source*/, std::string_view data, bool epoch) noexcept override {
    if (port_ == nullptr) {
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
    sp_port* p = nullptr;
    sp_return r = sp_get_port_by_name(config_.path.c_str(), &p);
    if (r == SP_OK) r = sp_open(p, SP_MODE_READ_WRITE);
    if (r == SP_OK) r = configure(p, baud_);
    int fd = -1;
    if (r == SP_OK) r = sp_get_port_handle(p, &fd);
    if (r != SP_OK) {
      if (p != nullptr) {
        sp_close(p);
        sp_free_port(p);
      }
      fail("cannot open: " + sp_text(r));
      return;
    }
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
    port_ = p;
    boost::system::error_code ec;
    sd_.assign(fd, ec);
    if (failures_ > 0) {
      ++stats_.reopens;
      spdlog::info("output {}: {} open again after {} failed attempt(s)", config_.name, config_.path, failures_);
    }
    failures_ = 0;
    retry_delay_ = kFirstRetry;
    read();
  }

  static sp_return configure(sp_port* p, uint32_t baud) {
    sp_return r = sp_set_baudrate(p, static_cast<int>(baud));
    if (r == SP_OK) r = sp_set_bits(p, 8);
    if (r == SP_OK) r = sp_set_parity(p, SP_PARITY_NONE);
    if (r == SP_OK) r = sp_set_stopbits(p, 1);
    if (r == SP_OK) r = sp_set_flowcontrol(p, SP_FLOWCONTROL_NONE);
    return r;
  }

  // Logged at a limited rate: the first failure, then once a minute.
  void fail(const std::string& what) {
    const auto now = std::chrono::steady_clock::now();
    if (failures_ == 0 || now - last_warning_ >= kRepeatWarning) {
      spdlog::warn("output {}: {} {}; retrying every {} s at most ({} attempts so far)", config_.name, config_.path,
                   what, std::chrono::duration<double>(kMaxRetry).count(), failures_ + 1);
      last_warning_ = now;
    }
    ++failures_;
    close_device();
    if (stopped_) return;
    retry_timer_.expires_after(retry_delay_);
    retry_delay_ = std::min<std::chrono::steady_clock::duration>(retry_delay_ * 2, kMaxRetry);
    retry_timer_.async_wait([this](const boost::system::error_code& ec) {
      if (!ec) try_open();
    });
  }

  void close_device() noexcept {
    boost::system::error_code ec;
    sd_.cancel(ec);
    if (sd_.is_open()) sd_.release();  // libserialport owns the fd
    if (port_ != nullptr) {
      sp_close(port_);
      sp_free_port(port_);
      port_ = nullptr;
    }
    queue_.clear();
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
      read();
    });
  }

  void flush() noexcept {
    if (writing_ || queue_.empty() || port_ == nullptr) return;
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
    if (port_ == nullptr || (queue_.empty() && sp_output_waiting(port_) == 0) || timed_out) {
      if (port_ != nullptr && !timed_out) sp_drain(port_);
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
    if (port_ != nullptr) {
      const sp_return r = sp_set_baudrate(port_, static_cast<int>(b));
      if (r != SP_OK) {
        spdlog::warn("output {}: cannot set {} baud: {}", config_.name, b, sp_text(r));
        return;
      }
    }
    spdlog::info("output {}: line now {} baud (was {})", config_.name, b, baud_);
    baud_ = b;
    ++stats_.baud_changes;
    queue_.append(held_);
    held_.clear();
    flush();
  }

  asio::posix::stream_descriptor sd_;
  asio::steady_timer retry_timer_;
  asio::steady_timer drain_timer_;
  sp_port* port_ = nullptr;
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

std::unique_ptr<OutputPort> make_serial_port(const config::OutputPortConfig& cfg, asio::io_context& io) {
  return std::make_unique<SerialPort>(cfg, io);
}

}  // namespace gnssemu::daemon::detail
