#pragma once
// PortChannel: the protocol side of one output port — an emulated u-blox M8
// whose UART1 is wired to the port (docs/ports.md). Input bytes go through
// the UBX/NMEA stream decoder into the configuration responder and replies
// go back at once on the same port; each epoch it sends the messages due
// under the port's CFG-MSG rates (UBX and NMEA, from the same Fix), through
// a model of the M8's transmit buffer drained at the line rate.
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include "config/config.hpp"
#include "core/protocol/nmea/nmea_encoder.hpp"
#include "core/protocol/ubx/ubx_decoder.hpp"
#include "core/protocol/ubx/ubx_responder.hpp"
#include "core/receiver/fix.hpp"
#include "daemon/output_port.hpp"
#include "daemon/tx_budget.hpp"

namespace gnssemu::daemon {

/// u-blox port the daemon's port is wired to.
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
};

class PortChannel final : public PortListener {
public:
  /// Monotonic clock, s (steady_clock in the daemon; a fake in tests).
  using Clock = std::function<double()>;
  /// Called when a host changed the navigation period (CFG-RATE), s.
  using NavPeriodHandler = std::function<void(double period_s)>;
  /// Called when a host sent CFG-RST (after the channel applied it).
  using ResetHandler = std::function<void(const protocol::ubx::ResetRequest& reset)>;

  /// Port settings (baud, protocol masks, message rates) from cfg become the
  /// responder's saved configuration; nav_period_s: the daemon's epoch period.
  PortChannel(const config::OutputPortConfig& cfg, std::unique_ptr<OutputPort> port, double nav_period_s,
              Clock clock, const protocol::ubx::ResponderConfig& responder_cfg = {});
  ~PortChannel() override;
  PortChannel(const PortChannel&) = delete;
  PortChannel& operator=(const PortChannel&) = delete;

  /// Start the port's input (replies need the event loop running).
  void start();
  void on_nav_period_change(NavPeriodHandler h) { on_nav_period_ = std::move(h); }
  void on_reset(ResetHandler h) { on_reset_ = std::move(h); }
  /// Abandon partial input frames after kInputIdleS of silence, on a timer
  /// of io (the daemon). Without it only check_idle() does (tests).
  void use_idle_timer(boost::asio::io_context& io);
  /// Sources whose input has been quiet for kInputIdleS with a partial frame
  /// pending: give the frame up and rescan what is held (replies go out).
  /// Returns true while some source still holds a partial frame.
  bool check_idle() noexcept;
  /// Receiver power-on on the channel's clock (default: construction). The
  /// uptime (NAV-STATUS msss) and the time to first fix count from it, and
  /// from every CFG-RST.
  void set_power_on(double clock_s) noexcept { uptime_origin_s_ = clock_s; }
  /// The shared receiver restarted (a CFG-RST on another port of the same
  /// chip): uptime and time to first fix count from now here too.
  void navigation_restarted() noexcept;

  /// One navigation epoch: messages due on this port, through the TX budget,
  /// written as one block. No allocation after the first epochs.
  void on_epoch(const receiver::Fix& fix) noexcept;

  /// Another port changed CFG-RATE: keep this receiver's stored rate equal.
  void set_nav_rate(const protocol::ubx::wire::CfgRate& rate) noexcept;
  /// The period the daemon actually runs epochs at, s (a CFG-RATE outside
  /// 1..10 Hz is clamped); the budget warning quotes it.
  void set_epoch_period(double period_s) noexcept { epoch_period_s_ = period_s; }

  void on_port_input(int source, std::span<const uint8_t> bytes) override;
  void on_source_closed(int source) override;

  OutputPort& port() noexcept { return *port_; }
  const OutputPort& port() const noexcept { return *port_; }
  protocol::ubx::ConfigResponder& responder() noexcept { return responder_; }
  const ChannelStats& stats() const noexcept { return stats_; }
  const TxBudget& budget() const noexcept { return budget_; }
  /// Per message label ("NAV-SAT", "GSV") the count dropped so far.
  const std::map<std::string, uint64_t, std::less<>>& drops() const noexcept { return drops_by_name_; }
  /// "NMEA", "UBX" or "NMEA+UBX": what the port sends each epoch now.
  std::string output_summary() const;

private:
  class Sink;
  struct Input {
    protocol::ubx::StreamDecoder decoder;
    double last_input_s = 0.0;
  };
  void arm_idle_timer(double delay_s);
  void handle_result(int source, const protocol::ubx::ResponderResult& r);
  void send_reply(int source) noexcept;
  /// Admit the messages in data through the budget; append the admitted to
  /// out_. now_s: clock.
  void admit_all(std::string_view data, double now_s) noexcept;
  void warn_drops();

  config::OutputPortConfig cfg_;
  std::unique_ptr<OutputPort> port_;
  Clock clock_;
  protocol::ubx::ConfigResponder responder_;
  protocol::nmea::NmeaConfig nmea_cfg_;
  TxBudget budget_;
  bool line_;  ///< the port has a line rate that baud changes act on
  std::map<int, std::unique_ptr<Input>> inputs_;
  std::unique_ptr<Sink> sink_;
  NavPeriodHandler on_nav_period_;
  ResetHandler on_reset_;
  std::unique_ptr<boost::asio::steady_timer> idle_timer_;
  bool idle_armed_ = false;  ///< idle_timer_ has a wait pending
  double uptime_origin_s_ = 0.0;  ///< power-on or the last CFG-RST, clock s
  // Set while a decoder is feeding the responder: the decoder must not be
  // reset or destroyed under it, so those wait until feed() returns.
  bool feeding_ = false;
  bool reset_after_feed_ = false;  ///< baud change or reset: drop the partial frame
  bool drop_after_feed_ = false;   ///< the source went away
  receiver::Fix last_fix_{};
  bool have_fix_ = false;

  std::string ubx_buf_, nmea_buf_, out_, reply_;
  ChannelStats stats_;
  std::map<std::string, uint64_t, std::less<>> drops_by_name_;
  // This epoch, for the one-time warning.
  std::size_t epoch_bytes_ = 0;
  std::string epoch_dropped_;
  bool warned_ = false;
  double epoch_period_s_;
};

}  // namespace gnssemu::daemon
