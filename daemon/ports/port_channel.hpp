// SPDX-License-Identifier: Apache-2.0
#pragma once
// PortChannel: the transport side of one output port, wired to UART1 of the
// emulated u-blox (docs/ports.md). Input bytes go through the UBX/NMEA
// stream decoder into the device and its replies go back at once on the
// same port (behind what a latency link fault holds); each epoch it sends the messages the device composed for the
// port through a model of the M8's transmit buffer drained at the line rate,
// and through the link faults active on the port (daemon/ports/link_faults.hpp).
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include "core/faults/fault_stage.hpp"
#include "core/protocol/ubx/wire/ubx_decoder.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "daemon/ports/delay_line.hpp"
#include "daemon/ports/link_faults.hpp"
#include "daemon/ports/output_port.hpp"
#include "daemon/ports/tx_budget.hpp"

namespace gnssemu::daemon {

/// u-blox port every output is wired to: a host on TCP talks to UART1 as
/// through a serial-to-network bridge.
inline constexpr uint8_t kWiredPort = protocol::ubx::kPortUart1;
/// Quiet time on a port's input after which a partial frame is abandoned
/// (StreamDecoder::on_idle), s. Hosts wait for a reply before sending more,
/// so a garbage header must not hold back their next command for long; PX4
/// waits 250 ms for an ACK.
inline constexpr double kInputIdleS = 0.1;

struct ChannelStats {
  uint64_t messages_sent = 0;
  uint64_t messages_dropped = 0;  ///< TX buffer full (line too slow for the message set)
  uint64_t bytes_offered = 0;     ///< bytes of every message due, sent or not
  LinkFaultStats link_faults;     ///< what the port's link faults did
};

class PortChannel final : public PortListener {
public:
  /// Monotonic clock, s (steady_clock in the daemon; a fake in tests).
  using Clock = std::function<double()>;
  /// Called after the device handled a host's input on this channel (and
  /// the channel sent the reply and followed a baud change).
  using InputHandler = std::function<void(const protocol::ubx::InputResult& result)>;

  /// port talks as UART1 of device's output number output (< device.outputs());
  /// device outlives the channel.
  PortChannel(std::unique_ptr<OutputPort> port, protocol::ubx::Device& device, std::size_t output, Clock clock);
  ~PortChannel() override;
  PortChannel(const PortChannel&) = delete;
  PortChannel& operator=(const PortChannel&) = delete;

  /// Start the port's input (replies need the event loop running).
  void start();
  void on_input(InputHandler h) { on_input_ = std::move(h); }
  /// Abandon partial input frames after kInputIdleS of silence, and send
  /// epochs and replies a latency link fault held back when they are due, on timers of
  /// io (the daemon). Without it only check_idle() and check_delayed() do (tests).
  void use_idle_timer(boost::asio::io_context& io);
  /// The clock of the line's byte budget, s (default: the channel's clock).
  /// In lockstep the line is simulated too: it drains in simulation time.
  void set_line_clock(Clock clock) { line_clock_ = std::move(clock); }
  /// Sources whose input has been quiet for kInputIdleS with a partial frame
  /// pending: give the frame up and rescan what is held (replies go out).
  /// Returns true while some source still holds a partial frame.
  bool check_idle() noexcept;
  /// A host on another output reset the chip or loaded its configuration:
  /// the line follows this output's UART1 baud, and after a reset whatever
  /// partial input arrived before it is gone.
  void follow_device(bool reset) noexcept;

  /// The world's seed: the link faults' draws repeat for it.
  void set_link_seed(uint64_t seed) noexcept { link_.set_seed(seed); }
  /// This epoch's fault status (FaultStage::status(), after the receiver
  /// step; empty without a fault stage): the port events active on this
  /// output act from the next send_epoch on.
  void set_link_faults(std::span<const faults::FaultStatus> status) noexcept { link_.update(status); }
  const LinkFaults& link_faults() const noexcept { return link_; }

  /// Send what the device composed for this port this epoch (after
  /// Device::on_epoch) through the link faults and the TX budget, as one
  /// block. No allocation after the first epochs (a latency fault: after
  /// the most epochs it ever held at once).
  void send_epoch() noexcept;
  /// Send the device's NAV-RELPOSNED of this epoch that came after the
  /// epoch's output (Device::compose_relposned; a moving-base rover), between
  /// epochs: through the TX budget and the link faults (a stopped, frozen or
  /// slowed output sends none; drops and corruption draw after the epoch's
  /// messages; byte loss as for a reply; a latency holds it behind the epoch).
  void send_relative_position() noexcept;
  /// Send the epochs and replies a latency fault held that are due now. Returns true
  /// while some are still held.
  bool check_delayed() noexcept;

  void on_port_input(int source, std::span<const uint8_t> bytes) override;
  void on_source_closed(int source) override;

  OutputPort& port() noexcept { return *port_; }
  const OutputPort& port() const noexcept { return *port_; }
  /// Where the channel's hosts are attached to the device.
  protocol::ubx::Link link() const noexcept { return {output_, kWiredPort}; }
  const ChannelStats& stats() const noexcept { return stats_; }
  const TxBudget& budget() const noexcept { return budget_; }
  /// Per message label ("NAV-SAT", "GSV") the count dropped so far.
  const std::map<std::string, uint64_t, std::less<>>& drops() const noexcept { return drops_by_name_; }
  /// "NMEA", "UBX", "NMEA+UBX" or "nothing": what the port sends each epoch now.
  std::string_view output_summary() const noexcept;

private:
  class Sink;
  struct Input {
    protocol::ubx::StreamDecoder decoder;
    double last_input_s = 0.0;
  };
  /// A timer of the daemon's io and whether a wait is pending on it.
  struct Timer {
    std::unique_ptr<boost::asio::steady_timer> timer;
    bool armed = false;
  };
  /// Run check in delay_s on t (one wait per timer: an earlier one stays).
  void arm(Timer& t, double delay_s, bool (PortChannel::*check)() noexcept);
  void send_composed(double now) noexcept;
  /// Admit message (label for the drop counts) to out_ through the TX budget.
  bool admit(std::string_view message, std::string_view label, double now) noexcept;
  void handle_result(int source, const protocol::ubx::InputResult& r);
  void send_reply(int source, std::string_view label) noexcept;
  /// Ask the port for baud once what is queued has drained, and drain the budget at it from now.
  void switch_baud(uint32_t baud) noexcept;
  void count_drop(std::string_view label);
  void warn_drops();

  std::unique_ptr<OutputPort> port_;
  protocol::ubx::Device& device_;
  std::size_t output_;
  Clock clock_;
  Clock line_clock_;  ///< of budget_
  TxBudget budget_;
  bool line_;  ///< the port has a line rate that baud changes act on
  std::map<int, std::unique_ptr<Input>> inputs_;
  std::unique_ptr<Sink> sink_;
  InputHandler on_input_;
  Timer idle_timer_;   ///< abandons partial input frames
  Timer delay_timer_;  ///< sends epochs and replies a latency fault held
  /// Expires with this channel: a timer handler already queued when the
  /// channel is destroyed finds it gone instead of a dangling this.
  std::shared_ptr<int> alive_ = std::make_shared<int>(0);
  // Set while a decoder is feeding the device: the decoder must not be
  // reset or destroyed under it, so those wait until feed() returns.
  bool feeding_ = false;
  bool reset_after_feed_ = false;  ///< baud change or reset: drop the partial frame
  bool drop_after_feed_ = false;   ///< the source went away

  protocol::ubx::MessageList epoch_;
  protocol::ubx::MessageList between_;  ///< a NAV-RELPOSNED between epochs
  std::string between_bytes_;           ///< of it, admitted
  std::string reply_;
  ChannelStats stats_;
  std::map<std::string, uint64_t, std::less<>> drops_by_name_;
  // This epoch, for the one-time warning.
  std::size_t epoch_bytes_ = 0;
  std::string epoch_dropped_;
  std::string out_;                 ///< this epoch's admitted messages
  std::vector<std::size_t> out_ends_;  ///< where each of them ends in out_
  bool warned_ = false;
  LinkFaults link_;
  DelayLine delay_;
  std::string wire_;                    ///< out_ as the line carries it (byte loss)
  std::vector<std::size_t> wire_ends_;
};

}  // namespace gnssemu::daemon
