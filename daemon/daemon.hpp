// SPDX-License-Identifier: Apache-2.0
#pragma once
// Daemon: the event loop of gnssemud — truth datagrams in, epochs on the
// schedule, sentences out to every port (docs/daemon.md). One thread. Its
// vehicles and receivers (Rig) share one sky per epoch: each vehicle's truth
// comes from the one truth socket, each receiver steps its own pipeline on
// the shared sky at its antenna (docs/architecture.md §Fleet).
#include <array>
#include <chrono>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <functional>
#include <string>
#include <vector>

#include <boost/asio.hpp>

#include "config/config.hpp"
#include "config/scenario_file.hpp"
#include "core/geo/local_frame.hpp"
#include "core/orbit/constellation.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/scene/scene.hpp"
#include "daemon/control/control_commands.hpp"
#include "daemon/control/control_server.hpp"
#include "core/world/sky/shared_sky.hpp"
#include "daemon/truth/demo_trajectory.hpp"
#include "daemon/truth/drop_stats.hpp"
#include "daemon/fault_log.hpp"
#include "config/setup/base_station.hpp"
#include "daemon/ports/ntrip_caster.hpp"
#include "daemon/ports/output_port.hpp"
#include "daemon/ports/port_channel.hpp"
#include "daemon/reload_plan.hpp"
#include "daemon/rig.hpp"
#include "daemon/run_plan.hpp"
#include "daemon/service/signals.hpp"
#include "daemon/status/status_line.hpp"
#include "daemon/service/systemd_notify.hpp"
#include "daemon/truth/truth_allow.hpp"
#include "daemon/status/status_producer.hpp"
#include "daemon/status/status_server.hpp"
#include "daemon/truth/time_mapping.hpp"
#include "daemon/truth/fleet_router.hpp"
#include "daemon/truth/truth_router.hpp"

namespace gnssemu::daemon {

namespace asio = boost::asio;

/// Truth datagrams taken per wake-up of the truth socket (a port's input
/// takes 1 kB per wake-up within its InputBudget).
inline constexpr int kTruthPerWake = 64;
/// A vehicle's truth jumps are logged at most once per this period, s (the rest counted).
inline constexpr double kJumpLogPeriodS = 5.0;

class Daemon final : private ControlTarget {
public:
  /// nav: the configured nav data as read (kept to re-date the constellation
  /// for a lockstep simulator's GPS time). Builds receiver and encoders;
  /// throws gnssemu::Error on a bad config or a start the data cannot serve.
  Daemon(asio::io_context& io, const config::Config& cfg, const orbit::NavData& nav, const RunPlan& plan);
  ~Daemon();

  /// Run the events of a scenario file (gnssemud --scenario), time zero at
  /// the first epoch (lockstep: the simulator's first), each on the
  /// receivers its target names (none: all). Before start(); throws
  /// gnssemu::Error naming source for a port event without its output or a
  /// target that names no receiver.
  void set_scenario(std::vector<config::ScenarioEvent> events, const std::string& source);

  /// Open ports and the truth socket, print where NMEA goes, start the
  /// schedule and signal handling. Throws gnssemu::Error.
  void start();

  /// Loads the configuration anew for SIGHUP (the same file and command-line
  /// overrides as at start); throws gnssemu::Error naming file:line.
  using Reloader = std::function<config::Config()>;
  void set_reloader(Reloader r) { reloader_ = std::move(r); }
  /// SIGHUP: load, validate, apply what can change live (ReloadPlan); a bad
  /// configuration is logged and the running one kept. Never throws.
  void reload() noexcept;
  /// The status line (logged every minute and on SIGUSR1/SIGUSR2): the
  /// receiver's; a fleet's: how many vehicles have which fix (status_lines
  /// has one per vehicle).
  std::string status_line();
  /// One status line per vehicle ("v0: fix 3D, 9 sats; ..."); the single
  /// form: its one line.
  std::vector<std::string> status_lines();

private:
  using Clock = std::chrono::steady_clock;

  double now_s() const noexcept;
  time::GpsTime realtime_clock_gps() noexcept;
  /// Per vehicle: its routing state beyond the truth router's.
  struct VehicleState {
    DropStats drops;              ///< drops of its packets the router refused
    TruthAllowList allow;         ///< its [[vehicle]] allow (empty: any sender)
    uint64_t packets_ok = 0;
    uint64_t jumps = 0;           ///< accepted packets that jumped (VehicleTrack::Step::jump)
    uint64_t jumps_logged = 0;    ///< of which logged (one line per vehicle per kJumpLogPeriodS)
    double jump_logged_s = -1e300;  ///< monotonic time of the last jump line
    bool ever_driven = false;     ///< a simulator drove it: the demo is off for good
    world::Truth truth;           ///< its reference point, this epoch
    StatusLine line;              ///< its status line (rates since the last one)
  };
  /// Each vehicle's allow list from cfg_.vehicles (start-up and reload).
  void refresh_vehicle_allows();
  /// A fresh receiver in a fresh world (start-up, or GPS time going back),
  /// started as start says, with the device's CFG-NAV5 applied.
  void restart_receiver(Rig& rig, receiver::StartMode start);
  /// The device's CFG-NAV5 (dynModel, static hold) and GNSS selection into the receiver.
  /// [base]: its station and NTRIP caster (setup; throws gnssemu::Error).
  void start_base();
  void apply_chip_settings(Rig& rig);
  /// A host on channel src of rig changed the device: follow its reset, epoch
  /// period and the other ports' line settings.
  void on_host_input(Rig& rig, std::size_t src, const protocol::ubx::InputResult& result);
  void arm_timer();
  void on_timer(const boost::system::error_code& ec);
  void receive();
  /// Up to kTruthPerWake more datagrams the kernel already holds.
  void drain_truth();
  void on_datagram(std::size_t n);
  /// Count the jump of vehicle id (routed to vehicles_[v]; the single form
  /// tracks several ids in one) and log it, one line per kJumpLogPeriodS.
  void note_jump(std::size_t v, const std::string& id, const VehicleTrack::Step& step, double now);
  void lockstep_advance(const time::GpsTime& stamp);
  /// Lockstep: the next epoch is the first of the rate's grid at or after t.
  void lock_grid_from(const time::GpsTime& t) noexcept;
  /// Lockstep: the next epoch n (>= 1, whole) epochs of the grid on.
  void lock_step(double n) noexcept;
  void align_to_packet_time(const time::GpsTime& stamp);
  /// Epoch t for every receiver: each vehicle's truth (its track; the
  /// fallback when it has no driver or fallback_only), the shared sky at
  /// every antenna, then each rig. demo_elapsed_s: the demo circle's time.
  /// send false: the rigs' ports get the epoch later, from send_epochs().
  void emit_epoch(const time::GpsTime& t, double demo_elapsed_s, bool fallback_only, bool send = true);
  void send_epochs() noexcept;
  /// One rig's part of epoch t (the sky and rig.truth are set), run time run_s.
  void emit_rig_epoch(Rig& rig, const time::GpsTime& t, double run_s, bool send);
  static void send_rig_epoch(Rig& rig) noexcept;
  static std::span<const faults::FaultStatus> link_status(const Rig& rig) noexcept;
  /// The emulated chip's clock (NAV-STATUS msss, ttff), s: the wall clock in
  /// realtime; in lockstep epoch t's GPS time from chip_origin_, so uptime
  /// and ttff advance with the simulation as iTOW does, whatever its speed.
  double chip_clock_s(const time::GpsTime& t) const noexcept;
  world::Truth fallback_truth(std::size_t v, const time::GpsTime& t, double demo_elapsed_s) const noexcept;
  /// The demo circle drives vehicle v (no simulator ever did, demo on):
  /// what fallback_truth, the status line and the status page all say.
  bool demo_drives(std::size_t v) const noexcept { return !vehicles_[v].ever_driven && cfg_.demo.enabled; }
  /// Logs when the epoch clock leaves or re-enters what the constellation serves.
  void note_coverage(const time::GpsTime& t) noexcept;
  /// Lockstep: the simulator's GPS time t lies outside the constellation:
  /// date it anew for t (auto/relabel/almanac) or say why there is no fix.
  void redate_constellation(const time::GpsTime& t);
  /// The device's epoch period may have changed (CFG-RATE, a reset or a
  /// configuration load from channel src): run at it.
  void on_nav_period(Rig& rig, std::size_t src);
  /// The first receiver: the single-vehicle form's one.
  Rig& rig() noexcept { return *rigs_.front(); }
  const Rig& rig() const noexcept { return *rigs_.front(); }
  /// "ego/gps1: " before a rig's log lines in a fleet; "" in the single form.
  std::string who(const Rig& rig) const { return fleet_ ? rig.label() + ": " : std::string(); }
  void shutdown();
  void on_signal(SignalAction action, int sig);
  /// Once a second: drop summaries that are due, the status line every minute.
  void arm_tick();
  void on_tick();
  /// A host reconfigured channel src's port (CFG-PRT, $PUBX,41, a config
  /// load): say what it sends now.
  void log_port_change(Rig& rig, std::size_t src);
  /// Truth from a vehicle that is not driving the receiver: say so once.
  void note_other_vehicle(const std::string& id);
  /// Wire port to output i of rig's device (replacing what was there).
  void open_channel(Rig& rig, std::size_t i, std::unique_ptr<OutputPort> port);
  /// Power rig's chip on at chip clock power_on_s and wire ports (one per
  /// output, opened) to its outputs (start-up, a vehicle a reload adds).
  void wire_rig(Rig& rig, std::vector<std::unique_ptr<OutputPort>> ports, double power_on_s);
  /// "gnssemud: ego/gps1: NMEA on pty ..." on stdout, one line per output.
  void print_ports(const Rig& rig) const;
  /// Each output's counters in the log (the exit summary; a removed vehicle's).
  void log_port_summary(const Rig& rig) const;
  // SIGHUP reload (daemon_reload.cpp).
  /// A reload's change to one running receiver, built before anything running is touched.
  struct RigUpdate {
    Rig* rig = nullptr;
    config::Config cfg;  ///< its configuration in the loaded file (on the running top level)
    ReloadPlan plan;     ///< its live part is applied
    bool lever_arm = false;
    Vec3 lever_arm_m;
    std::unique_ptr<pipeline::Pipeline> receiver;        ///< plan.receiver or plan.scene: the new one
    std::vector<std::unique_ptr<OutputPort>> reopened;  ///< one per plan.reopen, open
  };
  /// Builds u's receiver and opens its reopened ports (scene: the one it will
  /// run in). Throws; touches nothing running.
  void prepare_rig_update(RigUpdate& u, const scene::Scene* scene);
  /// Applies a prepared update to its rig (the scene already swapped).
  void apply_rig_update(RigUpdate& u);
  /// The fleet form's reload: vehicles added, removed, kept or changed
  /// (FleetReloadPlan); top: the top level's plan, whose receiver and scene
  /// parts a fleet takes per vehicle or at a restart. Throws before anything
  /// running is touched; returns the summary for the log.
  std::string reload_fleet(const config::Config& loaded, ReloadPlan& top);
  // Scenario and control socket (daemon_control.cpp).
  /// A fresh fault stage with the scenario's events, time zero at the next epoch.
  void restart_scenario();
  /// The events of events that act on rig (their target names it, or none).
  static std::vector<faults::FaultEvent> events_for(const Rig& rig, const std::vector<config::ScenarioEvent>& events);
  /// Throws gnssemu::Error (source:line) for an event whose target names no
  /// receiver or whose port event names an output a targeted rig lacks.
  void check_targets(const std::vector<config::ScenarioEvent>& events, const std::string& source) const;
  void start_control_socket();
  void write_status(std::string& out, std::string_view target) override;
  std::vector<std::string> inject(std::string_view scenario, const std::string& source,
                                  std::string_view target) override;
  std::size_t clear(std::string_view target) override;
  /// The rigs target names ("" every one); throws gnssemu::Error when none.
  std::vector<Rig*> rigs_of(std::string_view target) const;
  std::size_t fault_count() const override;
  /// The fault list for the status (at most once a second of run time).
  void record_faults(Rig& rig, double run_s);
  /// Log the fault events that started or ended at this epoch (status: the stage's, after it).
  void log_fault_transitions(Rig& rig, std::span<const faults::FaultStatus> status, double run_s);
  /// Log the end of every active fault event before the stage drops them (why: "cleared", ...).
  void log_fault_ends(Rig& rig, std::string_view why);
  /// A reload's check of the port events against loaded's [[output]] list
  /// (docs/daemon.md §Reload): throws gnssemu::Error for a --scenario event
  /// whose output the file no longer has at its index; returns a warning per
  /// injected event in that case.
  std::vector<std::string> check_reload_port_events(const config::Config& loaded);
  /// Run time of epoch t, s: from the first epoch (the status history's and the fault log's clock).
  double run_time_s(const time::GpsTime& t) noexcept;
  // Status page (daemon_status.cpp).
  void start_status_page();
  /// The status page's settings and port list from the running state (after
  /// start, a reload, a rate change).
  void refresh_status_setup();
  void record_status(Rig& rig, double run_s, const receiver::Fix& fix) noexcept;
  /// Every rig's port counters after the epoch's sends, then the status page's snapshot.
  void publish_status() noexcept;
  static void record_port_counters(Rig& rig) noexcept;

  asio::io_context& io_;
  config::Config cfg_;
  orbit::NavData raw_nav_;               ///< the nav files as read
  orbit::Constellation constellation_;   ///< the satellites for the run's dates
  orbit::EphemerisStore store_;
  geo::LocalFrame frame_;
  std::unique_ptr<scene::Scene> scene_;  ///< buildings ([scene]); outlives the rigs' receivers
  DemoTrajectory demo_;
  bool fleet_;                  ///< [[vehicle]] or [fleet]: packets route by id
  FleetRouter router_;
  std::vector<VehicleState> vehicles_;
  DropStats drops_;             ///< every drop (parse, allow, unknown vehicle, a router's)
  time::GpsTime start_;         ///< GPS time of elapsed 0 (realtime) / the first epoch (lockstep)
  double period_s_;
  double output_delay_s_;       ///< realtime: epoch to first byte on the wire, s

  /// The emulated receivers, vehicle by vehicle in config order.
  std::vector<std::unique_ptr<Rig>> rigs_;
  double rate_hz_;              // epoch rate now (CFG-RATE may change it)
  world::SharedSky sky_;        ///< every satellite's state this epoch, read by every rig
  std::vector<Ecef> antennas_;  ///< this epoch's antenna positions (capacity: one per rig)
  double sched_base_s_ = 0.0;   // realtime: elapsed time of index 0 of the current rate
  /// Realtime: the epoch is computed this long before its output time, then
  /// every port sends at that time (twice the slowest recent epoch's compute
  /// time + 5 ms, at most output_delay_s), so a fleet's last receiver is not
  /// later on the wire than its first.
  double compute_lead_s_ = 0.0;
  double compute_max_s_ = 0.0;  ///< slowest recent epoch computation, decaying 3 % an epoch
  bool send_pending_ = false;   // realtime: computed, waiting for its output time

  std::unique_ptr<StatusServer> status_server_;  ///< null: [status] port = 0
  std::optional<time::GpsTime> status_first_t_;  ///< run time 0 of the status history
  std::vector<config::ScenarioEvent> scenario_;  ///< --scenario (time zero: the first epoch)
  std::string scenario_source_;
  std::unique_ptr<ControlServer> control_;       ///< null: no [control] socket
  double last_run_s_ = 0.0;                      ///< run time of the last epoch, s

  asio::steady_timer timer_;
  asio::steady_timer retry_timer_;  // back-off after a socket error
  asio::ip::udp::socket socket_;
  asio::ip::udp::endpoint peer_;
  std::unique_ptr<SignalDispatch> signals_;
  std::unique_ptr<config::BaseStation> base_;  ///< [base]: null without one
  std::unique_ptr<NtripCaster> caster_;        ///< [base.ntrip]: null without one
  std::string base_bytes_;                     ///< the base's epoch, reused
  /// [[base.output]]: ports carrying the base's RTCM stream.
  std::vector<std::unique_ptr<OutputPort>> base_ports_;
  SystemdNotify notify_;
  TruthAllowList allow_;
  asio::steady_timer tick_timer_;
  Reloader reloader_;
  double last_status_s_ = 0.0;
  std::vector<std::string> noted_vehicles_;  ///< non-driving vehicles already logged
  bool stopped_ = false;
  std::array<char, 65536> rx_buf_{};

  Clock::time_point power_on_;  // realtime: receiver power-on (process start): uptime (msss) and ttff count from here
  Clock::time_point t0_;
  int64_t index_ = 0;           // realtime: epoch index since t0
  bool served_ = true;          // the last epoch had the constellation
  time::GpsTime lock_next_;     // lockstep: GPS time of the next epoch: (lock_week_, lock_k_ / rate_hz_)
  int32_t lock_week_ = 0;
  double lock_k_ = 0.0;         // lockstep: index of the next epoch in lock_week_ (whole; may pass the week's end)
  double line_s_ = 0.0;         // lockstep: simulation time the serial lines have run, s (their byte budget's clock)
  time::GpsTime chip_origin_;   // lockstep: GPS time of the chip's power-on (start, then the first packet's epoch)
  time::GpsTime last_epoch_t_;  // GPS time of the last epoch emitted
  uint64_t epochs_ = 0;
  uint64_t epochs_skipped_ = 0;
  uint64_t packets_ok_ = 0;
  bool warned_gps_offset_ = false;
  bool gps_aligned_ = false;
};

}  // namespace gnssemu::daemon
