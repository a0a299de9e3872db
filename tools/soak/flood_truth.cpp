// SPDX-License-Identifier: Apache-2.0
// flood_truth: floods gnssemud's truth port with good and bad datagrams at
// up to millions of packets per second (docs/robustness.md §Flood), for
// tools/soak/soak.py flood. Good packets are vehicle "ego" on a circle
// around the daemon's origin (binary records and JSON, sim time strictly
// increasing); bad ones cycle through every drop reason a single packet
// can show, plus other vehicles (the first few tracked, then "too many").
// Prints what it sent per kind and the rate it reached. Exit 0; 2 on a bad
// command line; 1 when the socket fails.
#include <netinet/in.h>
#include <arpa/inet.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "tools/senders/trajectory.hpp"
#include "tools/senders/truth_record.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using gnssemu::senders::RecordBytes;
using gnssemu::senders::TruthRecord;

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_signal(int) { g_stop = 1; }

constexpr std::size_t kBatch = 256;       // datagrams per sendmmsg
constexpr double kTick_s = 0.001;         // pacing step

struct Options {
  std::string host = "127.0.0.1";  // IPv4 address
  int port = 5500;                 // 1..65535
  double rate_pps = 100000.0;      // packets per second, > 0
  double duration_s = 10.0;        // s, > 0
  double good_fraction = 0.5;      // [0, 1]
  double json_fraction = 0.5;      // of the good ones, [0, 1]
  gnssemu::senders::CircleParams circle{50.0, 10.0, 0.0};
};

// The bad kinds, each named after the drop reason the daemon should give.
enum Kind : std::size_t {
  kGoodBinary, kGoodJson,
  kBadMagic, kBadSize, kUnknownVersion, kBadFlags, kNonFinite, kLatitudeRange, kHeightRange, kSpeedRange,
  kMalformedJson, kNotObject, kMissingVersion, kDuplicateKey, kTooLarge, kSimTimeBackwards, kBadVehicleId,
  kOtherVehicles, kKinds
};
constexpr std::array<const char*, kKinds> kKindNames = {
    "good binary", "good json", "bad_magic", "bad_size", "unknown_version", "bad_flags", "non_finite",
    "latitude_range", "height_range", "speed_range", "malformed_json", "not_an_object", "missing_version",
    "duplicate_key", "too_large", "sim_time_backwards", "bad_vehicle_id", "other vehicles"};
constexpr std::size_t kFirstBad = kBadMagic;

std::string as_string(const RecordBytes& r) { return std::string(reinterpret_cast<const char*>(r.data()), r.size()); }

RecordBytes record(const TruthRecord& rec) {
  RecordBytes out{};
  gnssemu::senders::encode_truth_record(rec, out);
  return out;
}

std::string good_json(const TruthRecord& r) {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "{\"version\":1,\"vehicle\":\"ego\",\"sim_time_s\":%.9f,\"enu\":{\"e_m\":%.4f,\"n_m\":%.4f,\"u_m\":%.4f},"
                "\"vel_enu\":{\"e_m_s\":%.4f,\"n_m_s\":%.4f,\"u_m_s\":%.4f}}",
                r.sim_time_s, r.position[0], r.position[1], r.position[2], r.vel_m_s[0], r.vel_m_s[1], r.vel_m_s[2]);
  return buf;
}

// One bad datagram of kind k; n numbers it (other vehicles' ids).
std::string bad(std::size_t k, uint64_t n, const TruthRecord& now) {
  TruthRecord r = now;
  switch (k) {
    case kBadMagic: { std::string s = as_string(record(r)); s[1] = 'X'; return s; }
    case kBadSize: return as_string(record(r)).substr(0, 159);
    case kUnknownVersion: { std::string s = as_string(record(r)); s[4] = 2; return s; }
    case kBadFlags: { std::string s = as_string(record(r)); s[5] = static_cast<char>(0xC3); return s; }
    case kNonFinite: r.position[0] = std::nan(""); return as_string(record(r));
    case kLatitudeRange:
      r.position_frame = gnssemu::senders::PositionFrame::kLla;
      r.position = {91.0, 2.0, 100.0};
      return as_string(record(r));
    case kHeightRange: r.position[2] = 2.0e5; return as_string(record(r));
    case kSpeedRange: r.vel_m_s = {2000.0, 0.0, 0.0}; return as_string(record(r));
    case kMalformedJson: return "{\"version\":1,\"vehicle\":\"ego\",\"sim_time_s\":";
    case kNotObject: return "[1,2,3]";
    case kMissingVersion: return "{\"vehicle\":\"ego\",\"sim_time_s\":1,\"enu\":{\"e_m\":0,\"n_m\":0,\"u_m\":0}}";
    case kDuplicateKey:
      return "{\"version\":1,\"vehicle\":\"ego\",\"sim_time_s\":1,\"sim_time_s\":2,\"enu\":{\"e_m\":0,\"n_m\":0,\"u_m\":0}}";
    case kTooLarge: return std::string(4097, ' ');
    case kSimTimeBackwards: r.sim_time_s = 0.0; return as_string(record(r));
    case kBadVehicleId: { std::string s = as_string(record(r)); s[8] = '\x01'; return s; }
    case kOtherVehicles: {
      const std::string id = "v" + std::to_string(n % 1000);
      r.vehicle = id;
      return as_string(record(r));
    }
    default: break;
  }
  return {};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"flood_truth: floods gnssemud's truth port with good and bad packets (docs/robustness.md)"};
  Options o;
  app.add_option("--host", o.host, "daemon IPv4 address")->capture_default_str();
  app.add_option("--port", o.port, "daemon truth port")->check(CLI::Range(1, 65535))->capture_default_str();
  app.add_option("--rate", o.rate_pps, "packets per second")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--duration", o.duration_s, "seconds")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--good-fraction", o.good_fraction, "fraction of good packets")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  app.add_option("--json-fraction", o.json_fraction, "fraction of the good packets sent as JSON")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  app.add_option("--radius", o.circle.radius_m, "circle radius around the origin, m")
      ->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--speed", o.circle.speed_m_s, "speed on the circle, m/s")->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }

  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(o.port));
  if (inet_pton(AF_INET, o.host.c_str(), &addr.sin_addr) != 1) {
    std::fprintf(stderr, "flood_truth: --host %s is not an IPv4 address\n", o.host.c_str());
    return 2;
  }
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0 || connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    std::perror("flood_truth: socket");
    return 1;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);

  std::array<uint64_t, kKinds> sent{};
  uint64_t planned = 0, failed = 0, good_n = 0, bad_n = 0;
  double good_acc = 0.0, json_acc = 0.0;
  std::vector<std::string> payloads(kBatch);
  std::vector<iovec> iov(kBatch);
  std::vector<mmsghdr> msgs(kBatch);
  const auto t0 = Clock::now();
  const auto total = static_cast<uint64_t>(std::llround(o.rate_pps * o.duration_s));
  const double good_rate = std::max(o.rate_pps * o.good_fraction, 1.0);
  auto next = t0;
  while (planned < total && g_stop == 0) {
    const double elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
    const auto due = std::min<uint64_t>(total, static_cast<uint64_t>(elapsed * o.rate_pps) + 1);
    while (planned < due) {
      std::size_t n = 0;
      for (; n < kBatch && planned < due; ++n, ++planned) {
        // Good packets on their own schedule: strictly increasing sim time.
        const TruthRecord now = gnssemu::senders::circle_at(o.circle, static_cast<double>(good_n) / good_rate);
        TruthRecord ego = now;
        ego.vehicle = "ego";
        ego.sim_time_s = 1.0 + static_cast<double>(good_n) / good_rate;
        good_acc += o.good_fraction;
        std::size_t kind;
        if (good_acc >= 1.0) {
          good_acc -= 1.0;
          json_acc += o.json_fraction;
          kind = json_acc >= 1.0 ? kGoodJson : kGoodBinary;
          if (kind == kGoodJson) json_acc -= 1.0;
          payloads[n] = kind == kGoodJson ? good_json(ego) : as_string(record(ego));
          ++good_n;
        } else {
          kind = kFirstBad + bad_n % (kKinds - kFirstBad);
          payloads[n] = bad(kind, bad_n / (kKinds - kFirstBad), ego);
          ++bad_n;
        }
        ++sent[kind];
        iov[n] = {payloads[n].data(), payloads[n].size()};
        msgs[n] = {};
        msgs[n].msg_hdr.msg_iov = &iov[n];
        msgs[n].msg_hdr.msg_iovlen = 1;
      }
      std::size_t done = 0;
      while (done < n) {
        const int r = sendmmsg(fd, msgs.data() + done, static_cast<unsigned>(n - done), 0);
        if (r <= 0) {  // ECONNREFUSED while the daemon is not up, ENOBUFS: counted, not retried
          failed += n - done;
          break;
        }
        done += static_cast<std::size_t>(r);
      }
    }
    next += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kTick_s));
    std::this_thread::sleep_until(next);
  }
  const double took_s = std::chrono::duration<double>(Clock::now() - t0).count();
  close(fd);

  std::printf("flood_truth: %llu packets in %.2f s (%.0f/s, asked %.0f/s), %llu not sent\n",
              static_cast<unsigned long long>(planned), took_s, static_cast<double>(planned) / took_s, o.rate_pps,
              static_cast<unsigned long long>(failed));
  for (std::size_t k = 0; k < kKinds; ++k) {
    std::printf("flood_truth:   %-20s %llu\n", kKindNames[k], static_cast<unsigned long long>(sent[k]));
  }
  return 0;
}
