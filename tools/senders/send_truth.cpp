// SPDX-License-Identifier: Apache-2.0
// send_truth: sends binary truth records (docs/truth-protocol.md §Binary
// record) to gnssemud over UDP, paced on an absolute schedule at up to
// 1 kHz, and reports what it sent. Exit 0; 2 on a bad command line; 1 when
// the trajectory file or the socket fails.
#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/common/error.hpp"
#include "tools/senders/trajectory.hpp"
#include "tools/senders/truth_record.hpp"

namespace {

using gnssemu::senders::TruthRecord;
using Clock = std::chrono::steady_clock;

constexpr double kMaxRate_hz = 1000.0;
constexpr double kSecondsPerWeek = 604800.0;

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_signal(int) { g_stop = 1; }

// Command line; ranges are checked by CLI11 (see main).
struct Options {
  std::string host = "127.0.0.1";
  int port = 5500;                  // 1..65535
  std::string vehicle = "ego";      // 1..64 printable characters
  double rate_hz = 10.0;            // records per second, (0, 1000]
  double duration_s = 0.0;          // s; 0: no limit
  long count = 0;                   // records; 0: no limit
  double sim_start_s = 0.0;         // sim_time_s of the first record, s
  std::vector<double> gps_start;    // empty, or week 0..9999 and tow_s [0, 604800)
  bool hex = false;
  std::vector<double> lla, ecef, enu;  // static: one of them, deg/deg/m or m
  gnssemu::senders::CircleParams circle;
  std::string csv_file;
  double speedup = 1.0;             // csv replay speed factor, > 0
};

// One record to send and when, in seconds after the start.
struct Scheduled {
  TruthRecord rec;
  double send_at_s = 0.0;
};

class UdpSender {
public:
  UdpSender(const std::string& host, int port) {
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_DGRAM;
    addrinfo* res = nullptr;
    const int rc = getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &res);
    if (rc != 0) throw gnssemu::Error(host + ": " + gai_strerror(rc));
    fd_ = socket(res->ai_family, res->ai_socktype, res->ai_protocol);
    if (fd_ >= 0) {
      std::copy_n(reinterpret_cast<const char*>(res->ai_addr), res->ai_addrlen, reinterpret_cast<char*>(&addr_));
      addr_len_ = res->ai_addrlen;
    }
    freeaddrinfo(res);
    if (fd_ < 0) throw gnssemu::Error("socket: cannot create a UDP socket");
  }
  ~UdpSender() { close(fd_); }
  UdpSender(const UdpSender&) = delete;
  UdpSender& operator=(const UdpSender&) = delete;

  bool send(const gnssemu::senders::RecordBytes& bytes) const noexcept {
    return sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&addr_), addr_len_) ==
           static_cast<ssize_t>(bytes.size());
  }

private:
  int fd_ = -1;
  sockaddr_storage addr_{};
  socklen_t addr_len_ = 0;
};

void print_hex(const gnssemu::senders::RecordBytes& bytes) {
  for (uint8_t b : bytes) std::printf("%02x", b);
  std::printf("\n");
}

// GPS time start + dt_s, carried into the next week past the end of one.
void set_gps_time(TruthRecord& rec, const std::vector<double>& start, double dt_s) {
  double week = start[0];
  double tow = start[1] + dt_s;
  const double weeks = std::floor(tow / kSecondsPerWeek);
  week += weeks;
  tow -= weeks * kSecondsPerWeek;
  rec.has_gps_time = true;
  rec.gps_week = static_cast<uint16_t>(std::clamp(week, 0.0, 65535.0));
  rec.gps_tow_s = tow;
}

// The k-th record of a rate-paced trajectory (static, circle).
Scheduled paced_record(const Options& o, const std::string& mode, long k) {
  const double t = static_cast<double>(k) / o.rate_hz;
  Scheduled s;
  s.send_at_s = t;
  if (mode == "circle") {
    s.rec = gnssemu::senders::circle_at(o.circle, t);
  } else {
    using gnssemu::senders::PositionFrame;
    const std::vector<double>& p = !o.lla.empty() ? o.lla : !o.ecef.empty() ? o.ecef : o.enu;
    s.rec.position_frame = !o.lla.empty() ? PositionFrame::kLla : !o.ecef.empty() ? PositionFrame::kEcef
                                                                                  : PositionFrame::kEnu;
    s.rec.position = {p[0], p[1], p[2]};
    s.rec.velocity_frame = gnssemu::senders::VelocityFrame::kEnu;  // standing still
  }
  s.rec.sim_time_s = o.sim_start_s + t;
  if (!o.gps_start.empty()) set_gps_time(s.rec, o.gps_start, t);
  return s;
}

// Sleeps until target or a stop signal, in short steps so a signal ends a long wait.
void sleep_until(Clock::time_point target) {
  while (!g_stop) {
    const auto now = Clock::now();
    if (now >= target) return;
    std::this_thread::sleep_until(std::min(target, now + std::chrono::milliseconds(100)));
  }
}

int run(const Options& o, const std::string& mode) {
  std::vector<TruthRecord> rows;
  if (mode == "csv") rows = gnssemu::senders::read_trajectory_csv(o.csv_file);
  std::optional<UdpSender> udp;
  if (!o.hex) udp.emplace(o.host, o.port);
  const long count = o.hex && o.count == 0 && o.duration_s <= 0.0 ? 1 : o.count;

  long sent = 0;
  long errors = 0;
  long late = 0;  // sent more than one period after its time
  double max_late_s = 0.0;
  const double period_s = mode == "csv" ? 0.0 : 1.0 / o.rate_hz;
  const auto t0 = Clock::now();
  for (long k = 0; !g_stop && (count == 0 || k < count); ++k) {
    Scheduled s;
    if (mode == "csv") {
      if (static_cast<std::size_t>(k) >= rows.size()) break;
      s.rec = rows[static_cast<std::size_t>(k)];
      s.send_at_s = (s.rec.sim_time_s - rows.front().sim_time_s) / o.speedup;
      if (!o.gps_start.empty() && !s.rec.has_gps_time) {
        set_gps_time(s.rec, o.gps_start, s.rec.sim_time_s - rows.front().sim_time_s);
      }
    } else {
      s = paced_record(o, mode, k);
    }
    if (o.duration_s > 0.0 && s.send_at_s > o.duration_s) break;
    s.rec.vehicle = o.vehicle;
    gnssemu::senders::RecordBytes bytes{};
    gnssemu::senders::encode_truth_record(s.rec, bytes);  // vehicle checked when parsing options
    if (o.hex) {
      print_hex(bytes);
      ++sent;
      continue;
    }
    const auto target = t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s.send_at_s));
    sleep_until(target);
    if (g_stop) break;
    const double late_s = std::chrono::duration<double>(Clock::now() - target).count();
    max_late_s = std::max(max_late_s, late_s);
    if (period_s > 0.0 && late_s > period_s) ++late;
    if (udp->send(bytes)) {
      ++sent;
    } else {
      ++errors;
    }
  }
  if (!o.hex) {
    const double elapsed_s = std::chrono::duration<double>(Clock::now() - t0).count();
    std::fprintf(stderr,
                 "send_truth: %ld records sent in %.3f s (%.1f /s), %ld send errors, %ld more than one period "
                 "late, latest %.3f ms\n",
                 sent, elapsed_s, elapsed_s > 0.0 ? static_cast<double>(sent) / elapsed_s : 0.0, errors, late,
                 max_late_s * 1e3);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"Send binary truth records to gnssemud over UDP (docs/truth-protocol.md)"};
  app.add_option("--host", o.host, "daemon address")->capture_default_str();
  app.add_option("--port", o.port, "daemon truth port")->check(CLI::Range(1, 65535))->capture_default_str();
  app.add_option("--vehicle", o.vehicle, "vehicle id, 1..64 printable characters")->capture_default_str();
  app.add_option("--rate", o.rate_hz, "records per second, up to 1000 (static, circle)")
      ->check(CLI::Range(1e-3, kMaxRate_hz))
      ->capture_default_str();
  app.add_option("--duration", o.duration_s, "seconds to send; 0: until the trajectory ends or a signal")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--count", o.count, "records to send; 0: no limit")->check(CLI::NonNegativeNumber);
  app.add_option("--sim-start", o.sim_start_s, "sim_time_s of the first record, s");
  app.add_option("--gps-start", o.gps_start, "GPS week and time of week (s) of the first record")
      ->expected(2);
  app.add_flag("--hex", o.hex, "print the records as hex instead of sending them (one unless --count/--duration)");
  app.require_subcommand(1);

  CLI::App* stat = app.add_subcommand("static", "a fixed point, velocity zero");
  auto* lla = stat->add_option("--lla", o.lla, "latitude deg, longitude deg, height m")->expected(3);
  auto* ecef = stat->add_option("--ecef", o.ecef, "ECEF x, y, z m")->expected(3);
  auto* enu = stat->add_option("--enu", o.enu, "east, north, up m from the daemon's origin")->expected(3);
  lla->excludes(ecef)->excludes(enu);
  ecef->excludes(enu);

  CLI::App* circle = app.add_subcommand("circle", "a circle around the daemon's origin, with heading");
  circle->add_option("--radius", o.circle.radius_m, "m")->check(CLI::PositiveNumber)->capture_default_str();
  circle->add_option("--speed", o.circle.speed_m_s, "m/s")->check(CLI::Range(0.0, 1000.0))->capture_default_str();
  circle->add_option("--up", o.circle.up_m, "height above the origin, m")->capture_default_str();

  CLI::App* csv = app.add_subcommand("csv", "replay a CSV file (send_truth.py's columns) at its own pace");
  csv->add_option("file", o.csv_file, "CSV file")->required()->check(CLI::ExistingFile);
  csv->add_option("--speedup", o.speedup, "replay this many times faster")->check(CLI::PositiveNumber);

  try {
    app.parse(argc, argv);
    if (stat->parsed() && o.lla.empty() && o.ecef.empty() && o.enu.empty()) {
      throw CLI::ValidationError("static", "give --lla, --ecef or --enu");
    }
    if (!o.gps_start.empty() &&
        (o.gps_start[0] != std::floor(o.gps_start[0]) || o.gps_start[0] < 0.0 || o.gps_start[0] > 9999.0 ||
         o.gps_start[1] < 0.0 || o.gps_start[1] >= kSecondsPerWeek)) {
      throw CLI::ValidationError("--gps-start", "week an integer 0..9999, time of week in [0, 604800) s");
    }
    TruthRecord probe;
    probe.vehicle = o.vehicle;
    gnssemu::senders::RecordBytes scratch{};
    if (!gnssemu::senders::encode_truth_record(probe, scratch) ||
        std::any_of(o.vehicle.begin(), o.vehicle.end(), [](char c) { return (c >= 0 && c < 0x20) || c == 0x7f; })) {
      throw CLI::ValidationError("--vehicle", "1..64 printable characters");
    }
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  const std::string mode = stat->parsed() ? "static" : circle->parsed() ? "circle" : "csv";
  try {
    return run(o, mode);
  } catch (const gnssemu::Error& e) {
    std::fprintf(stderr, "send_truth: %s\n", e.what());
    return 1;
  }
}
