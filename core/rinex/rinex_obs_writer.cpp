// SPDX-License-Identifier: Apache-2.0
#include "core/rinex/rinex_obs_writer.hpp"

#include <algorithm>
#include <cmath>

#include "core/rinex/rinex_format.hpp"

namespace gnssemu::rinex {

namespace {

// Observation kinds of one signal, in the order of SYS / # / OBS TYPES.
constexpr char kKinds[4] = {'C', 'L', 'D', 'S'};
constexpr int kMaxTypesPerLine = 13;      // RINEX 3.04 Table A2
constexpr int kMaxSlotsPerLine = 8;       // GLONASS SLOT / FRQ #
// F14.3 holds |x| < 1e10.
constexpr double kMaxF14_3 = 9.999e9;

/// Signals a system is observed on, in band order; their count.
int signals_of(GnssSystem sys, int num_bands, std::array<SignalId, kNumBands>& out) noexcept {
  int n = 0;
  for (int b = 0; b < num_bands && b < kNumBands; ++b) {
    if (const std::optional<SignalId> s = signal_of(sys, b)) out[static_cast<std::size_t>(n++)] = *s;
  }
  return n;
}

void value(LineBuf& l, double v, bool valid, int lli, int ssi) noexcept {
  if (!valid || !std::isfinite(v) || std::fabs(v) > kMaxF14_3) {
    l.add("%16s", "");
    return;
  }
  l.add("%14.3f", v);
  if (lli > 0) {
    l.add("%1d", lli);
  } else {
    l.add(" ");
  }
  if (ssi > 0) {
    l.add("%1d", ssi);
  } else {
    l.add(" ");
  }
}

}  // namespace

int loss_of_lock_indicator(const receiver::RawMeasurement& m, double prev_lock_time_s) noexcept {
  if (!m.carrier_valid) return 0;
  int lli = 0;
  if (m.lock_time_s <= 0.0 || m.lock_time_s < prev_lock_time_s) lli |= 1;
  if (!m.half_cycle_resolved) lli |= 2;
  return lli;
}

int signal_strength_indicator(double cn0_dbhz) noexcept {
  if (!(cn0_dbhz > 0.0)) return 0;
  return std::clamp(static_cast<int>(cn0_dbhz / 6.0), 1, 9);
}

ObsWriter::ObsWriter(std::ostream& out, ObsHeaderInfo info) : out_(out), info_(std::move(info)) {
  for (auto& s : prev_lock_s_) s.fill(-1.0);
}

void ObsWriter::write_header(const time::GpsTime& first) noexcept {
  header_done_ = true;
  LineBuf l;
  version_line(out_, "OBSERVATION DATA", "M");
  program_line(out_);
  l.add("%-60.60s", info_.marker_name.c_str());
  header_line(out_, l, "MARKER NAME");
  l.add("%-20s", "NON_GEODETIC");
  header_line(out_, l, "MARKER TYPE");
  l.add("%-20.20s%-40.40s", info_.observer.c_str(), info_.agency.c_str());
  header_line(out_, l, "OBSERVER / AGENCY");
  l.add("%-20.20s%-20.20s%-20.20s", info_.receiver_number.c_str(), info_.receiver_type.c_str(),
        info_.receiver_version.c_str());
  header_line(out_, l, "REC # / TYPE / VERS");
  l.add("%-20.20s%-20.20s", info_.antenna_number.c_str(), info_.antenna_type.c_str());
  header_line(out_, l, "ANT # / TYPE");
  l.add("%14.4f%14.4f%14.4f", info_.approx_pos_m.x, info_.approx_pos_m.y, info_.approx_pos_m.z);
  header_line(out_, l, "APPROX POSITION XYZ");
  l.add("%14.4f%14.4f%14.4f", info_.antenna_delta_hen_m.x, info_.antenna_delta_hen_m.y, info_.antenna_delta_hen_m.z);
  header_line(out_, l, "ANTENNA: DELTA H/E/N");

  for (const SatNumbering& n : kSatNumbering) {
    if (!info_.systems.has(n.system)) continue;
    std::array<SignalId, kNumBands> sigs{};
    const int ns = signals_of(n.system, info_.num_bands, sigs);
    const int ntypes = 4 * ns;
    l.add("%c  %3d", n.letter, ntypes);
    for (int k = 0; k < ntypes; ++k) {
      if (k > 0 && k % kMaxTypesPerLine == 0) {
        header_line(out_, l, "SYS / # / OBS TYPES");
        l.add("%6s", "");
      }
      const SignalInfo& si = signal_info(sigs[static_cast<std::size_t>(k / 4)]);
      l.add(" %c%c%c", kKinds[k % 4], si.rinex_code[0], si.rinex_code[1]);
    }
    header_line(out_, l, "SYS / # / OBS TYPES");
  }
  l.add("%-20s", "DBHZ");
  header_line(out_, l, "SIGNAL STRENGTH UNIT");
  if (info_.interval_s > 0.0) {
    l.add("%10.3f", info_.interval_s);
    header_line(out_, l, "INTERVAL");
  }
  const time::CalendarTime c = first.to_calendar();
  l.add("%6d%6d%6d%6d%6d%13.7f%5s%3s", c.year, c.month, c.day, c.hour, c.minute, c.second, "", "GPS");
  header_line(out_, l, "TIME OF FIRST OBS");
  // The world's carriers carry no quarter-cycle offsets between a band's
  // signal components: every phase is already aligned (correction 0).
  for (const SatNumbering& n : kSatNumbering) {
    if (!info_.systems.has(n.system)) continue;
    std::array<SignalId, kNumBands> sigs{};
    const int ns = signals_of(n.system, info_.num_bands, sigs);
    for (int k = 0; k < ns; ++k) {
      const SignalInfo& si = signal_info(sigs[static_cast<std::size_t>(k)]);
      l.add("%c L%c%c %8.5f", n.letter, si.rinex_code[0], si.rinex_code[1], 0.0);
      header_line(out_, l, "SYS / PHASE SHIFT");
    }
  }
  if (info_.systems.has(GnssSystem::kGlonass)) {
    const int n = static_cast<int>(info_.glonass_channels.size());
    l.add("%3d ", n);
    for (int k = 0; k < n; ++k) {
      if (k > 0 && k % kMaxSlotsPerLine == 0) {
        header_line(out_, l, "GLONASS SLOT / FRQ #");
        l.add("%4s", "");
      }
      const auto& [slot, channel] = info_.glonass_channels[static_cast<std::size_t>(k)];
      l.add("R%02d %2d ", slot, channel);
    }
    header_line(out_, l, "GLONASS SLOT / FRQ #");
    // No code-phase bias between GLONASS code and carrier in the world.
    l.add(" C1C %8.3f C1P %8.3f C2C %8.3f C2P %8.3f", 0.0, 0.0, 0.0, 0.0);
    header_line(out_, l, "GLONASS COD/PHS/BIS");
  }
  if (info_.leap_seconds >= 0) {
    l.add("%6d", info_.leap_seconds);
    header_line(out_, l, "LEAP SECONDS");
  }
  header_line(out_, l, "END OF HEADER");
}

void ObsWriter::write(const receiver::RawEpoch& e) noexcept {
  if (!e.time_valid) return;
  int n_sats = 0;
  SatId last;
  for (int i = 0; i < e.num_meas; ++i) {
    const receiver::RawMeasurement& m = e.meas[static_cast<std::size_t>(i)];
    if (!info_.systems.has(m.sat.system) || signal_info(m.signal).band >= info_.num_bands) continue;
    if (n_sats == 0 || !(m.sat == last)) ++n_sats;
    last = m.sat;
  }
  if (n_sats == 0) return;  // nothing tracked yet (as convbin skips RAWX epochs without measurements)
  if (!header_done_) write_header(e.t_rx);
  LineBuf l;
  const time::CalendarTime c = e.t_rx.to_calendar();
  // Epoch flag 0; a clock step since the last epoch is a fact of the data
  // (RAWX clkReset), not an event: the pseudoranges carry it.
  l.add("> %4d %02d %02d %02d %02d%11.7f  %1d%3d", c.year, c.month, c.day, c.hour, c.minute, c.second, 0, n_sats);
  l.flush(out_);
  // Measurements come satellite by satellite, band order within one (RawEpoch).
  int i = 0;
  while (i < e.num_meas) {
    const SatId sat = e.meas[static_cast<std::size_t>(i)].sat;
    int j = i;
    while (j < e.num_meas && e.meas[static_cast<std::size_t>(j)].sat == sat) ++j;
    if (info_.systems.has(sat.system)) {
      std::array<SignalId, kNumBands> sigs{};
      const int ns = signals_of(sat.system, info_.num_bands, sigs);
      auto& prev = prev_lock_s_[static_cast<std::size_t>(sat.index())];
      l.add("%c%02d", system_letter(sat.system), sat.number);
      for (int k = 0; k < ns; ++k) {
        const receiver::RawMeasurement* m = nullptr;
        for (int q = i; q < j; ++q) {
          if (e.meas[static_cast<std::size_t>(q)].signal == sigs[static_cast<std::size_t>(k)]) {
            m = &e.meas[static_cast<std::size_t>(q)];
          }
        }
        const std::size_t band = static_cast<std::size_t>(signal_info(sigs[static_cast<std::size_t>(k)]).band);
        if (m == nullptr) {
          l.add("%64s", "");
          prev[band] = -1.0;
          continue;
        }
        const int ssi = signal_strength_indicator(m->cn0_dbhz);
        value(l, m->pseudorange_m, m->pseudorange_valid, 0, ssi);
        value(l, m->carrier_phase_cycles, m->carrier_valid, loss_of_lock_indicator(*m, prev[band]), ssi);
        value(l, m->doppler_hz, true, 0, ssi);
        value(l, m->cn0_dbhz, true, 0, 0);
        prev[band] = m->carrier_valid ? m->lock_time_s : -1.0;
      }
      l.flush(out_);
    }
    i = j;
  }
  ++epochs_;
}

void ObsWriter::finish() noexcept {
  if (!header_done_) write_header(time::GpsTime());
  out_.flush();
}

}  // namespace gnssemu::rinex
