// SPDX-License-Identifier: Apache-2.0
#pragma once
// StatusProducer: the one source of the daemon's live status (docs/status.md):
// the fix, every satellite with its state, the error against truth, truth
// and port counters, active faults and a short history. The status page's
// /api/status and server-sent events and the control socket's `status`
// serialise the same object with write_json. Plain class: no I/O, no clock
// (callers pass monotonic time); on_epoch and write_json allocate nothing
// once the output string has capacity.
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/receiver/fix.hpp"
#include "core/world/truth.hpp"
#include "daemon/ports/link_fault_stats.hpp"
#include "daemon/status/overview.hpp"
#include "daemon/truth/truth_packet.hpp"

namespace gnssemu::daemon {

/// What the run is set up with (constant while it runs).
struct StatusSettings {
  double elevation_mask_deg = 5.0;  ///< receiver elevation mask, deg [0, 90)
  double acquire_dbhz = 30.0;       ///< tracking: C/N0 to acquire, dB-Hz
  double lose_dbhz = 25.0;          ///< tracking: C/N0 below which lock is lost, dB-Hz
  double rate_hz = 1.0;             ///< configured epoch rate, Hz [1, 10]
  std::string time_mode = "realtime";  ///< "realtime" or "lockstep"
};

/// One output port, named once at start-up.
struct PortInfo {
  std::string name;      ///< [[output]] name
  std::string type;      ///< pty, serial, tcp, udp, file
  std::string where;     ///< path or address, as the start-up line prints it
};

/// One output port's counters, totals since start (the producer derives rates).
struct PortCounters {
  std::string_view protocols;      ///< "NMEA", "UBX", "NMEA+UBX", "nothing" (static text)
  uint32_t baud_bps = 0;           ///< line rate, bit/s; 0: no line (tcp, udp, file)
  uint64_t bytes_offered = 0;      ///< bytes of every message due, sent or dropped
  uint64_t bytes_written = 0;      ///< bytes handed to the transport
  uint64_t epochs_written = 0;
  uint64_t epochs_dropped = 0;     ///< the transport could not take them (reader too slow)
  uint64_t messages_dropped = 0;   ///< over the line budget (TX buffer full)
  double tx_level_bytes = 0.0;     ///< TX buffer queued now, bytes
  double tx_capacity_bytes = 0.0;  ///< TX buffer size, bytes
  LinkFaultStats link_faults;      ///< what port events did to the port (docs/faults.md §5)
};

/// Truth input counters, totals since start.
struct TruthCounters {
  uint64_t packets_accepted = 0;
  std::array<uint64_t, kDropReasonCount> dropped{};  ///< per DropReason
  bool simulator = false;          ///< a simulator's vehicle drives the receiver (else demo or none)
  bool fresh = false;              ///< its truth is within the timeout
  bool demo = false;               ///< the demo trajectory drives the receiver
  double age_s = std::numeric_limits<double>::quiet_NaN();  ///< since the simulator's last packet, s; NaN: none
};

/// RTCM 3 corrections the receiver's ports took (docs/rtk.md).
struct CorrectionCounters {
  uint64_t messages = 0;    ///< frames with a good CRC on a port that takes RTCM 3
  uint64_t used = 0;        ///< messages the corrections took
  uint64_t crc_failed = 0;
  uint64_t ignored = 0;     ///< frames on ports without RTCM 3 input
  uint64_t lost = 0;        ///< frames lost to a correction-link outage fault
  uint64_t epochs = 0;      ///< complete base epochs
  int station_id = -1;      ///< reference station (1005/1006/4072.0); -1 none yet
  double age_s = std::numeric_limits<double>::quiet_NaN();  ///< rover time - last base epoch's arrival, s; NaN none
  /// Rover - base distance the RTK filter solved this epoch, m; NaN: no differential solution.
  double baseline_m = std::numeric_limits<double>::quiet_NaN();
  uint64_t baseline_big = 0;   ///< epochs beyond 50 km (the F9P's INF-WARNING "DGNSS baseline big")
  uint64_t long_baseline = 0;  ///< epochs beyond the longest baseline fixed (float only, docs/rtk.md)
};

/// One fault of the fault stage, as the timeline shows it.
struct FaultStatus {
  std::string id;           ///< unique per event, e.g. "3"
  std::string type;         ///< jammer, spoofer, outage, sky_block, satellite, port
  std::string description;  ///< one line: the parameters now
  double start_s = 0.0;     ///< run time it starts, s (as history t_s)
  double end_s = std::numeric_limits<double>::quiet_NaN();  ///< run time it ends, s; NaN: to the end
  bool active = false;
};

/// Everything one epoch gives the producer.
struct EpochStatus {
  const receiver::Fix* fix = nullptr;     ///< the receiver's output (required)
  const world::Truth* truth = nullptr;    ///< truth the epoch ran on (required; valid false: none)
  double run_s = 0.0;       ///< run time of the epoch, s (monotonic; history and faults use it)
  double uptime_s = 0.0;    ///< receiver uptime (NAV-STATUS msss), s
  double ttff_s = 0.0;      ///< time to first fix, s; 0: none yet
};

class StatusProducer {
public:
  /// Epochs of history kept (10 min at 1 Hz, 1 min at 10 Hz).
  static constexpr std::size_t kHistory = 600;

  explicit StatusProducer(StatusSettings settings);

  /// The receiver settings shown (start-up, a reload, a host's CFG-RATE).
  void set_settings(StatusSettings settings) { settings_ = std::move(settings); }
  /// The output ports, in channel order (start-up; allocates).
  void set_ports(std::vector<PortInfo> ports);
  /// Counters of port i (< ports), updated every epoch. No allocation.
  void set_port_counters(std::size_t i, const PortCounters& c) noexcept;
  void set_truth(const TruthCounters& c) noexcept;
  void set_corrections(const CorrectionCounters& c) noexcept { corrections_ = c; }
  /// The faults the fault stage runs (allocates only when the list grows).
  void set_faults(std::span<const FaultStatus> faults);
  /// Record one epoch. No allocation, no exception.
  void on_epoch(const EpochStatus& e) noexcept;

  /// Append the status as one JSON object to out (docs/status.md);
  /// history_max: newest history entries included (0: none). No allocation
  /// once out has the capacity.
  void write_json(std::string& out, std::size_t history_max = kHistory) const noexcept;

  /// The receiver's row of the fleet overview (a view: valid until the next
  /// set_faults). No allocation.
  OverviewRow overview() const noexcept;

  uint64_t epochs() const noexcept { return epochs_; }
  const receiver::Fix& fix() const noexcept { return fix_; }

private:
  /// Counts per monotonic time over the last seconds: a rate.
  class RateMeter {
  public:
    void add(double t_s, double total) noexcept;
    /// Per second over the newest samples spanning up to kWindowS; NaN when < 2 samples.
    double rate() const noexcept;

  private:
    static constexpr std::size_t kSamples = 64;
    static constexpr double kWindowS = 5.0;
    std::array<double, kSamples> t_s_{};
    std::array<double, kSamples> v_{};
    std::size_t n_ = 0, next_ = 0;
  };
  struct HistoryPoint {
    double t_s = 0.0;
    double e_m = 0.0, n_m = 0.0, u_m = 0.0;  ///< NaN without fix or truth
    double h_acc_m = 0.0, v_acc_m = 0.0;     ///< NaN without fix
    int fix_type = 0;
    int num_used = 0;
    int num_tracked = 0;
  };
  struct PortSlot {
    PortInfo info;
    PortCounters counters;
    RateMeter bytes;
  };
  void update_error_stats() noexcept;
  void write_history(class JsonWriter& w, std::size_t history_max) const noexcept;

  StatusSettings settings_;
  receiver::Fix fix_{};
  world::Truth truth_{};
  double run_s_ = 0.0, uptime_s_ = 0.0, ttff_s_ = 0.0;
  uint64_t epochs_ = 0;
  bool error_valid_ = false;
  double e_m_ = 0.0, n_m_ = 0.0, u_m_ = 0.0;
  double cep50_m_ = std::numeric_limits<double>::quiet_NaN();
  double cep95_m_ = std::numeric_limits<double>::quiet_NaN();
  int error_samples_ = 0;

  std::array<HistoryPoint, kHistory> history_{};
  std::size_t history_n_ = 0, history_next_ = 0;
  std::array<double, kHistory> scratch_{};

  TruthCounters truth_counters_;
  CorrectionCounters corrections_;
  RateMeter truth_rate_;
  std::vector<PortSlot> ports_;
  std::vector<FaultStatus> faults_;
};

}  // namespace gnssemu::daemon
