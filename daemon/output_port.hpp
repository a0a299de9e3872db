#pragma once
// Output ports: where an epoch of sentences goes. Each port owns its encoder
// configuration. Writes never block the epoch loop: a pty nobody drains drops
// whole epochs (counted); the data a late reader sees is at most a few epochs old.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "config/config.hpp"

namespace gnssemu::daemon {

struct PortStats {
  uint64_t epochs_written = 0;
  uint64_t epochs_dropped = 0;  ///< not delivered: pty not drained, or write failed
  uint64_t bytes_written = 0;
  uint64_t bytes_from_reader = 0;  ///< bytes the reader wrote to us (discarded)
};

class OutputPort {
public:
  virtual ~OutputPort() = default;
  /// Deliver one epoch (complete sentences). Never blocks, never throws.
  virtual void write_epoch(std::string_view data) noexcept = 0;
  /// One line for the startup message, e.g. "/tmp/gnssemu/gps0 (pty /dev/pts/5)".
  virtual std::string describe() const = 0;
  const config::OutputPortConfig& config() const noexcept { return config_; }
  const PortStats& stats() const noexcept { return stats_; }

protected:
  explicit OutputPort(config::OutputPortConfig config) : config_(std::move(config)) {}
  config::OutputPortConfig config_;
  PortStats stats_;
};

/// Static checks of a port config, without touching the system beyond
/// lstat(): a pty path must be free or a symlink (a regular file is never
/// overwritten). Throws gnssemu::Error naming the port.
void validate_port(const config::OutputPortConfig& config);

/// Create the port (pty + symlink, or file). Throws gnssemu::Error.
std::unique_ptr<OutputPort> open_port(const config::OutputPortConfig& config);

/// Pty backlog (bytes unread by the reader) above which the queued epochs are
/// discarded before writing the next: keeps what a late reader sees fresh.
inline constexpr int kPtyMaxBacklogBytes = 2048;

}  // namespace gnssemu::daemon
