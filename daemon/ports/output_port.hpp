// SPDX-License-Identifier: Apache-2.0
#pragma once
// Output ports: the transports an emulated receiver talks on (docs/ports.md).
// A port moves bytes only; what to send is decided by its PortChannel. Every
// port type has a plain config (config::PtyPortConfig, ...), a static
// validator testable without hardware (validate_port) and a setup
// (open_port). Writes never block the event loop and never throw.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange

#include <boost/asio/io_context.hpp>

#include "config/config.hpp"

namespace gnssemu::daemon {

struct PortStats {
  uint64_t epochs_written = 0;
  uint64_t epochs_dropped = 0;     ///< not delivered: pty not drained, queue full, port closed, write failed
  uint64_t bytes_written = 0;
  uint64_t bytes_from_reader = 0;  ///< bytes received on the port's input
  uint64_t replies_written = 0;    ///< out-of-epoch writes (ACK/NAK, poll answers)
  uint64_t reopens = 0;            ///< serial: successful reopens after a failure
  uint64_t baud_changes = 0;       ///< line rate switches applied
};

/// Receives a port's input. source: 0, or a TCP client's id (> 0).
class PortListener {
public:
  virtual ~PortListener() = default;
  virtual void on_port_input(int source, std::span<const uint8_t> bytes) = 0;
  /// A TCP client went away (its partial input can be discarded).
  virtual void on_source_closed(int /*source*/) {}
};

class OutputPort {
public:
  virtual ~OutputPort() = default;
  /// Begin reading input (pty, serial, tcp clients) and, for serial,
  /// reopening after failures. listener may be null: input is discarded.
  virtual void start(PortListener* listener) { (void)listener; }
  /// Deliver one epoch of complete messages to every reader; message k ends
  /// at byte ends[k] of data (empty: data is one message). Datagram ports
  /// split only there.
  void write_epoch(std::string_view data, std::span<const std::size_t> ends = {}) noexcept {
    deliver(kAllSources, data, ends, true);
  }
  /// Deliver bytes outside the epoch schedule (a reply, sent whole) to
  /// source (a tcp client) or, for other ports, the port.
  void write_reply(int source, std::string_view data) noexcept { deliver(source, data, {}, false); }
  /// Source of write_reply for every reader (a message between epochs).
  static constexpr int kEveryReader = -1;
  /// Switch the line rate once everything queued so far has been
  /// transmitted (tcdrain), as a u-blox does after CFG-PRT / $PUBX,41.
  /// Serial: applied; pty: recorded in the termios only; others: ignored.
  virtual void set_baud_after_drain(uint32_t baud_bps) noexcept { (void)baud_bps; }
  /// Current line rate (bit/s) as the port knows it; 0 without a line.
  virtual uint32_t baud() const noexcept { return 0; }
  /// Readers now, for the status line: tcp clients; a pty 1 while someone
  /// drains it, else 0; -1 where the port cannot tell (serial, udp, file).
  virtual int readers() const noexcept { return -1; }
  /// One line for the startup message, e.g. "/tmp/gnssemu/gps0 (pty /dev/pts/5)".
  virtual std::string describe() const = 0;
  const config::OutputPortConfig& config() const noexcept { return config_; }
  const PortStats& stats() const noexcept { return stats_; }

protected:
  static constexpr int kAllSources = kEveryReader;
  explicit OutputPort(config::OutputPortConfig config) : config_(std::move(config)) {}
  /// Write data to source (kAllSources: everyone); ends: message ends as
  /// write_epoch's; epoch: count as an epoch, else as a reply. Never blocks
  /// or throws.
  virtual void deliver(int source, std::string_view data, std::span<const std::size_t> ends, bool epoch) noexcept = 0;
  config::OutputPortConfig config_;
  PortStats stats_;
};

/// Static checks of one port type, testable without hardware: they touch
/// the system no more than lstat()/stat(). A pty path must be free or a
/// symlink (a regular file is never overwritten); a file path not empty; a
/// serial device an absolute path that is not a regular file or folder, with
/// a baud rate; tcp/udp addresses must parse, a udp port be non-zero. Throw
/// gnssemu::Error naming the port (defined with each type's port).
void validate_port(const config::OutputPortConfig& port, const config::PtyPortConfig& pty);
void validate_port(const config::OutputPortConfig& port, const config::FilePortConfig& file);
void validate_port(const config::OutputPortConfig& port, const config::SerialPortConfig& serial);
void validate_port(const config::OutputPortConfig& port, const config::TcpPortConfig& server);
void validate_port(const config::OutputPortConfig& port, const config::UdpPortConfig& destination);
/// The check of port's type.
void validate_port(const config::OutputPortConfig& port);

/// Create the port (pty + symlink, serial device, listening socket, udp
/// socket, file). A serial device that is absent is not an error: the port
/// keeps retrying (logged). Throws gnssemu::Error.
std::unique_ptr<OutputPort> open_port(const config::OutputPortConfig& config, boost::asio::io_context& io);

/// Pty backlog (bytes unread by the reader) above which the queued epochs are
/// discarded before writing the next: Linux's tty read buffer (N_TTY_BUF_SIZE),
/// what a serial port's kernel side holds for a stalled reader.
inline constexpr int kPtyMaxBacklogBytes = 4096;
/// A pty nobody has read for this long has no reader: its queue is discarded
/// before the next epoch, so a reader that opens late gets the current one, s.
inline constexpr double kPtyReaderGone_s = 1.0;
/// Userspace queue per serial port / tcp client beyond which epochs are dropped.
inline constexpr std::size_t kMaxQueuedBytes = 64 * 1024;
/// Largest UDP datagram sent; an epoch is split at message boundaries.
inline constexpr std::size_t kMaxDatagramBytes = 1400;

}  // namespace gnssemu::daemon
