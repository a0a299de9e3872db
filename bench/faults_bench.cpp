// SPDX-License-Identifier: Apache-2.0
// faults_bench: the evidence of docs/faults.md, as figures. Each case runs
// the pipeline (u-blox M8 profile, static receiver at 48.87N 2.30E, real
// broadcast ephemerides) with faults between world and receiver and reads
// what the receiver and its UBX messages report. Prints figures; not a test.
//   faults_bench [jam|drag|takeover|step|cost|all] [nav_file]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/faults/interference.hpp"
#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/orbit/rinex_nav.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/pipeline/receiver_profile.hpp"
#include "core/protocol/ubx/wire/ubx_encoder.hpp"
#include "tests/support/alloc_counter.hpp"

namespace {

using namespace gnssemu;
using faults::FaultEvent;
using faults::FaultType;
using faults::Param;
using faults::Ramp;

const Lla kSite{48.8738 * kDegToRad, 2.2950 * kDegToRad, 100.0};

struct Rig {
  explicit Rig(const orbit::EphemerisStore& store, time::GpsTime start)
      : t0(start),
        rx(store, pipeline::apply_profile(pipeline::PipelineConfig{}, pipeline::ReceiverProfile::kUbloxM8,
                                          kSite.lat_rad)) {
    truth.pos_m = geo::ecef_from_lla(kSite);
    truth.valid = true;
  }
  const receiver::Fix& step(double s) {
    truth.t = t0 + s;
    return rx.step(truth.t, truth);
  }
  Enu error(const receiver::Fix& f) const {
    return geo::ecef_to_enu_vector(f.pos_m - truth.pos_m, kSite.lat_rad, kSite.lon_rad);
  }
  time::GpsTime t0;
  pipeline::Pipeline rx;
  world::Truth truth;
};

// MON-HW and NAV-STATUS fields as the M8 encoder writes them, MON-RF and
// SEC-SIG as the M9's (CFG-ITFM enabled at factory thresholds and the first
// fix behind us, so jammingState is reported).
struct UbxView {
  int agc = 0, noise = 0, jam_ind = 0, jam_state = 0, a_status = 0, spoof = 0;
  int rf_jam_ind = 0, rf_jam_state = 0, sig_jam_state = 0;
};
UbxView ubx_view(const receiver::Fix& f) {
  static const protocol::ubx::UbxEncoder enc;
  static const protocol::ubx::UbxEncoder m9(protocol::ubx::mon_ver_of(protocol::ubx::Generation::kM9));
  protocol::ubx::EpochInfo info;
  info.itfm.enabled = true;
  info.ttff_ms = 1;
  std::string out;
  enc.mon_hw(f, info, out);
  const std::uint8_t* p = reinterpret_cast<const std::uint8_t*>(out.data()) + 6;  // payload
  UbxView v;
  const std::span<const std::uint8_t> hw{p, out.size() - 6};
  v.noise = static_cast<int>(protocol::ubx::load_le(hw, 16, 2));
  v.agc = static_cast<int>(protocol::ubx::load_le(hw, 18, 2));
  v.a_status = p[20];
  v.jam_state = (p[22] >> 2) & 3;
  v.jam_ind = p[45];
  out.clear();
  enc.nav_status(f, info, out);
  v.spoof = (static_cast<std::uint8_t>(out[6 + 7]) >> 3) & 3;
  out.clear();
  m9.mon_rf(f, info, out);  // one block at payload offset 4
  p = reinterpret_cast<const std::uint8_t*>(out.data()) + 6;
  v.rf_jam_state = p[4 + 1] & 3;
  v.rf_jam_ind = p[4 + 16];
  out.clear();
  m9.sec_sig(f, info, out);
  p = reinterpret_cast<const std::uint8_t*>(out.data()) + 6;
  v.sig_jam_state = (p[4] >> 1) & 3;  // jamFlags
  return v;
}

double max_abs_residual(const receiver::Fix& f) {
  double m = 0.0;
  for (int i = 0; i < f.num_sats; ++i)
    if (f.sats[i].used) m = std::max(m, std::fabs(f.sats[i].residual_m));
  return m;
}

FaultEvent event(FaultType type, double start_s, double duration_s = faults::kForever_s, int mode = 0) {
  return FaultEvent::of(type, start_s, duration_s, static_cast<std::uint8_t>(mode));
}

// Jamming sweep: J/S 0 -> 60 dB in 2 dB steps of 20 s after 60 s clean.
void jam_sweep(const orbit::EphemerisStore& store, time::GpsTime t0) {
  const double step_s = 20.0, warm_s = 60.0;
  std::vector<FaultEvent> ev;
  for (int js = 0; js <= 60; js += 2) {
    FaultEvent e = event(FaultType::kJammer, warm_s + step_s * js / 2, step_s);
    e.put(Param::kJsDb, js);
    ev.push_back(e);
  }
  Rig rig(store, t0);
  rig.rx.set_faults(ev);
  const auto& link = rig.rx.world().config().signal.link;
  const double n0 = signal::thermal_noise_density_dbw_hz(link.noise_temperature_k) + link.noise_figure_db +
                    link.environment_noise_rise_db;
  std::array<double, kNumSats> clean{};  ///< by SatId::index()
  const double lose = rig.rx.receiver().config().tracking.lose_dbhz;
  int top = -1;  // index of the strongest clean satellite: its C/N0 shows the slope
  double prev_top = NAN;
  std::printf("jamming sweep (wideband, Q = 2): each J/S held %.0f s; means over its last 10 s\n", step_s);
  std::printf("%6s %9s %9s %7s %9s %9s %7s %5s %4s %8s %7s %6s %6s %8s %7s %7s\n", "js_db", "top_cn0", "analytic",
              "slope", "mean_cn0", "analytic", "tracked", "used", "fix", "hacc_m", "agcCnt", "noise", "jamInd",
              "jamState", "rfState", "sigJam");
  double sum_cn0 = 0, sum_an = 0, sum_tr = 0, sum_used = 0, sum_hacc = 0, sum_top = 0;
  int n = 0, n_cn0 = 0, fix_epochs = 0, n_top = 0;
  for (int s = 0; s < static_cast<int>(warm_s + step_s * 31); ++s) {
    const receiver::Fix& f = rig.step(s);
    if (s < warm_s) {
      for (int i = 0; i < f.num_sats; ++i)
        if (f.sats[i].tracked) clean[static_cast<std::size_t>(f.sats[i].sat.index())] = f.sats[i].cn0_dbhz;
      if (s == warm_s - 1) {
        for (int p = 0; p < kNumSats; ++p)
          if (top < 0 || clean[p] > clean[top]) top = p;
        // The model's prediction: each satellite is lost where its effective
        // C/N0 falls below the lose threshold; 3D needs four, 2D three.
        std::vector<double> lost_at;
        for (const double clean_dbhz : clean) {
          if (!(clean_dbhz > 0)) continue;
          double js = 0;
          while (js < 100 && faults::effective_cn0_dbhz(clean_dbhz, n0, faults::interference_density_w_hz(
                                                                                 faults::kNominalSignal_dbw + js,
                                                                                 faults::JammerKind::kWideband)) >= lose)
            js += 0.1;
          lost_at.push_back(js);
        }
        std::sort(lost_at.rbegin(), lost_at.rend());
        std::printf("model: %zu satellites tracked clean; 3D fix lost at J/S %.1f dB (4th satellite below %.0f dB-Hz), "
                    "any fix at %.1f dB (3rd); the jammer equals the noise floor (I0 = N0) at J/S %.1f dB\n",
                    lost_at.size(), lost_at.size() > 3 ? lost_at[3] : 0.0, lose, lost_at.size() > 2 ? lost_at[2] : 0.0,
                    n0 - faults::kNominalSignal_dbw + 10.0 * std::log10(2.0 * kCaChipRate_hz));
      }
      continue;
    }
    const int k = static_cast<int>((s - warm_s) / step_s);
    const double in_step = s - warm_s - k * step_s;
    if (in_step == 0) sum_cn0 = sum_an = sum_tr = sum_used = sum_hacc = sum_top = n = n_cn0 = fix_epochs = n_top = 0;
    if (in_step < step_s - 10) continue;
    const double js = 2.0 * k;
    const double i0 = faults::interference_density_w_hz(faults::kNominalSignal_dbw + js, faults::JammerKind::kWideband);
    for (int i = 0; i < f.num_sats; ++i) {
      if (!f.sats[i].tracked) continue;
      sum_cn0 += f.sats[i].cn0_dbhz;
      sum_an += faults::effective_cn0_dbhz(clean[static_cast<std::size_t>(f.sats[i].sat.index())], n0, i0);
      ++n_cn0;
      if (f.sats[i].sat.index() == top) sum_top += f.sats[i].cn0_dbhz, ++n_top;
    }
    sum_tr += f.num_tracked;
    sum_used += f.num_used;
    if (f.type != receiver::FixType::kNone) {
      sum_hacc += f.h_acc_m;
      ++fix_epochs;
    }
    ++n;
    if (in_step == step_s - 1) {
      const UbxView u = ubx_view(f);
      const double top_cn0 = n_top ? sum_top / n_top : NAN;
      std::printf("%6.0f %9.2f %9.2f %7.2f %9.2f %9.2f %7.1f %5.1f %4d %8.2f %7d %6d %6d %8d %7d %7d\n", js,
                  top_cn0, faults::effective_cn0_dbhz(clean[top - 1], n0, i0), (prev_top - top_cn0) / 2.0,
                  n_cn0 ? sum_cn0 / n_cn0 : NAN, n_cn0 ? sum_an / n_cn0 : NAN, sum_tr / n, sum_used / n,
                  static_cast<int>(f.type), fix_epochs ? sum_hacc / fix_epochs : NAN, u.agc, u.noise, u.jam_ind,
                  u.jam_state, u.rf_jam_state, u.sig_jam_state);
      if (u.rf_jam_ind != u.jam_ind || u.rf_jam_state != u.jam_state || u.sig_jam_state != u.jam_state) {
        std::printf("  MON-RF / SEC-SIG disagree with MON-HW\n");
      }
      prev_top = top_cn0;
    }
  }
  std::printf("top_cn0: PRN %02d (%.1f dB-Hz clean); slope: its C/N0 drop per dB of J/S; mean_cn0 over tracked "
              "satellites (survivors)\n", top, clean[top - 1]);
}

// Drag-off 2 m/s east for 300 s after 60 s clean.
void drag(const orbit::EphemerisStore& store, time::GpsTime t0) {
  FaultEvent e = event(FaultType::kSpoofer, 60.0, 300.0, static_cast<int>(faults::SpoofMode::kDrag));
  e.put(Param::kDragSpeedMS, 2.0);
  e.put(Param::kDragHeadingDeg, 90.0);
  e.put(Param::kPowerAdvantageDb, 6.0);
  Rig rig(store, t0);
  rig.rx.set_faults(std::vector<FaultEvent>{e});
  std::printf("drag-off: 2 m/s toward 090 for 300 s from t = 60 s, power advantage 6 dB\n");
  std::printf("%6s %9s %9s %8s %5s %9s %5s %6s\n", "t_s", "east_m", "h_err_m", "hacc_m", "used", "max_res_m", "fix",
              "spoof");
  double max_hacc = 0, max_res = 0;
  int losses = 0, excluded = 0;
  for (int s = 0; s <= 360; ++s) {
    const receiver::Fix& f = rig.step(s);
    const Enu d = rig.error(f);
    if (s >= 60) {
      max_hacc = std::max(max_hacc, f.h_acc_m);
      max_res = std::max(max_res, max_abs_residual(f));
      losses += f.type == receiver::FixType::kNone;
      excluded += f.num_tracked - f.num_used;
    }
    if (s % 30 == 0 || s == 359) {
      std::printf("%6d %9.1f %9.1f %8.2f %5d %9.2f %5d %6d\n", s, d.x, std::hypot(d.x, d.y), f.h_acc_m, f.num_used,
                  max_abs_residual(f), static_cast<int>(f.type), ubx_view(f).spoof);
    }
  }
  std::printf("during the drag: max hAcc %.2f m, max |residual| %.2f m, epochs without fix %d, exclusions %d\n",
              max_hacc, max_res, losses, excluded);
}

// Abrupt takeover: 500 m north and +10 us at t = 60 s, 10 dB advantage.
void takeover(const orbit::EphemerisStore& store, time::GpsTime t0) {
  FaultEvent e = event(FaultType::kSpoofer, 60.0, faults::kForever_s, static_cast<int>(faults::SpoofMode::kTakeover));
  e.put(Param::kOffsetNorthM, 500.0);
  e.put(Param::kClockJumpUs, 10.0);
  e.put(Param::kPowerAdvantageDb, 10.0);
  Rig rig(store, t0);
  rig.rx.set_faults(std::vector<FaultEvent>{e});
  std::printf("abrupt takeover at t = 60 s: false position 500 m north, clock +10 us, advantage 10 dB\n");
  std::printf("%6s %14s %9s %8s %5s %6s %10s\n", "t_s", "clock_bias_us", "north_m", "hacc_m", "used", "spoof",
              "mean_cn0");
  for (int s = 0; s <= 100; ++s) {
    const receiver::Fix& f = rig.step(s);
    const Enu d = rig.error(f);
    double cn0 = 0;
    int n = 0;
    for (int i = 0; i < f.num_sats; ++i)
      if (f.sats[i].tracked) cn0 += f.sats[i].cn0_dbhz, ++n;
    if ((s >= 57 && s <= 64) || s % 20 == 0) {
      std::printf("%6d %14.3f %9.1f %8.2f %5d %6d %10.1f\n", s, f.clock_bias_s * 1e6, d.y, f.h_acc_m, f.num_used,
                  ubx_view(f).spoof, n ? cn0 / n : 0.0);
    }
  }
}

// A step on one used satellite: 50 m (excluded) and 3 m (not). The same
// seed without the fault gives the reference, so the difference is the
// fault's effect alone.
void step(const orbit::EphemerisStore& store, time::GpsTime t0) {
  int prn = 0;
  {
    Rig probe(store, t0);
    for (int s = 0; s < 30; ++s) probe.step(s);  // acquisition
    const receiver::Fix& f = probe.step(30);
    for (int i = 0; i < f.num_sats && prn == 0; ++i)
      if (f.sats[i].used) prn = f.sats[i].sat.prn();
  }
  for (const double bias : {50.0, 3.0}) {
    FaultEvent e = event(FaultType::kSatellite, 60.0, 60.0);
    e.put(Param::kPrn, prn);
    e.put(Param::kBiasM, bias);
    Rig rig(store, t0), ref(store, t0);
    rig.rx.set_faults(std::vector<FaultEvent>{e});
    double shift_sum = 0, shift_max = 0, err_ref = 0, err = 0;
    int used_epochs = 0, first_excluded = -1;
    for (int s = 0; s < 120; ++s) {
      const receiver::Fix& f = rig.step(s);
      const receiver::Fix& g = ref.step(s);
      if (s < 60) continue;
      bool used = false;
      for (int i = 0; i < f.num_sats; ++i)
        if (f.sats[i].sat == SatId::gps(prn)) used = f.sats[i].used;
      used_epochs += used;
      if (!used && first_excluded < 0) first_excluded = s - 60;
      const Enu d = rig.error(f), dr = ref.error(g);
      const double shift = std::hypot(d.x - dr.x, d.y - dr.y, d.z - dr.z);
      shift_sum += shift;
      shift_max = std::max(shift_max, shift);
      err += std::hypot(d.x, d.y);
      err_ref += std::hypot(dr.x, dr.y);
    }
    std::printf("step %4.1f m on PRN %02d for 60 s: used in %2d of 60 epochs; first excluded: %s; 3D "
                "shift against the fault-free run mean %.2f m, max %.2f m; mean horizontal error %.2f m (fault-free "
                "%.2f m)\n",
                bias, prn, used_epochs,
                first_excluded < 0 ? "never" : (std::to_string(first_excluded) + " epoch(s) after onset").c_str(),
                shift_sum / 60, shift_max, err / 60, err_ref / 60);
  }
}

// Cost per epoch of each fault's FaultStage::apply (on the world's
// observables of a running receiver), and allocations after warm-up.
void cost(const orbit::EphemerisStore& store, time::GpsTime t0) {
  struct Case {
    const char* name;
    std::vector<FaultEvent> ev;
  };
  std::vector<Case> cases;
  cases.push_back({"none", {}});
  {
    FaultEvent e = event(FaultType::kJammer, 0.0);
    e.put(Param::kEirpDbw, -30.0);
    e.put(Param::kLatDeg, 48.88);
    e.put(Param::kLonDeg, 2.30);
    cases.push_back({"jammer", {e}});
  }
  {
    FaultEvent e = event(FaultType::kJammer, 0.0);
    e.put(Param::kJsDb, 20.0);
    cases.push_back({"jammer_js", {e}});
  }
  {
    FaultEvent e = event(FaultType::kSpoofer, 0.0);
    e.put(Param::kDragSpeedMS, 2.0);
    cases.push_back({"spoofer", {e}});
  }
  {
    FaultEvent e = event(FaultType::kSkyBlock, 0.0, 400.0);
    e.put(Param::kAzFromDeg, Ramp{0.0, 360.0});
    e.put(Param::kAzToDeg, 90.0);
    e.put(Param::kLossDb, 10.0);
    cases.push_back({"sky_block", {e}});
  }
  {
    FaultEvent e = event(FaultType::kSatellite, 0.0);
    e.put(Param::kPrn, 4);
    e.put(Param::kEphAlongM, 100.0);
    e.put(Param::kRateMS, 1.0);
    cases.push_back({"satellite", {e}});
  }
  cases.push_back({"outage", {event(FaultType::kOutage, 0.0)}});
  std::vector<FaultEvent> all;
  for (const Case& c : cases) all.insert(all.end(), c.ev.begin(), c.ev.end());
  cases.push_back({"all_six", all});
  const int n = 3000, warm = 50;
  std::printf("cost of FaultStage::apply per epoch (10 Hz, %d epochs after %d of warm-up; best of 3 runs)\n", n, warm);
  std::printf("%-10s %10s %12s\n", "fault", "ns/epoch", "allocs/ep");
  Rig rig(store, t0);
  const world::WorldConfig& wc = rig.rx.world().config();
  const faults::FaultContext ctx{wc.seed, wc.signal.link, world::MeasurementNoise::of(wc)};
  std::vector<std::unique_ptr<faults::FaultStage>> stages;
  for (const Case& c : cases) stages.push_back(std::make_unique<faults::FaultStage>(ctx, c.ev));
  std::vector<double> best(cases.size(), 1e300);
  std::vector<long> allocs(cases.size(), 0);
  world::Observables obs;
  for (int run = 0; run < 3; ++run) {
    std::vector<double> ns(cases.size(), 0.0);
    for (int k = -warm; k < n; ++k) {
      const double t_s = 0.1 * (k + warm + run * (n + warm));
      rig.step(t_s);
      for (std::size_t c = 0; c < cases.size(); ++c) {
        obs = rig.rx.world().observables();
        const long a0 = support::allocation_count();
        const auto c0 = std::chrono::steady_clock::now();
        stages[c]->apply(rig.truth.t, rig.truth, obs);
        const auto c1 = std::chrono::steady_clock::now();
        if (k < 0) continue;
        allocs[c] += support::allocation_count() - a0;
        ns[c] += std::chrono::duration<double, std::nano>(c1 - c0).count();
      }
    }
    for (std::size_t c = 0; c < cases.size(); ++c) best[c] = std::min(best[c], ns[c] / n);
  }
  for (std::size_t c = 0; c < cases.size(); ++c)
    std::printf("%-10s %10.0f %12.3f\n", cases[c].name, best[c], static_cast<double>(allocs[c]) / (3.0 * n));
}

}  // namespace

int main(int argc, char** argv) {
  const std::string what = argc > 1 ? argv[1] : "all";
  const std::string nav_path =
      argc > 2 ? argv[2] : std::string(GNSSEMU_SOURCE_DIR) + "/tests/data/nav/brdc0010.22n";
  try {
    const orbit::NavData nav = orbit::read_rinex_nav(nav_path);
    const orbit::EphemerisStore store(nav.ephemerides);
    const time::GpsTime t0 = store.first_valid() + 8.0 * 3600.0;
    std::printf("faults_bench: %s, start %d/%.0f, u-blox M8 profile, static 48.87N 2.30E 100 m\n", nav_path.c_str(),
                t0.week(), t0.tow_s());
    const bool all = what == "all";
    if (all || what == "jam") jam_sweep(store, t0);
    if (all || what == "drag") drag(store, t0);
    if (all || what == "takeover") takeover(store, t0);
    if (all || what == "step") step(store, t0);
    if (all || what == "cost") cost(store, t0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "faults_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
