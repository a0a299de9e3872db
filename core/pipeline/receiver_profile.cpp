// SPDX-License-Identifier: Apache-2.0
#include "core/pipeline/receiver_profile.hpp"

#include <string>

#include "core/common/error.hpp"

namespace gnssemu::pipeline {

namespace {

// The pooled fit of the five station-days (NYA1 2024-124 and -127, ESBC
// 2020-177, S6 2023-248 00-12 h, ROAP 2009-181; mask 10 deg, 30 s;
// 12960 epochs, 121251 residuals): gnssemu calibrate with every day's
// --obs/--nav/--station, docs/validation.md.
constexpr double kKlobucharScale = 0.765;
constexpr double kIonoScaleSigma = 0.408;     // relative
constexpr double kIonoScaleTau_s = 38800.0;
constexpr double kIonoSigma_tecu = 0.96;      // per line of sight
constexpr double kIonoTau_s = 1360.0;
constexpr double kGradientEquatorward_m = 0.326;  // fitted north -0.326 m at 36-79 N
constexpr double kGradientEast_m = -0.234;
constexpr double kGradientSigma_m = 0.458;
constexpr double kGradientTau_s = 19000.0;
constexpr double kOrbitClockSigma_m = 0.652;
constexpr double kOrbitClockTau_s = 5430.0;
constexpr double kMultipathSigma_m = 0.018;   // zenith, / sin(el)
constexpr double kMultipathTau_s = 60.0;
// Geodetic: S1C of NYA1 and ESBC (85475 samples, RMS 1.23 dB about the
// curve): 53.3 dB-Hz at the zenith (20 200 km), 34.8 dB-Hz at the horizon;
// the DLL's white part at 30 s (carrier-aided, narrow): B_L 0.080 Hz.
constexpr double kGeodeticZenithGain_dbi = 7.99;
constexpr double kGeodeticHorizonGain_dbi = -8.38;
constexpr double kGeodeticLoopBandwidth_hz = 0.080;
// u-blox M8 with a patch antenna: NEO-M8N NAV-SAT (Adelaide, static, 14
// satellites; tools/validation/ublox_cn0.py): 43.0 dB-Hz at the zenith,
// -13.7 dB to the horizon, as gains of the default link budget. Code loop:
// NEO-M8T RXM-RAWX prStdev 0.32 m at 42-51 dB-Hz and 2.3 m at 30 dB-Hz;
// the DLL model gives 0.32 m at 45 dB-Hz and 1.9 m at 30 dB-Hz with 0.15 Hz.
constexpr double kM8ZenithGain_dbi = -2.3;
constexpr double kM8HorizonGain_dbi = -13.9;
constexpr double kM8LoopBandwidth_hz = 0.15;

}  // namespace

ReceiverProfile receiver_profile(std::string_view name) {
  if (name == "ublox_m8") return ReceiverProfile::kUbloxM8;
  if (name == "geodetic") return ReceiverProfile::kGeodetic;
  throw Error("receiver profile '" + std::string(name) + "' is not one of ublox_m8, geodetic");
}

std::string_view profile_name(ReceiverProfile p) noexcept {
  return p == ReceiverProfile::kGeodetic ? "geodetic" : "ublox_m8";
}

PipelineConfig apply_profile(PipelineConfig c, ReceiverProfile p, double lat_rad) {
  world::WorldConfig& w = c.world;
  world::ErrorModelConfig& e = w.errors;
  // The signals in space: the same for every receiver.
  e.orbit_clock = {kOrbitClockSigma_m, kOrbitClockTau_s};
  e.multipath = {kMultipathSigma_m, kMultipathTau_s};
  e.iono_scale = {kIonoScaleSigma, kIonoScaleTau_s};
  e.gradient = {};
  e.gradient.north_m = lat_rad < 0.0 ? kGradientEquatorward_m : -kGradientEquatorward_m;
  e.gradient.east_m = kGradientEast_m;
  e.gradient.process = {kGradientSigma_m, kGradientTau_s};
  world::use_klobuchar_ionosphere(w.atmosphere, kKlobucharScale, kIonoSigma_tecu, kIonoTau_s);
  world::use_receiver_troposphere(w.atmosphere);  // the fit gives no offset
  // The device: antenna and code loop.
  e.thermal_model = world::ThermalModel::kDll;
  const bool geodetic = p == ReceiverProfile::kGeodetic;
  w.signal.link.antenna.zenith_gain_dbi = geodetic ? kGeodeticZenithGain_dbi : kM8ZenithGain_dbi;
  w.signal.link.antenna.horizon_gain_dbi = geodetic ? kGeodeticHorizonGain_dbi : kM8HorizonGain_dbi;
  w.signal.dll.loop_bandwidth_hz = geodetic ? kGeodeticLoopBandwidth_hz : kM8LoopBandwidth_hz;
  // Station receivers' positions are compared as single-point solutions of
  // their raw code (RINEX): no navigation filter. The M8 filters.
  if (geodetic) c.receiver.filter.type = receiver::NavFilterType::kNone;
  return c;
}

}  // namespace gnssemu::pipeline
