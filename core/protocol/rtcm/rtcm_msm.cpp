// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/rtcm/rtcm_msm.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/common/constants.hpp"
#include "core/protocol/rtcm/rtcm_bits.hpp"
#include "core/protocol/rtcm/rtcm_frame.hpp"

namespace gnssemu::protocol::rtcm {

namespace {

constexpr double kRangeMs_m = kSpeedOfLight_m_s * 1e-3;  ///< the MSM range unit: 1 ms of light travel
constexpr double kP2_10 = 1.0 / 1024.0;
constexpr double kP2_24 = 1.0 / 16777216.0;
constexpr double kP2_29 = 1.0 / 536870912.0;
constexpr double kP2_31 = 1.0 / 2147483648.0;
/// Largest |fine pseudorange| and |fine phase-range| the fields hold, m
/// (2^-10 ms and 2^-8 ms, a little under).
constexpr double kMaxFinePseudorange_m = 292.7;
constexpr double kMaxFinePhaseRange_m = 1171.0;
constexpr double kMaxFineRate_m_s = 1.6384;
constexpr double kSecondsPerWeek = 604800.0;
constexpr double kBdtMinusGpst_s = -14.0;

std::int64_t round_i(double v) noexcept { return static_cast<std::int64_t>(std::floor(v + 0.5)); }

/// The MSM epoch holds whole milliseconds of the receiver's clock: the
/// observables are moved from t_rx to that instant along their Doppler (the
/// shift is below 0.5 ms; the rate's change over it is below a micrometre).
double tag_shift_s(const receiver::RawEpoch& e) noexcept {
  return std::floor(e.t_rx.tow_s() * 1e3 + 0.5) * 1e-3 - e.t_rx.tow_s();
}
double pseudorange_at_m(const receiver::RawMeasurement& m, double lam_m, double dt_s) noexcept {
  return m.pseudorange_m - m.doppler_hz * lam_m * dt_s;
}
double phase_at_cycles(const receiver::RawMeasurement& m, double dt_s) noexcept {
  return m.carrier_phase_cycles - m.doppler_hz * dt_s;
}

/// Messages go out in message-number order.
constexpr std::array<GnssSystem, 6> kMsmOrder{GnssSystem::kGps, GnssSystem::kGlonass, GnssSystem::kGalileo,
                                              GnssSystem::kSbas, GnssSystem::kQzss, GnssSystem::kBeiDou};

/// DF004 / DF248 / DF427 / DF416+DF034 of the receive time.
std::uint32_t msm_epoch_field(GnssSystem sys, const receiver::RawEpoch& e) noexcept {
  if (sys == GnssSystem::kGlonass) {
    const time::GpsTime g = e.t_rx + (10800.0 - e.leap_seconds);
    auto dow = static_cast<std::uint32_t>(g.tow_s() / 86400.0);
    auto tod_ms = static_cast<std::uint32_t>(round_i((g.tow_s() - dow * 86400.0) * 1e3));
    if (tod_ms >= 86400000u) {
      tod_ms -= 86400000u;
      dow = (dow + 1) % 7;
    }
    return (dow & 7u) << 27 | tod_ms;
  }
  double tow = e.t_rx.tow_s();
  if (sys == GnssSystem::kBeiDou) tow += kBdtMinusGpst_s;
  if (tow < 0.0) tow += kSecondsPerWeek;
  auto ms = static_cast<std::uint32_t>(round_i(tow * 1e3));
  if (ms >= 604800000u) ms -= 604800000u;
  return ms;
}

}  // namespace

int msm_message_number(GnssSystem sys, MsmKind kind) noexcept {
  const int k = static_cast<int>(kind);
  switch (sys) {
    case GnssSystem::kGps: return 1070 + k;
    case GnssSystem::kGlonass: return 1080 + k;
    case GnssSystem::kGalileo: return 1090 + k;
    case GnssSystem::kSbas: return 1100 + k;
    case GnssSystem::kQzss: return 1110 + k;
    case GnssSystem::kBeiDou: return 1120 + k;
  }
  return 0;
}

int msm_satellite_id(SatId sat) noexcept {
  switch (sat.system) {
    case GnssSystem::kQzss: return sat.prn() - 192;
    case GnssSystem::kSbas: return sat.prn() - 119;
    default: return sat.prn();
  }
}

int msm4_lock_indicator(double lock_s) noexcept {
  if (!(lock_s >= 0.032)) return 0;
  // i = 1..14: 2^(i+4) ms <= t < 2^(i+5) ms; 15 from 524.288 s.
  for (int i = 1; i <= 14; ++i)
    if (lock_s * 1e3 < std::ldexp(1.0, i + 5)) return i;
  return 15;
}

int msm7_lock_indicator(double lock_s) noexcept {
  if (!(lock_s > 0.0)) return 0;
  const auto t_ms = static_cast<std::int64_t>(lock_s * 1e3);
  if (t_ms < 64) return static_cast<int>(t_ms);
  // Band n = 1..20 covers [2^(n+5), 2^(n+6)) ms at 2^n ms steps:
  // i = (t + n 2^(n+5)) / 2^n, so t = 2^n i - n 2^(n+5) (Table 3.5-76).
  for (int n = 1; n <= 20; ++n) {
    if (t_ms < (std::int64_t{1} << (n + 6))) return static_cast<int>((t_ms + n * (std::int64_t{1} << (n + 5))) >> n);
  }
  return 704;
}

struct MsmEncoder::Sat {
  SatId sat;
  int id = 0;                  ///< MSM satellite id, 1..64
  double rough_range_m = 0.0;  ///< 0: none yet
  double rough_rate_m_s = 0.0;
  std::array<const receiver::RawMeasurement*, kNumBands> meas{};  ///< by band
};

namespace {

/// The satellites of sys with a valid pseudorange on some band, in id
/// order (RawEpoch is in SatId order), and the signal ids they use.
template <typename SatT>
int gather(GnssSystem sys, const receiver::RawEpoch& e, std::array<SatT, 64>& sats, std::uint32_t& sig_bits) {
  int n = 0;
  sig_bits = 0;
  for (int i = 0; i < e.num_meas && i < receiver::kMaxRawMeasurements; ++i) {
    const receiver::RawMeasurement& m = e.meas[static_cast<std::size_t>(i)];
    if (m.sat.system != sys || !m.pseudorange_valid) continue;
    const int id = msm_satellite_id(m.sat);
    if (id < 1 || id > 64) continue;
    if (n == 0 || sats[static_cast<std::size_t>(n - 1)].sat != m.sat) {
      if (n == 64) break;
      sats[static_cast<std::size_t>(n)] = SatT{};
      sats[static_cast<std::size_t>(n)].sat = m.sat;
      sats[static_cast<std::size_t>(n)].id = id;
      ++n;
    }
    SatT& s = sats[static_cast<std::size_t>(n - 1)];
    const SignalInfo& info = signal_info(m.signal);
    s.meas[static_cast<std::size_t>(info.band)] = &m;
    sig_bits |= 1u << (info.rtcm_msm_sig - 1);
    if (s.rough_range_m == 0.0 && m.pseudorange_m > 0.0) {
      const double lam = kSpeedOfLight_m_s / signal_carrier_hz(m.signal, m.glonass_channel);
      const double pr_m = pseudorange_at_m(m, lam, tag_shift_s(e));
      s.rough_range_m = static_cast<double>(round_i(pr_m / kRangeMs_m / kP2_10)) * kRangeMs_m * kP2_10;
      s.rough_rate_m_s = static_cast<double>(round_i(-m.doppler_hz * lam));
    }
  }
  return n;
}

}  // namespace

MsmEpochStats MsmEncoder::append_epoch(const receiver::RawEpoch& epoch, SystemSet systems, std::string& out) {
  MsmEpochStats stats;
  if (!epoch.time_valid) return stats;
  std::array<Sat, 64> sats;
  std::uint32_t sig_bits = 0;
  // First pass: how many messages, so the last one clears the multiple-message bit.
  int total = 0;
  for (GnssSystem sys : kMsmOrder) {
    if (!systems.has(sys)) continue;
    const int nsat = gather(sys, epoch, sats, sig_bits);
    const int nsig = std::popcount(sig_bits);
    if (nsat == 0 || nsig == 0) continue;
    const int per_msg = 64 / nsig;
    total += (nsat + per_msg - 1) / per_msg;
  }
  int sent = 0;
  for (GnssSystem sys : kMsmOrder) {
    if (!systems.has(sys)) continue;
    const int nsat = gather(sys, epoch, sats, sig_bits);
    std::array<int, 32> sig_ids{};
    int nsig = 0;
    for (int b = 0; b < 32; ++b)
      if ((sig_bits >> b) & 1u) sig_ids[static_cast<std::size_t>(nsig++)] = b + 1;
    if (nsat == 0 || nsig == 0) continue;
    const int per_msg = 64 / nsig;
    for (int first = 0; first < nsat; first += per_msg) {
      const int n = std::min(per_msg, nsat - first);
      ++sent;
      encode_message(sys, epoch, sats.data() + first, n, sig_ids, nsig, sent < total, out, stats);
    }
  }
  return stats;
}

void MsmEncoder::encode_message(GnssSystem sys, const receiver::RawEpoch& epoch, const Sat* sats, int nsat,
                                const std::array<int, 32>& sig_ids, int nsig, bool more, std::string& out,
                                MsmEpochStats& stats) {
  const bool msm7 = kind_ == MsmKind::kMsm7;
  const double dt_s = tag_shift_s(epoch);
  Payload buf;
  BitWriter w(buf);
  w.u(12, static_cast<std::uint64_t>(msm_message_number(sys, kind_)));
  w.u(12, static_cast<std::uint64_t>(station_id_));
  w.u(30, msm_epoch_field(sys, epoch));
  w.u(1, more ? 1 : 0);  // DF393
  w.u(3, 0);             // DF409 IODS
  w.u(7, 0);             // reserved
  w.u(2, 0);             // DF411 clock steering: unknown
  w.u(2, 0);             // DF412 external clock: internal
  w.u(1, 0);             // DF417 divergence-free smoothing: no
  w.u(3, 0);             // DF418 smoothing interval: none
  std::uint64_t sat_mask = 0;
  for (int i = 0; i < nsat; ++i) sat_mask |= std::uint64_t{1} << (64 - sats[i].id);
  w.u(64, sat_mask);
  std::uint32_t sig_mask = 0;
  for (int j = 0; j < nsig; ++j) sig_mask |= 1u << (32 - sig_ids[static_cast<std::size_t>(j)]);
  w.u(32, sig_mask);

  // Cells, satellite-major, with their field values.
  struct CellValues {
    std::int64_t psr, phr, rate;
    int lock, half, cnr;
  };
  std::array<CellValues, 64> cells;
  int ncell = 0;
  for (int i = 0; i < nsat; ++i) {
    for (int j = 0; j < nsig; ++j) {
      const receiver::RawMeasurement* m = nullptr;
      for (const auto* c : sats[i].meas)
        if (c && signal_info(c->signal).rtcm_msm_sig == sig_ids[static_cast<std::size_t>(j)]) m = c;
      w.u(1, m ? 1 : 0);
      if (!m) continue;
      const Sat& s = sats[i];
      const double lam = kSpeedOfLight_m_s / signal_carrier_hz(m->signal, m->glonass_channel);
      CellValues& v = cells[static_cast<std::size_t>(ncell++)];
      ++stats.cells;
      // Fine pseudorange.
      const double psr_m = pseudorange_at_m(*m, lam, dt_s) - s.rough_range_m;
      const bool psr_ok = m->pseudorange_valid && std::abs(psr_m) <= kMaxFinePseudorange_m;
      v.psr = psr_ok ? round_i(psr_m / kRangeMs_m / (msm7 ? kP2_29 : kP2_24)) : (msm7 ? -524288 : -16384);
      // Fine phase-range, less the whole-cycle offset of this lock.
      PhaseState& ps = phase_[static_cast<std::size_t>(m->sat.index() * kNumBands + signal_info(m->signal).band)];
      double lock_s = 0.0;
      bool phr_ok = false;
      double phr_m = 0.0;
      if (m->carrier_valid) {
        phr_m = phase_at_cycles(*m, dt_s) * lam - s.rough_range_m;
        const bool restart = !ps.active || m->lock_time_s < ps.prev_lock_s || m->lock_time_s <= 0.0;
        if (restart || std::abs(phr_m - ps.offset_cycles * lam) > kMaxFinePhaseRange_m) {
          ps.offset_cycles = std::floor(phr_m / lam + 0.5);
          ps.reset = !restart;
          ps.reset_at = epoch.t_rx;
        }
        ps.active = true;
        ps.prev_lock_s = m->lock_time_s;
        phr_m -= ps.offset_cycles * lam;
        phr_ok = std::abs(phr_m) <= kMaxFinePhaseRange_m;
        lock_s = ps.reset ? std::min(m->lock_time_s, epoch.t_rx - ps.reset_at) : m->lock_time_s;
      } else {
        ps.active = false;
      }
      v.phr = phr_ok ? round_i(phr_m / kRangeMs_m / (msm7 ? kP2_31 : kP2_29)) : (msm7 ? -8388608 : -2097152);
      if ((m->pseudorange_valid && !psr_ok) || (m->carrier_valid && !phr_ok)) ++stats.dropped_cells;
      v.lock = msm7 ? msm7_lock_indicator(lock_s) : msm4_lock_indicator(lock_s);
      v.half = m->half_cycle_resolved ? 0 : 1;
      v.cnr = msm7 ? static_cast<int>(std::clamp<std::int64_t>(round_i(m->cn0_dbhz / 0.0625), 0, 1023))
                   : static_cast<int>(std::clamp<std::int64_t>(round_i(m->cn0_dbhz), 0, 63));
      const double rate_m_s = -m->doppler_hz * lam - s.rough_rate_m_s;
      v.rate = std::abs(rate_m_s) <= kMaxFineRate_m_s ? round_i(rate_m_s / 1e-4) : -16384;
    }
  }
  // Satellite data, field by field (DF397, [ext info], DF398, [DF399]).
  for (int i = 0; i < nsat; ++i) {
    const double r = sats[i].rough_range_m;
    const bool ok = r > 0.0 && r < kRangeMs_m * 255.0;
    w.u(8, ok ? static_cast<std::uint64_t>(round_i(r / kRangeMs_m / kP2_10)) >> 10 : 255u);
  }
  if (msm7) {
    for (int i = 0; i < nsat; ++i) {
      int info = 0;
      if (sys == GnssSystem::kGlonass) {
        const auto* m = sats[i].meas[0] ? sats[i].meas[0] : sats[i].meas[1];
        info = m ? m->glonass_channel + 7 : 15;
      }
      w.u(4, static_cast<std::uint64_t>(info));
    }
  }
  for (int i = 0; i < nsat; ++i) {
    const double r = sats[i].rough_range_m;
    const bool ok = r > 0.0 && r < kRangeMs_m * 255.0;
    w.u(10, ok ? static_cast<std::uint64_t>(round_i(r / kRangeMs_m / kP2_10)) & 0x3FFu : 0u);
  }
  if (msm7) {
    for (int i = 0; i < nsat; ++i) {
      const double rr = sats[i].rough_rate_m_s;
      w.s(14, std::abs(rr) > 8191.0 ? -8192 : round_i(rr));
    }
  }
  // Signal data, field by field.
  for (int c = 0; c < ncell; ++c) w.s(msm7 ? 20 : 15, cells[static_cast<std::size_t>(c)].psr);
  for (int c = 0; c < ncell; ++c) w.s(msm7 ? 24 : 22, cells[static_cast<std::size_t>(c)].phr);
  for (int c = 0; c < ncell; ++c) w.u(msm7 ? 10 : 4, static_cast<std::uint64_t>(cells[static_cast<std::size_t>(c)].lock));
  for (int c = 0; c < ncell; ++c) w.u(1, static_cast<std::uint64_t>(cells[static_cast<std::size_t>(c)].half));
  for (int c = 0; c < ncell; ++c) w.u(msm7 ? 10 : 6, static_cast<std::uint64_t>(cells[static_cast<std::size_t>(c)].cnr));
  if (msm7)
    for (int c = 0; c < ncell; ++c) w.s(15, cells[static_cast<std::size_t>(c)].rate);
  if (append_frame(std::span<const std::uint8_t>(buf.data(), w.bytes()), out)) ++stats.messages;
}

}  // namespace gnssemu::protocol::rtcm
