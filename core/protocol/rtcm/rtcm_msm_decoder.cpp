// SPDX-License-Identifier: Apache-2.0
// MSM4-7 into the pending epoch of a Decoder (RTCM 10403.3 §3.5.6; the
// field layout is rtcm_msm_fields.hpp, the reconstruction rtk-raw.md §2.4).
#include <array>
#include <bit>
#include <cmath>

#include "core/protocol/rtcm/rtcm_bits.hpp"
#include "core/protocol/rtcm/rtcm_decoder.hpp"
#include "core/protocol/rtcm/rtcm_msm_fields.hpp"

namespace gnssemu::protocol::rtcm {

namespace {

constexpr double kSecondsPerWeek = 604800.0;
constexpr double kSecondsPerDay = 86400.0;
constexpr double kBdtMinusGpst_s = -14.0;
constexpr double kMoscowMinusUtc_s = 10800.0;
constexpr std::uint32_t kRoughInvalid = 255;  ///< DF397
constexpr std::int64_t kRoughRateInvalid = -8192;  ///< DF399
/// Epochs of one base differ by whole epochs; messages of one epoch agree to the millisecond.
constexpr double kSameEpoch_s = 0.5e-3;

std::optional<GnssSystem> msm_system(int number) noexcept {
  switch (number / 10) {
    case 107: return GnssSystem::kGps;
    case 108: return GnssSystem::kGlonass;
    case 109: return GnssSystem::kGalileo;
    case 110: return GnssSystem::kSbas;
    case 111: return GnssSystem::kQzss;
    case 112: return GnssSystem::kBeiDou;
    default: return std::nullopt;
  }
}

/// The satellite of MSM satellite id (1..64) of sys (the inverse of msm_satellite_id).
SatId msm_satellite(GnssSystem sys, int id) noexcept {
  if (sys == GnssSystem::kSbas) return SatId(sys, id + 19);  // id 1 = PRN 120 = S20
  return SatId(sys, id);                                    // QZSS id 1 = PRN 193 = J01
}

std::optional<SignalId> msm_signal(GnssSystem sys, int sig) noexcept {
  for (const SignalInfo& s : kSignals)
    if (s.system == sys && s.rtcm_msm_sig == sig) return s.id;
  return std::nullopt;
}

}  // namespace

std::optional<time::GpsTime> msm_epoch_time(GnssSystem sys, std::uint32_t field, time::GpsTime now,
                                            int leap_seconds) noexcept {
  double tow_s = 0.0;
  double period_s = kSecondsPerWeek;
  if (sys == GnssSystem::kGlonass) {
    const std::uint32_t dow = field >> 27;
    const std::uint32_t tod_ms = field & 0x7FFFFFFu;
    if (tod_ms >= 86401000u) return std::nullopt;
    tow_s = tod_ms * 1e-3 - kMoscowMinusUtc_s + leap_seconds;
    if (dow < 7) {
      tow_s += dow * kSecondsPerDay;
    } else {
      period_s = kSecondsPerDay;  // 7: day not given, the nearest day
    }
  } else {
    if (field >= 604800000u) return std::nullopt;
    tow_s = field * 1e-3;
    if (sys == GnssSystem::kBeiDou) tow_s -= kBdtMinusGpst_s;
  }
  const double k = std::floor((tow_s - now.tow_s()) / period_s + 0.5);
  tow_s -= k * period_s;
  return time::GpsTime::make(now.week(), tow_s);
}

bool Decoder::decode_msm(std::span<const std::uint8_t> payload, int number, time::GpsTime now, int leap_seconds,
                         DecodeResult& res) noexcept {
  const GnssSystem sys = *msm_system(number);
  const MsmFields& f = msm_fields(number % 10);
  BitReader r(payload);
  r.u(24);
  const auto epoch_field = static_cast<std::uint32_t>(r.u(30));
  const bool more = r.u(1) != 0;
  r.u(3 + 7 + 2 + 2 + 1 + 3);
  const std::uint64_t sat_mask = r.u(64);
  const auto sig_mask = static_cast<std::uint32_t>(r.u(32));
  const int nsat = std::popcount(sat_mask);
  const int nsig = std::popcount(sig_mask);
  if (r.overrun() || nsat * nsig > kMsmMaxCells) {
    ++stats_.bad_masks;
    return false;
  }
  const std::uint64_t cell_mask = nsat * nsig > 0 ? r.u(nsat * nsig) : 0;
  const int ncell = std::popcount(cell_mask);
  const std::size_t need = static_cast<std::size_t>(kMsmHeaderBits + 96 + nsat * nsig + nsat * f.sat_bits() +
                                                    ncell * f.cell_bits());
  if (payload.size() * 8 < need || payload.size() > (need + 7) / 8 + 1) {
    ++stats_.bad_masks;
    return false;
  }
  const std::optional<time::GpsTime> t = msm_epoch_time(sys, epoch_field, now, leap_seconds);
  if (!t) {
    ++stats_.bad_time;
    return false;
  }

  struct SatFields {
    std::uint32_t rough_ms = kRoughInvalid;
    int ext = -1;
    std::uint32_t rough_mod = 0;
    std::int64_t rough_rate = kRoughRateInvalid;
  };
  std::array<SatFields, kMsmMaxCells> sats{};
  for (int i = 0; i < nsat; ++i) sats[static_cast<std::size_t>(i)].rough_ms = static_cast<std::uint32_t>(r.u(8));
  if (f.ext_info)
    for (int i = 0; i < nsat; ++i) sats[static_cast<std::size_t>(i)].ext = static_cast<int>(r.u(4));
  for (int i = 0; i < nsat; ++i) sats[static_cast<std::size_t>(i)].rough_mod = static_cast<std::uint32_t>(r.u(10));
  if (f.rates)
    for (int i = 0; i < nsat; ++i) sats[static_cast<std::size_t>(i)].rough_rate = r.s(14);
  struct CellFields {
    std::int64_t psr, phr, rate = 0;
    int lock, half, cnr;
  };
  std::array<CellFields, kMsmMaxCells> cells{};
  for (int c = 0; c < ncell; ++c) cells[static_cast<std::size_t>(c)].psr = r.s(f.psr_bits);
  for (int c = 0; c < ncell; ++c) cells[static_cast<std::size_t>(c)].phr = r.s(f.phr_bits);
  for (int c = 0; c < ncell; ++c) cells[static_cast<std::size_t>(c)].lock = static_cast<int>(r.u(f.lock_bits));
  for (int c = 0; c < ncell; ++c) cells[static_cast<std::size_t>(c)].half = static_cast<int>(r.u(1));
  for (int c = 0; c < ncell; ++c) cells[static_cast<std::size_t>(c)].cnr = static_cast<int>(r.u(f.cnr_bits));
  if (f.rates)
    for (int c = 0; c < ncell; ++c) cells[static_cast<std::size_t>(c)].rate = r.s(15);

  // A message of a new epoch: the previous one's last message never came.
  if (pending_valid_ && std::abs(*t - pending_.t_rx) > kSameEpoch_s) {
    ++stats_.unterminated_epochs;
    complete(now);
  }
  if (!pending_valid_) {
    pending_ = receiver::RawEpoch{};
    pending_.t_rx = *t;
    pending_.time_valid = true;
    pending_.leap_seconds = leap_seconds;
    pending_.leap_seconds_valid = true;
    pending_valid_ = true;
    pending_station_ = res.station_id;
  }

  std::array<std::optional<SignalId>, 32> sig_of{};
  {
    int j = 0;
    for (int b = 0; b < 32; ++b)
      if ((sig_mask >> (31 - b)) & 1u) sig_of[static_cast<std::size_t>(j++)] = msm_signal(sys, b + 1);
  }
  int i = 0, cell_bit = 0, c = 0;
  for (int id = 1; id <= 64; ++id) {
    if (!((sat_mask >> (64 - id)) & 1u)) continue;
    const SatFields& s = sats[static_cast<std::size_t>(i++)];
    const SatId sat = msm_satellite(sys, id);
    const bool sat_ok = sat.valid();
    if (!sat_ok) ++stats_.unknown_satellites;
    int channel = 0;
    bool channel_known = sys != GnssSystem::kGlonass;
    if (sys == GnssSystem::kGlonass && sat_ok) {
      if (s.ext >= 0 && s.ext <= 13) set_glonass_channel(sat.number, s.ext - 7);
      const std::int8_t k = glonass_fcn_[sat.number];
      channel_known = k != kUnknownFcn;
      channel = channel_known ? k : 0;
    }
    const bool rough_ok = s.rough_ms != kRoughInvalid;
    const double rough_ms = s.rough_ms + s.rough_mod * (1.0 / 1024.0);
    for (int j = 0; j < nsig; ++j, ++cell_bit) {
      if (!((cell_mask >> (nsat * nsig - 1 - cell_bit)) & 1u)) continue;
      const CellFields& v = cells[static_cast<std::size_t>(c++)];
      if (!sat_ok) continue;
      const std::optional<SignalId> sig = sig_of[static_cast<std::size_t>(j)];
      if (!sig) {
        ++stats_.unknown_signals;
        continue;
      }
      bool repeated = false;
      for (int k = 0; k < pending_.num_meas; ++k) {
        const receiver::RawMeasurement& o = pending_.meas[static_cast<std::size_t>(k)];
        if (o.sat == sat && signal_info(o.signal).band == signal_info(*sig).band) repeated = true;
      }
      if (repeated || pending_.num_meas >= receiver::kMaxRawMeasurements) {
        ++stats_.overflow_cells;
        continue;
      }
      receiver::RawMeasurement& m = pending_.meas[static_cast<std::size_t>(pending_.num_meas++)];
      m = receiver::RawMeasurement{};
      m.sat = sat;
      m.signal = *sig;
      m.glonass_channel = channel;
      const double lam_m = kSpeedOfLight_m_s / signal_carrier_hz(*sig, channel);
      m.pseudorange_valid = rough_ok && v.psr != MsmFields::invalid(f.psr_bits);
      if (m.pseudorange_valid) m.pseudorange_m = (rough_ms + static_cast<double>(v.psr) * f.psr_unit_ms) * kMsmRangeMs_m;
      m.carrier_valid = rough_ok && channel_known && v.phr != MsmFields::invalid(f.phr_bits);
      if (m.carrier_valid) m.carrier_phase_cycles = (rough_ms + static_cast<double>(v.phr) * f.phr_unit_ms) * kMsmRangeMs_m / lam_m;
      if (f.rates && channel_known && s.rough_rate != kRoughRateInvalid && v.rate != MsmFields::invalid(15))
        m.doppler_hz = -(static_cast<double>(s.rough_rate) + static_cast<double>(v.rate) * 1e-4) / lam_m;
      m.lock_time_s = f.high_resolution() ? msm7_lock_time_s(v.lock) : msm4_lock_time_s(v.lock);
      m.half_cycle_resolved = v.half == 0;
      m.cn0_dbhz = v.cnr * f.cnr_unit_dbhz;
    }
  }
  ++stats_.msm;
  if (!more) {
    complete(now);
    res.epoch_complete = true;
  }
  return true;
}

}  // namespace gnssemu::protocol::rtcm
