// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/ubx/device/ubx_front_end.hpp"

#include <algorithm>
#include <cmath>

namespace gnssemu::protocol::ubx {

namespace {

/// The noise floor's rise in a quiet countryside, dB (Fix::noise_rise_db's
/// default): "normal" for the monitor's thresholds.
constexpr double kQuietNoiseRiseDb = 1.0;

/// CW line over the noise floor, dB (0 without one), clamped to [0, 60].
double cw_db(const receiver::Fix& fix) noexcept {
  const double j = fix.cw_jam_to_noise;
  return j > 0.0 && std::isfinite(j) ? std::clamp(10.0 * std::log10(1.0 + j), 0.0, 60.0) : 0.0;
}

}  // namespace

FrontEnd front_end(const receiver::Fix& fix, const EpochInfo& info) noexcept {
  // Heuristic front-end model (docs/ubx.md): the AGC takes gain out as the
  // noise floor rises, the noise level after the AGC creeps up, and the CW
  // jamming indicator scales with the rise. Quiet sky: noise ~ 85, AGC ~ 60 %,
  // jamInd ~ 10 (typical M8 readings in public logs). A CW / narrowband
  // interferer stands out of the noise as a spectral line, so it adds to
  // jamInd beyond its share of the AGC rise.
  const double rise = std::isfinite(fix.noise_rise_db) ? std::clamp(fix.noise_rise_db, 0.0, 60.0) : 0.0;
  const double cw = cw_db(fix);
  FrontEnd f;
  f.noise_per_ms = static_cast<std::uint16_t>(std::lround(82.0 + 3.0 * rise));
  const double agc = 5000.0 - 110.0 * rise;
  f.agc_cnt = static_cast<std::uint16_t>(std::lround(std::clamp(agc, 0.0, 8191.0)));
  f.jam_ind = static_cast<std::uint8_t>(std::lround(std::clamp(7.0 + 5.0 * rise + 4.0 * cw, 0.0, 255.0)));
  // The AGC holds the ADC level until its gain runs out (agcCnt 0 at ~45 dB
  // of rise); beyond that the signal magnitude grows with the interference.
  const double beyond_agc_db = std::max(0.0, -agc / 110.0);
  f.mag_iq = static_cast<std::uint8_t>(std::lround(std::min(255.0, 128.0 * std::pow(10.0, beyond_agc_db / 20.0))));
  // Antenna supervisor: SHORT switches the supply off (aPower 0), OPEN keeps it on.
  const bool antenna_ok = fix.antenna_status == receiver::AntennaStatus::kOk;
  f.ant_status = fix.antenna_status == receiver::AntennaStatus::kShort  ? 3
                 : fix.antenna_status == receiver::AntennaStatus::kOpen ? 4
                                                                        : 2;
  f.ant_power = fix.antenna_status == receiver::AntennaStatus::kShort ? 0 : 1;
  // The monitor compares the spectrum with a reference taken at a good fix:
  // unknown while disabled, before the first fix and without an antenna
  // (u-blox 9 integration manuals, "Jamming/interference monitor").
  if (!info.itfm.enabled || info.ttff_ms == 0 || !antenna_ok) return f;
  // Broadband: the noise floor above its quiet level (1 dB, Fix::noise_rise_db)
  // beyond bbThreshold; CW: the line beyond cwThreshold (CFG-ITFM, dB above normal).
  const double bb_excess_db = rise - kQuietNoiseRiseDb;
  const bool visible = bb_excess_db >= info.itfm.bb_threshold_db || cw >= info.itfm.cw_threshold_db;
  f.jamming_state = !visible                                 ? JammingState::kOk
                    : reports_fix_ok(fix, info.reported_fix) ? JammingState::kWarning
                                                             : JammingState::kCritical;
  return f;
}

std::uint8_t spoof_det_state(const receiver::Fix& fix) noexcept {
  return static_cast<std::uint8_t>(std::min<unsigned>(fix.spoof_det_state, 3));
}

}  // namespace gnssemu::protocol::ubx
