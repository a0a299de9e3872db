// SPDX-License-Identifier: Apache-2.0
#include "core/faults/fault_event.hpp"

#include <cmath>

#include "core/common/constants.hpp"

namespace gnssemu::faults {

namespace {

constexpr std::uint8_t bit(FaultType t) { return static_cast<std::uint8_t>(1u << static_cast<int>(t)); }
constexpr std::uint8_t kJam = bit(FaultType::kJammer), kSpoof = bit(FaultType::kSpoofer),
                       kSky = bit(FaultType::kSkyBlock), kSat = bit(FaultType::kSatellite),
                       kPort = bit(FaultType::kPort);

// One row per Param, in Param order (checked below).
constexpr ParamSpec kSpecs[] = {
    {Param::kJsDb, "js_db", {-50.0, 120.0, "dB"}, kJam, true, false, false,
     "jammer-to-signal ratio at the antenna against the nominal L1 C/A power (-158.5 dBW), dB"},
    {Param::kEirpDbw, "eirp_dbw", {-100.0, 60.0, "dBW"}, kJam, true, false, false, "jammer EIRP, dBW (1 W = 0 dBW)"},
    {Param::kDistanceM, "distance_m", {0.1, 1.0e7, "m"}, kJam, true, false, false,
     "jammer distance from the antenna, m (instead of lat/lon)"},
    {Param::kLatDeg, "lat_deg", {-90.0, 90.0, "deg"}, kJam, true, false, false, "jammer latitude, deg"},
    {Param::kLonDeg, "lon_deg", {-180.0, 180.0, "deg"}, kJam, true, false, false, "jammer longitude, deg"},
    {Param::kHeightM, "height_m", {-1000.0, 1.0e5, "m"}, kJam, true, false, false,
     "jammer height above the ellipsoid, m (default: the receiver's)"},
    {Param::kGainDbi, "gain_dbi", {-40.0, 30.0, "dBi"}, kJam, true, false, false,
     "receive antenna gain toward the jammer, dBi (default: the antenna pattern at the jammer's elevation)"},
    {Param::kFreqMhz, "freq_mhz", {1100.0, 1700.0, "MHz"}, kJam, true, false, false,
     "centre of the jammer's spectrum, MHz (default 1575.42, GPS L1)"},
    {Param::kBandwidthMhz, "bandwidth_mhz", {0.0, 200.0, "MHz"}, kJam, true, false, false,
     "full width of the jammer's spectrum, MHz (default: wideband 2.046, narrowband and cw a line, 0); a satellite "
     "is hit by the part inside its signal's main lobe"},
    {Param::kPowerAdvantageDb, "power_advantage_db", {-20.0, 40.0, "dB"}, kSpoof, true, false, false,
     "spoofed signal power over the strongest authentic signal, dB (default 6)"},
    {Param::kCaptureMarginDb, "capture_margin_db", {0.0, 20.0, "dB"}, kSpoof, true, false, false,
     "spoofed-over-authentic power a tracking loop needs to be captured, dB (default 3)"},
    {Param::kDragSpeedMS, "drag_speed_m_s", {0.0, 1000.0, "m/s"}, kSpoof, true, false, false,
     "horizontal speed of the false position away from the truth, m/s"},
    {Param::kDragAccelMS2, "drag_accel_m_s2", {0.0, 100.0, "m/s^2"}, kSpoof, true, false, false,
     "horizontal acceleration of the drag-off, m/s^2"},
    {Param::kDragHeadingDeg, "drag_heading_deg", {0.0, 360.0, "deg"}, kSpoof, true, false, false,
     "direction of the drag-off, deg from true north"},
    {Param::kDragUpMS, "drag_up_m_s", {-100.0, 100.0, "m/s"}, kSpoof, true, false, false,
     "vertical speed of the false position, m/s"},
    {Param::kPushRateNsS, "push_rate_ns_s", {-1.0e6, 1.0e6, "ns/s"}, kSpoof, true, false, false,
     "time push: rate of the false clock offset, ns/s"},
    {Param::kDelayUs, "delay_us", {0.0, 1.0e6, "us"}, kSpoof, true, false, false, "meaconing replay delay, us"},
    {Param::kOffsetEastM, "offset_east_m", {-1.0e7, 1.0e7, "m"}, kSpoof, true, false, false,
     "false position east of the truth (takeover, meaconing antenna), m"},
    {Param::kOffsetNorthM, "offset_north_m", {-1.0e7, 1.0e7, "m"}, kSpoof, true, false, false,
     "false position north of the truth, m"},
    {Param::kOffsetUpM, "offset_up_m", {-1.0e5, 1.0e5, "m"}, kSpoof, true, false, false,
     "false position above the truth, m"},
    {Param::kClockJumpUs, "clock_jump_us", {-1.0e6, 1.0e6, "us"}, static_cast<std::uint8_t>(kSpoof | kSat), true,
     false, false, "spoofer: false clock offset at takeover; satellite: its clock jump, us"},
    {Param::kSystems, "systems", {1.0, static_cast<double>(SystemSet::all().bits()), ""}, kSpoof, false, true, false,
     "systems the spoofer forges, RINEX letters (\"G\", \"G,R,E,C\"; default \"G\": GPS L1 C/A only, as "
     "gps-sdr-sim and other SDR spoofers); the others stay authentic",
     false, true},
    {Param::kAzFromDeg, "az_from_deg", {0.0, 360.0, "deg"}, kSky, true, false, false,
     "blocked sector from this azimuth clockwise, deg"},
    {Param::kAzToDeg, "az_to_deg", {0.0, 360.0, "deg"}, kSky, true, false, false, "blocked sector to this azimuth, deg"},
    {Param::kElMinDeg, "el_min_deg", {0.0, 90.0, "deg"}, kSky, true, false, false, "lowest blocked elevation, deg"},
    {Param::kElMaxDeg, "el_max_deg", {0.0, 90.0, "deg"}, kSky, true, false, false, "highest blocked elevation, deg"},
    {Param::kLossDb, "loss_db", {0.0, 100.0, "dB"}, kSky, true, false, false,
     "attenuation instead of full blockage, dB"},
    {Param::kPrn, "prn", {1.0, sat_param(SatId::from_index(kNumSats - 1)), ""}, kSat, false, true, false,
     "the faulty satellite: a GPS PRN (5) or a RINEX name (\"G05\", \"R12\", \"E11\", \"C19\", \"J02\", \"S23\")", true},
    {Param::kBiasM, "bias_m", {-1.0e6, 1.0e6, "m"}, kSat, true, false, false,
     "pseudorange step (a [from, to] ramp is a ramp), m"},
    {Param::kRateMS, "rate_m_s", {-1.0e4, 1.0e4, "m/s"}, kSat, true, false, false,
     "pseudorange ramp rate from the event start (a runaway clock), m/s"},
    {Param::kEphRadialM, "eph_radial_m", {-1.0e5, 1.0e5, "m"}, kSat, true, false, false,
     "broadcast ephemeris error: semi-major axis, m"},
    {Param::kEphAlongM, "eph_along_m", {-1.0e5, 1.0e5, "m"}, kSat, true, false, false,
     "broadcast ephemeris error: along track (mean anomaly), m"},
    {Param::kUnhealthy, "unhealthy", {0.0, 1.0, ""}, kSat, false, true, true,
     "broadcast health set to unhealthy (true/false)"},
    {Param::kOutput, "output", {0.0, 63.0, ""}, kPort, false, true, false,
     "[[output]] index (0-based) the link fault acts on (default: all)"},
    {Param::kProbability, "probability", {0.0, 1.0, ""}, kPort, true, false, false,
     "byte_loss / corrupt / drop: probability per byte or message"},
    {Param::kLatencyMs, "latency_ms", {0.0, 60000.0, "ms"}, kPort, true, false, false, "latency: added delay, ms"},
    {Param::kRateHz, "rate_hz", {0.01, 10.0, "Hz"}, kPort, true, false, false, "rate: output rate, Hz"},
    {Param::kFixType, "fix_type", {0.0, 5.0, ""}, kPort, false, true, false, "wrong_fix: fix type reported (0..5)"},
};
static_assert(std::size(kSpecs) == kParamCount);
constexpr bool in_order() {
  for (int i = 0; i < kParamCount; ++i)
    if (static_cast<int>(kSpecs[i].id) != i) return false;
  return true;
}
static_assert(in_order(), "kSpecs rows follow Param order");

constexpr std::string_view kTypeNames[] = {"jammer", "spoofer", "outage", "sky_block", "satellite", "port"};
constexpr std::string_view kJammerKinds[] = {"wideband", "narrowband", "cw"};
constexpr std::string_view kSpoofModes[] = {"drag", "time_push", "meacon", "takeover"};
constexpr std::string_view kOutageKinds[] = {"blockage", "open", "short"};
constexpr std::string_view kLinkFaults[] = {"byte_loss", "corrupt", "drop",      "latency",     "freeze",
                                            "stop",      "rate",    "wrong_fix", "rtcm_outage", "rtcm_stale"};

}  // namespace

std::string_view type_name(FaultType t) noexcept { return kTypeNames[static_cast<int>(t)]; }

std::optional<FaultType> type_from_name(std::string_view name) noexcept {
  for (int i = 0; i < kFaultTypeCount; ++i)
    if (kTypeNames[i] == name) return static_cast<FaultType>(i);
  return std::nullopt;
}

std::span<const ParamSpec> param_specs() noexcept { return kSpecs; }
const ParamSpec& spec_of(Param p) noexcept { return kSpecs[static_cast<int>(p)]; }

const ParamSpec* find_param(FaultType t, std::string_view name) noexcept {
  for (const ParamSpec& s : kSpecs)
    if (s.name == name && (s.types & bit(t)) != 0) return &s;
  return nullptr;
}

std::string_view mode_key(FaultType t) noexcept {
  switch (t) {
    case FaultType::kJammer: return "kind";
    case FaultType::kSpoofer: return "mode";
    case FaultType::kOutage: return "antenna";
    case FaultType::kPort: return "fault";
    default: return {};
  }
}

std::span<const std::string_view> mode_names(FaultType t) noexcept {
  switch (t) {
    case FaultType::kJammer: return kJammerKinds;
    case FaultType::kSpoofer: return kSpoofModes;
    case FaultType::kOutage: return kOutageKinds;
    case FaultType::kPort: return kLinkFaults;
    default: return {};
  }
}

std::optional<SatId> sat_from_param(double v) noexcept {
  if (!(v >= 0.0 && v < 256.0 * kNumSystems) || v != std::floor(v)) return std::nullopt;
  const int code = static_cast<int>(v);
  const SatId sat(static_cast<GnssSystem>(code >> 8), code & 0xFF);
  if (!sat.valid()) return std::nullopt;
  return sat;
}

std::string systems_param_text(double v) {
  if (!(v >= 1.0 && v <= SystemSet::all().bits()) || v != std::floor(v)) return format_number(v);
  return std::string(systems_text(SystemSet(static_cast<std::uint8_t>(v))).data());
}

std::string sat_param_text(double v) {
  const auto sat = sat_from_param(v);
  if (!sat || sat->system == GnssSystem::kGps) return format_number(v);
  return std::string(sat_name(*sat).data());
}

double default_value(Param p) noexcept {
  switch (p) {
    case Param::kPowerAdvantageDb: return 6.0;
    case Param::kCaptureMarginDb: return 3.0;
    case Param::kAzToDeg: return 360.0;
    case Param::kElMaxDeg: return 90.0;
    case Param::kOutput: return -1.0;  // every output
    case Param::kFreqMhz: return kL1Freq_hz * 1e-6;
    case Param::kSystems: return static_cast<double>(SystemSet::only(GnssSystem::kGps).bits());
    default: return 0.0;
  }
}

double FaultEvent::value(Param p, double f) const noexcept {
  return has(p) ? param(p).at(f) : default_value(p);
}

double FaultEvent::fraction_at(double s) const noexcept {
  if (!std::isfinite(duration_s) || !(duration_s > 0.0)) return 0.0;
  const double f = (s - start_s) / duration_s;
  return f < 0.0 ? 0.0 : f > 1.0 ? 1.0 : f;
}

std::string describe(const FaultEvent& e, double s) {
  std::string out;
  const auto names = mode_names(e.type);
  if (!names.empty() && e.mode < names.size()) {
    out += std::string(mode_key(e.type)) + "=" + std::string(names[e.mode]);
  }
  const double f = e.fraction_at(s);
  for (const ParamSpec& p : kSpecs) {
    if (!e.has(p.id)) continue;
    if (!out.empty()) out += ' ';
    const double v = e.value(p.id, f);
    out += std::string(p.name) + "=" +
           (p.boolean     ? std::string(v >= 0.5 ? "true" : "false")
            : p.satellite ? sat_param_text(v)
            : p.systems   ? systems_param_text(v)
                          : format_number(v));
  }
  return out;
}

std::optional<std::string> check_event(const FaultEvent& e) {
  if (!(e.start_s >= 0.0) || !std::isfinite(e.start_s)) return "start_s: must be a finite number >= 0";
  if (!(e.duration_s > 0.0)) return "duration_s: must be > 0";
  if (e.mode >= mode_names(e.type).size() && !mode_names(e.type).empty()) return std::string(mode_key(e.type)) + ": out of range";
  for (const ParamSpec& s : kSpecs) {
    if (!e.has(s.id)) continue;
    if ((s.types & bit(e.type)) == 0) {
      return std::string(s.name) + ": not a parameter of type " + std::string(type_name(e.type));
    }
    const Ramp& r = e.param(s.id);
    for (double v : {r.from, r.to}) {
      if (s.satellite && !sat_from_param(v)) {
        return std::string(s.name) + ": " + sat_param_text(v) +
               " is out of range: not a satellite (a GPS PRN 1..32 or a RINEX name such as G05, E11)";
      }
      if (!s.range.contains(v)) {
        return std::string(s.name) + ": " + format_number(v) + " is out of range " + format_range(s.range);
      }
      if (s.integer && v != std::floor(v)) return std::string(s.name) + ": must be a whole number";
    }
    if (r.ramped() && !s.rampable) return std::string(s.name) + ": cannot be ramped";
    if (r.ramped() && !std::isfinite(e.duration_s)) {
      return std::string(s.name) + ": a [from, to] ramp needs a finite duration_s";
    }
  }
  const auto has = [&](Param p) { return e.has(p); };
  switch (e.type) {
    case FaultType::kJammer: {
      const bool js = has(Param::kJsDb);
      const bool src = has(Param::kEirpDbw);
      const bool where = has(Param::kDistanceM) || has(Param::kLatDeg) || has(Param::kLonDeg);
      if (js && (src || where)) return "js_db: give either js_db or eirp_dbw with a position, not both";
      if (!js && !src) return "jammer: give js_db, or eirp_dbw with distance_m or lat_deg/lon_deg";
      if (src && !where) return "eirp_dbw: needs distance_m or lat_deg and lon_deg";
      if (has(Param::kDistanceM) && (has(Param::kLatDeg) || has(Param::kLonDeg))) {
        return "distance_m: give either distance_m or lat_deg/lon_deg, not both";
      }
      if (has(Param::kLatDeg) != has(Param::kLonDeg)) return "lat_deg: lat_deg and lon_deg go together";
      if (js && has(Param::kGainDbi)) return "gain_dbi: only with eirp_dbw (js_db is at the antenna output)";
      break;
    }
    case FaultType::kSatellite:
      if (!has(Param::kPrn)) return "satellite: prn is required";
      break;
    case FaultType::kSkyBlock:
      if (e.value(Param::kElMinDeg, 0.0) > e.value(Param::kElMaxDeg, 0.0) ||
          e.value(Param::kElMinDeg, 1.0) > e.value(Param::kElMaxDeg, 1.0)) {
        return "el_min_deg: must not exceed el_max_deg";
      }
      break;
    default: break;
  }
  return std::nullopt;
}

}  // namespace gnssemu::faults
