// SPDX-License-Identifier: Apache-2.0
// Truth datagrams (JSON and the binary record) through parse_truth_packet
// and, when accepted, a truth router. Oracles: a drop has a reason and a
// detail; an accepted sample obeys docs/truth-protocol.md §Validation; the
// router never yields a non-finite truth.
#include <cmath>
#include <string>

#include "core/common/constants.hpp"
#include "daemon/truth/truth_packet.hpp"
#include "daemon/truth/truth_router.hpp"
#include "fuzz_support.hpp"

namespace {

using namespace gnssemu;
using namespace gnssemu::daemon;

// Paris, as config/default.toml: ENU positions are relative to it.
const geo::LocalFrame kFrame(Lla{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0});

void check_sample(const TruthSample& s) {
  fuzz::expect(!s.vehicle.empty() && s.vehicle.size() <= kMaxVehicleIdChars, "vehicle id length");
  for (unsigned char c : s.vehicle) fuzz::expect(c >= 0x20 && c != 0x7f, "vehicle id printable");
  fuzz::expect(std::isfinite(s.sim_time_s), "sim_time_s finite");
  fuzz::expect(s.pos_m.finite(), "position finite");
  fuzz::expect(std::abs(s.lla.lat_rad) <= kPi / 2.0 + 1e-12, "latitude in range");
  fuzz::expect(std::abs(s.lla.lon_rad) <= kPi + 1e-12, "longitude in range");
  fuzz::expect(s.lla.height_m >= kMinHeight_m && s.lla.height_m <= kMaxHeight_m, "height in range");
  if (s.vel_m_s) {
    fuzz::expect(s.vel_m_s->finite(), "velocity finite");
    fuzz::expect(s.vel_m_s->norm() <= kMaxSpeed_m_s * (1.0 + 1e-9), "speed in range");
  }
  if (s.gps_time) {
    fuzz::expect(s.gps_time->week() >= 0 && s.gps_time->week() <= 9999, "gps week in range");
    fuzz::expect(s.gps_time->tow_s() >= 0.0 && s.gps_time->tow_s() < kSecondsPerWeek, "gps tow in range");
  }
  if (s.attitude) {
    fuzz::expect(std::isfinite(s.attitude->roll_rad) && std::isfinite(s.attitude->pitch_rad) &&
                     std::isfinite(s.attitude->yaw_rad),
                 "attitude finite");
  }
}

void check_truth(const world::Truth& t) {
  if (!t.valid) return;
  fuzz::expect(t.pos_m.finite() && t.vel_m_s.finite(), "router truth finite");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view datagram(reinterpret_cast<const char*>(data), size);
  const ParseResult r = parse_truth_packet(datagram, kFrame);
  if (!r.ok) {
    fuzz::expect(r.reason < DropReason::kCount, "drop reason in range");
    fuzz::expect(!r.detail.empty(), "drop detail given");
    fuzz::expect(std::string(drop_reason_name(r.reason)) != "unknown", "drop reason named");
    return 0;
  }
  check_sample(r.sample);

  // The sample in both time modes, again 0.1 s later, and the truth around it.
  for (const config::TimeMode mode : {config::TimeMode::kRealtime, config::TimeMode::kLockstep}) {
    TruthRouter router(TrackParams{2.0, 0.5}, mode);
    const time::GpsTime clock(2190, 522000.0);
    const TruthRouter::Ingest first = router.ingest(r.sample, clock, 10.0);
    fuzz::expect(first.accepted, "first sample of a vehicle accepted");
    TruthSample later = r.sample;
    later.sim_time_s = r.sample.sim_time_s + 0.1;
    if (later.gps_time) later.gps_time = *later.gps_time + 0.1;
    router.ingest(later, clock + 0.1, 10.1);
    for (const double dt : {-1.0, 0.0, 0.05, 0.3, 1.0, 5.0}) {
      check_truth(router.truth_at(first.stamp + dt, 10.0 + dt));
    }
  }
  return 0;
}
