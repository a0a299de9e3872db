// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/stations/spp.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "core/atmosphere/receiver_corrections.hpp"
#include "core/common/error.hpp"
#include "core/common/gnss_systems.hpp"
#include "core/geo/geodesy.hpp"
#include "core/geo/local_frame.hpp"
#include "core/receiver/solution/weight_model.hpp"
#include "core/world/sky/sky.hpp"

namespace gnssemu::cli {

double receiver_correction_m(const orbit::KlobucharParams& k, const Lla& rx, double az_rad, double el_rad,
                             const time::GpsTime& t, const receiver::SolverConfig& solver, double* variance_m2,
                             double carrier_hz) {
  const double doy = t.fractional_day_of_year();
  const double iono_m = solver.iono == atmosphere::IonoCorrection::kKlobuchar
                            ? atmosphere::receiver_iono_delay_m(k, rx.lat_rad, rx.lon_rad, az_rad, el_rad, t.tow_s(),
                                                                kSpeedOfLight_m_s / carrier_hz)
                            : 0.0;
  // The solver's variance of the same correction (its sigma scales with the delay).
  if (variance_m2 != nullptr) *variance_m2 = receiver::correction_variance_m2(solver, iono_m, std::sin(el_rad));
  return iono_m + atmosphere::receiver_tropo_delay_m(rx.lat_rad, rx.height_m, el_rad, doy, solver.tropo);
}

int pseudorange_type(const observation::ObsHeader& header, GnssSystem s) {
  static constexpr std::array<std::array<const char*, 5>, kNumSystems> kPriority{{
      {"C1C", nullptr, nullptr, nullptr, nullptr},
      {"C1C", "C1P", nullptr, nullptr, nullptr},
      {"C1C", "C1A", "C1B", "C1X", "C1Z"},
      {"C2I", "C2Q", "C2X", nullptr, nullptr},
      {"C1C", "C1L", "C1S", "C1X", "C1Z"},
      {nullptr, nullptr, nullptr, nullptr, nullptr},
  }};
  for (const char* code : kPriority[static_cast<std::size_t>(s)]) {
    if (code == nullptr) break;
    const int i = header.type_index(s, code);
    if (i >= 0) return i;
  }
  return -1;
}

namespace {
// The pseudoranges reach the solver already corrected (receiver_correction_m
// at the mask position), so its own iono / tropo corrections stay off.
receiver::SolverConfig precorrected(receiver::SolverConfig s) {
  s.iono = atmosphere::IonoCorrection::kNone;
  s.tropo = atmosphere::TropoCorrection::kNone;
  return s;
}
// The first, unmasked and uncorrected solution of a cold start only places
// the mask and the corrections: its residuals carry the uncorrected
// atmosphere, so it is not tested (RTKLIB likewise corrects from its second
// iteration on and tests only the converged, corrected solution).
receiver::SolverConfig untested(receiver::SolverConfig s) {
  s.residual_test_pfa = 0.0;
  return s;
}
}  // namespace

SppEngine::SppEngine(const orbit::NavData& nav, const orbit::EphemerisStore& store,
                     const observation::ObsHeader& header, const receiver::ReceiverConfig& receiver,
                     SystemSet systems)
    : store_(store),
      klobuchar_(nav.klobuchar),
      rx_(receiver),
      solver_(precorrected(receiver.solver), receiver.max_pdop),
      cold_solver_(untested(precorrected(receiver.solver)), receiver.max_pdop) {
  receiver::validate(rx_);
  bool any = false;
  for (int k = 0; k < kNumSystems; ++k) {
    const auto sys = static_cast<GnssSystem>(k);
    const auto i = static_cast<std::size_t>(k);
    code_[i] = cn0_[i] = -1;
    if (!systems.has(sys)) continue;
    code_[i] = pseudorange_type(header, sys);
    if (code_[i] < 0) continue;
    any = true;
    std::string sn = header.types_of(sys)[static_cast<std::size_t>(code_[i])];
    sn[0] = 'S';
    cn0_[i] = header.type_index(sys, sn);
  }
  if (!any) {
    throw Error(fmt::format("observation file has no pseudoranges of {} (GPS C1C, GLONASS C1C, Galileo C1C/C1X, "
                            "BeiDou C2I, QZSS C1C; RINEX 2: C1)",
                            systems_text(systems).data()));
  }
}

bool SppEngine::run(const observation::ObsEpoch& epoch, const Ecef* site) {
  in_ = receiver::SolverInput{};
  in_.t_rx_local = epoch.t;
  in_.num_meas = 0;
  Lla site_lla;
  if (site != nullptr) site_lla = geo::lla_from_ecef(*site);
  for (const observation::SatObs& s : epoch.sats) {
    if (in_.num_meas >= kMaxSatsInView) break;
    const auto sys = static_cast<std::size_t>(s.sat.system);
    const observation::ObsValue* pr = s.get(code_[sys]);
    if (pr == nullptr || !(pr->value > 0.0)) continue;
    const SatId sat = s.sat;
    const orbit::Ephemeris* eph = store_.select(sat, epoch.t);
    if (eph == nullptr) continue;
    double corr_m = 0.0, corr_var_m2 = 0.0;
    if (site != nullptr) {
      const world::SkySat sky = world::sky_sat(*eph, epoch.t, *site, site_lla, Ecef{});
      if (!(sky.el_rad >= rx_.elevation_mask_rad)) continue;
      corr_m = receiver_correction_m(klobuchar_, site_lla, sky.az_rad, sky.el_rad, epoch.t, rx_.solver, &corr_var_m2,
                                     l1_carrier_hz(sat.system, eph->glo_channel));
    }
    receiver::Measurement& m = in_.meas[static_cast<std::size_t>(in_.num_meas)];
    m.eph = eph;
    // Corrections at the mask position (previous fix): the final pass is
    // within 100 m of the result, where they change by < 1 mm.
    m.pseudorange_m = pr->value - corr_m;
    m.correction_var_m2 = corr_var_m2;
    m.doppler_hz = 0.0;  // velocity is not reported by spp
    // S1C gives the solver's C/N0 weight term, as the live receiver's tracking does.
    const observation::ObsValue* sn = s.get(cn0_[sys]);
    m.cn0_dbhz = sn != nullptr && std::isfinite(sn->value) ? sn->value : 0.0;
    meas_sat_[static_cast<std::size_t>(in_.num_meas++)] = sat;
  }
  if (last_pos_m_) {
    in_.have_prior = true;
    in_.prior_pos_m = *last_pos_m_;
    in_.prior_clock_m = last_clock_m_;
  }
  (site != nullptr ? solver_ : cold_solver_).solve(in_, out_);
  return out_.type == receiver::FixType::k3D;
}

const SppEpoch& SppEngine::solve(const observation::ObsEpoch& epoch) {
  result_ = SppEpoch{};
  result_.t = epoch.t;
  // Mask at the previous fix, or at an unmasked first solution; repeat once
  // at the new fix if that changes which satellites are above the mask.
  std::optional<Ecef> at = last_pos_m_;
  if (!at) {
    if (!run(epoch, nullptr)) return result_;
    at = out_.pos_m;
  }
  bool ok = false;
  for (int pass = 0; pass < 3; ++pass) {
    ok = run(epoch, &*at);
    if (!ok) break;
    const Ecef moved = Ecef(out_.pos_m - *at);
    at = out_.pos_m;
    if (moved.norm() < 100.0) break;  // elevations change < 0.001 deg
  }
  if (!ok) return result_;
  result_.fix = true;
  result_.pos_m = out_.pos_m;
  result_.clock_m = out_.clock_m;
  result_.pdop = out_.dop.pdop;
  result_.nsat = out_.num_used;
  const Lla lla = out_.lla;
  // Used satellites only (fault exclusion may drop some of the measurements).
  std::size_t n = 0;
  for (int i = 0; i < in_.num_meas; ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    if (out_.excluded[k]) continue;
    result_.sat[n] = meas_sat_[k];
    result_.residual_m[n] = out_.residual_m[k];
    result_.el_rad[n] = world::sky_sat(*in_.meas[k].eph, epoch.t, out_.pos_m, lla, Ecef{}).el_rad;
    ++n;
  }
  last_pos_m_ = out_.pos_m;
  last_clock_m_ = out_.clock_m;
  return result_;
}

std::vector<Enu> spp_error_series(const observation::ObsData& obs, const orbit::NavData& nav,
                                  const orbit::EphemerisStore& store, const receiver::ReceiverConfig& receiver,
                                  const Ecef& station, double step_s, int* fixes, SystemSet systems) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (fixes != nullptr) *fixes = 0;
  if (obs.epochs.empty()) return {};
  SppEngine engine(nav, store, obs.header, receiver, systems);
  const geo::LocalFrame frame(geo::lla_from_ecef(station));
  const time::GpsTime t0 = obs.epochs.front().t;
  const long n_grid = std::lround((obs.epochs.back().t - t0) / step_s) + 1;
  std::vector<Enu> err(static_cast<std::size_t>(std::max(n_grid, 1L)), Enu(kNaN, kNaN, kNaN));
  for (const observation::ObsEpoch& e : obs.epochs) {
    const SppEpoch& s = engine.solve(e);
    if (!s.fix) continue;
    if (fixes != nullptr) ++*fixes;
    const long g = std::lround((e.t - t0) / step_s);
    if (g >= 0 && g < n_grid) err[static_cast<std::size_t>(g)] = frame.to_enu(s.pos_m);
  }
  return err;
}

std::vector<orbit::Ephemeris> rtklib_unique_ephemerides(const std::vector<orbit::Ephemeris>& ephemerides) {
  struct Key {
    int64_t ttr_s, toe_s;
    int sat;
    std::size_t index;
  };
  // RTKLIB's satellite numbers run G, R, E, J, C.
  constexpr std::array<int, kNumSystems> kOrder{0, 1, 2, 4, 3, 5};
  const auto whole_s = [](const time::GpsTime& t, double tow_s) {
    return static_cast<int64_t>(t.week()) * 604800 + static_cast<int64_t>(std::floor(tow_s));
  };
  std::vector<Key> keys;
  std::vector<orbit::Ephemeris> out;
  for (std::size_t i = 0; i < ephemerides.size(); ++i) {
    const orbit::Ephemeris& e = ephemerides[i];
    if (system_info(e.sat.system).orbit != OrbitKind::kKepler) {
      out.push_back(e);
      continue;
    }
    const int64_t toe_s = whole_s(e.toe, e.toe.tow_s());
    keys.push_back({e.transmit_known ? whole_s(e.toe, e.transmit_tow_s) : toe_s, toe_s,
                    kOrder[static_cast<std::size_t>(e.sat.system)] * 256 + e.sat.number, i});
  }
  std::stable_sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    if (a.ttr_s != b.ttr_s) return a.ttr_s < b.ttr_s;
    if (a.toe_s != b.toe_s) return a.toe_s < b.toe_s;
    return a.sat < b.sat;
  });
  for (std::size_t k = 0; k < keys.size(); ++k) {
    if (k > 0) {
      const orbit::Ephemeris& prev = ephemerides[keys[k - 1].index];
      const orbit::Ephemeris& cur = ephemerides[keys[k].index];
      // Compared with the last kept set: dropped ones are skipped over.
      if (cur.sat == prev.sat && cur.iode == prev.iode) {
        keys[k].index = keys[k - 1].index;
        continue;
      }
    }
    out.push_back(ephemerides[keys[k].index]);
  }
  // pntpos.c gettgd: the group delay of a satellite's first set in that
  // order, whichever set is selected for its orbit and clock.
  std::array<const orbit::Ephemeris*, kNumSats> first{};
  for (orbit::Ephemeris& e : out) {
    if (system_info(e.sat.system).orbit != OrbitKind::kKepler || !e.sat.valid()) continue;
    const orbit::Ephemeris*& f = first[static_cast<std::size_t>(e.sat.index())];
    if (f == nullptr) f = &e;
    e.tgd_s = f->tgd_s;
  }
  return out;
}

SppSummary write_spp(const observation::ObsData& obs, const orbit::NavData& nav,
                     const receiver::ReceiverConfig& receiver, const std::optional<Ecef>& station, std::ostream& out,
                     SystemSet systems, bool rtklib_sets) {
  const orbit::EphemerisStore store(rtklib_sets ? rtklib_unique_ephemerides(nav.ephemerides) : nav.ephemerides);
  if (store.size() == 0) throw Error(nav.source, 0, "no ephemerides in the file");
  SppEngine engine(nav, store, obs.header, receiver, systems);
  std::optional<geo::LocalFrame> frame;
  if (station) frame.emplace(geo::lla_from_ecef(*station));
  out << "gps_week,tow_s,x_m,y_m,z_m,nsat,pdop" << (station ? ",e_m,n_m,u_m" : "") << '\n';
  SppSummary sum;
  for (const observation::ObsEpoch& e : obs.epochs) {
    ++sum.epochs;
    const SppEpoch& r = engine.solve(e);
    if (!r.fix) continue;
    ++sum.fixes;
    out << fmt::format("{},{:.3f},{:.4f},{:.4f},{:.4f},{},{:.3f}", r.t.week(), r.t.tow_s(), r.pos_m.x, r.pos_m.y,
                       r.pos_m.z, r.nsat, r.pdop);
    if (frame) {
      const Enu d = frame->to_enu(r.pos_m);
      out << fmt::format(",{:.4f},{:.4f},{:.4f}", d.x, d.y, d.z);
    }
    out << '\n';
  }
  return sum;
}

}  // namespace gnssemu::cli
