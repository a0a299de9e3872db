// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/nmea/nmea_encoder.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/protocol/nmea/nmea_format.hpp"
#include "core/protocol/nmea/nmea_numbering.hpp"
#include "core/protocol/nmea/nmea_sky.hpp"
#include "core/protocol/nmea/nmea_utc.hpp"

namespace gnssemu::protocol::nmea {

namespace {

using receiver::Fix;
using receiver::FixType;
using receiver::SatInfo;

constexpr int kMaxGgaSats = 12;  // u-blox GGA numSV is 0-12 (every u-blox log: 12 with up to 25 used)
constexpr int kSatsPerGsv = 4;
constexpr double kKnotsPerMps = 3600.0 / 1852.0;
constexpr double kKmhPerMps = 3.6;
// Field ranges that keep every sentence within 82 characters. u-blox stops
// navigating far inside them (50 km altitude, 500 m/s).
constexpr double kMaxAbsAltitude_m = 99999.9;
constexpr double kMaxAbsGeoidSep_m = 999.9;
constexpr double kMaxSpeed_m_s = 5000.0;
constexpr double kMaxSigma_m = 99999.9;

using Talker = std::array<char, 2>;

/// Everything the sentences print, derived once from the Fix.
struct Epoch {
  NmeaVersion version = NmeaVersion::k411;
  bool v4 = false;        // NMEA 4.10 / 4.11 extra fields
  bool pos_mode_field = true;  // RMC, VTG, GLL posMode (NMEA 2.3 and later)
  bool has_time = false;
  bool has_fix = false;   // a position to print (a GNSS fix or dead reckoning)
  // The fix type as the sentences report it (u-blox NMEA position fix flags).
  int quality = 0;        // GGA: 0 none, 1 GNSS fix, 6 dead reckoning
  char status = 'V';      // RMC, GLL: A valid, V invalid
  char pos_mode = 'N';    // RMC, VTG, GLL: N none, A autonomous, E estimated (dead reckoning)
  int nav_mode = 1;       // GSA: 1 none, 2 2D, 3 3D
  double diff_age_s = -1.0;  // GGA age of differential corrections, s; < 0: empty
  int diff_station = -1;     // GGA reference station id; < 0: empty
  Talker main{'G', 'P'};  // talker of every sentence but GSV
  NmeaDevice device = NmeaDevice::kM9;
  UtcStamp utc;
  double lat_deg = 0.0, lon_deg = 0.0;
  double alt_msl_m = 0.0, geoid_sep_m = 0.0;
  double speed_m_s = 0.0;
  bool course_valid = false;
  double course_deg = 0.0;
  double pdop = receiver::Dop::kNoDop, hdop = receiver::Dop::kNoDop, vdop = receiver::Dop::kNoDop;
};

/// "GP" + "RMC".
struct Address {
  std::array<char, 5> chars{};
  Address(Talker t, std::string_view formatter) noexcept : chars{t[0], t[1], formatter[0], formatter[1], formatter[2]} {}
  operator std::string_view() const noexcept { return {chars.data(), chars.size()}; }
};

/// The main talker: CFG-NMEA's override, else GN when more than one NMEA
/// system is enabled, else that system's talker (u-blox "Multi-GNSS
/// considerations": the talker follows the GNSS the channels are assigned to).
Talker main_talker(const NmeaSky& sky, const NmeaSettings& cfg) {
  switch (cfg.main_talker) {
    case MainTalker::kGp: return {'G', 'P'};
    case MainTalker::kGl: return {'G', 'L'};
    case MainTalker::kGn: return {'G', 'N'};
    case MainTalker::kGa: return {'G', 'A'};
    case MainTalker::kGb: return cfg.beidou_talker;
    case MainTalker::kGq: return {'G', 'Q'};
    case MainTalker::kAuto: break;
  }
  if (sky.num_present() > 1) return {'G', 'N'};
  for (int k = 0; k < kNumNmeaSystems; ++k) {
    if (sky.present(static_cast<NmeaSystem>(k))) return system_talker(static_cast<NmeaSystem>(k), cfg);
  }
  return {'G', 'P'};
}

double clamp_finite(double v, double lo, double hi) {
  return std::isfinite(v) ? std::clamp(v, lo, hi) : v;
}

double dop_or_none(double dop, bool has_fix) {
  if (!has_fix || !std::isfinite(dop) || dop < 0.0) return receiver::Dop::kNoDop;
  return std::min(dop, receiver::Dop::kNoDop);
}

int rounded_deg(double rad) {
  const double deg = rad * kRadToDeg;
  return std::isfinite(deg) ? static_cast<int>(std::lround(deg)) : 0;
}

// The fix-type fields for a reported type, after the u-blox NMEA position
// fix flags table (UBX-13003221 / ZED-F9P interface description): dead
// reckoning is GGA quality 6, mode E, GSA navMode 2; GNSS + dead reckoning
// reads as a 3D GNSS fix; time only has no position, so it reads as none.
void set_fix_flags(Epoch& e, ReportedFix f) {
  switch (f) {
    case ReportedFix::kDeadReckoning: e.quality = 6; e.status = 'A'; e.pos_mode = 'E'; e.nav_mode = 2; return;
    case ReportedFix::k2D: e.quality = 1; e.status = 'A'; e.pos_mode = 'A'; e.nav_mode = 2; return;
    case ReportedFix::k3D:
    case ReportedFix::kGnssDeadReckoning: e.quality = 1; e.status = 'A'; e.pos_mode = 'A'; e.nav_mode = 3; return;
    case ReportedFix::kNoFix:
    case ReportedFix::kTimeOnly: e.quality = 0; e.status = 'V'; e.pos_mode = 'N'; e.nav_mode = 1; return;
  }
}

Epoch derive(const Fix& fix, const NmeaConfig& cfg, FixOverride reported) {
  Epoch e;
  e.version = cfg.version;
  e.device = cfg.device;
  e.v4 = has_system_ids(cfg.version);
  e.pos_mode_field = cfg.version != NmeaVersion::k21;
  e.has_time = fix.time_valid;
  if (e.has_time) e.utc = utc_stamp(fix.t, fix.leap_seconds, fix.in_leap_second);
  // A position needs time (a receiver cannot navigate without it) and finite numbers.
  e.has_fix = fix.type != FixType::kNone && e.has_time && std::isfinite(fix.lla.lat_rad) &&
              std::isfinite(fix.lla.lon_rad) && std::isfinite(fix.lla.height_m);
  if (e.has_fix) {
    e.lat_deg = std::clamp(fix.lla.lat_rad * kRadToDeg, -90.0, 90.0);
    e.lon_deg = std::remainder(fix.lla.lon_rad * kRadToDeg, 360.0);  // [-180, 180]
    const double sep = std::isfinite(fix.geoid_sep_m) ? fix.geoid_sep_m : 0.0;
    e.geoid_sep_m = clamp_finite(fix.geoid_sep_m, -kMaxAbsGeoidSep_m, kMaxAbsGeoidSep_m);
    e.alt_msl_m = std::clamp(fix.lla.height_m - sep, -kMaxAbsAltitude_m, kMaxAbsAltitude_m);
    e.speed_m_s = clamp_finite(std::fabs(fix.speed_m_s), 0.0, kMaxSpeed_m_s);
    if (std::isfinite(e.speed_m_s) && e.speed_m_s >= cfg.course_min_speed_m_s &&
        std::isfinite(fix.course_rad)) {
      double deg = std::fmod(fix.course_rad * kRadToDeg, 360.0);
      if (deg < 0.0) deg += 360.0;
      if (std::llround(deg * 100.0) >= 36000) deg = 0.0;  // 359.996 prints as 0.00
      e.course_valid = true;
      e.course_deg = deg;
    }
    e.pdop = dop_or_none(fix.dop.pdop, true);
    e.hdop = dop_or_none(fix.dop.hdop, true);
    e.vdop = dop_or_none(fix.dop.vdop, true);
  }
  if (reported) {
    set_fix_flags(e, *reported);
  } else if (e.has_fix) {
    set_fix_flags(e, fix.type == FixType::kDeadReckoning ? ReportedFix::kDeadReckoning
                     : fix.type == FixType::k3D          ? ReportedFix::k3D
                                                         : ReportedFix::k2D);
  }
  // Differential and RTK solutions (position fix flags: DGNSS quality 2 mode D,
  // RTK float 5 F, RTK fixed 4 R), with the correction age and station the
  // real F9K log prints ("...,M,0.0,2000"; receiver-logs/f9k_span_drive).
  if (!reported && e.has_fix && fix.type != FixType::kDeadReckoning && fix.diff_soln) {
    switch (fix.carr_soln) {
      case receiver::CarrierSolution::kFixed: e.quality = 4; e.pos_mode = 'R'; break;
      case receiver::CarrierSolution::kFloat: e.quality = 5; e.pos_mode = 'F'; break;
      case receiver::CarrierSolution::kNone: e.quality = 2; e.pos_mode = 'D'; break;
    }
    if (std::isfinite(fix.corr_age_s) && fix.corr_age_s >= 0.0) e.diff_age_s = std::min(fix.corr_age_s, 999.9);
    if (fix.ref_station_id >= 0) e.diff_station = std::min(fix.ref_station_id, 4095);
  }
  // NMEA 2.1 has no dead-reckoning quality: u-blox reports 1 (position fix flags).
  if (!e.pos_mode_field && e.quality == 6) e.quality = 1;
  return e;
}

void put_time(SentenceWriter& w, const Epoch& e) {
  if (e.has_time) {
    w.time_of_day(e.utc.hour, e.utc.minute, e.utc.second, e.utc.centisecond);
  } else {
    w.empty();
  }
}

void put_position(SentenceWriter& w, const Epoch& e) {
  if (e.has_fix) {
    w.latitude(e.lat_deg);
    w.longitude(e.lon_deg);
  } else {
    for (int i = 0; i < 4; ++i) w.empty();
  }
}


/// Appends finished sentences to out and tells the sink where each ends.
struct Emit {
  std::string& out;
  SentenceSink* sink;
  Sentence sentence;
  void operator()(SentenceWriter& w) const noexcept {
    const std::string_view s = w.finish();
    out.append(s.data(), s.size());
    if (sink != nullptr) sink->on_sentence(sentence, out.size());
  }
};

// RMC time,status,lat,NS,lon,EW,spd,cog,date,mv,mvEW[,posMode][,navStatus] (ref §3).
void write_rmc(const Epoch& e, const Emit& emit) {
  SentenceWriter w(Address(e.main, "RMC"));
  put_time(w, e);
  w.character(e.status);
  put_position(w, e);
  if (e.has_fix) {
    w.fixed(e.speed_m_s * kKnotsPerMps, 3);
  } else {
    w.empty();
  }
  if (e.course_valid) {
    w.fixed(e.course_deg, 2);
  } else {
    w.empty();
  }
  if (e.has_time) {
    w.date_ddmmyy(e.utc.day, e.utc.month, e.utc.year);
  } else {
    w.empty();
  }
  w.empty();  // magnetic variation: u-blox leaves it empty
  w.empty();
  if (e.pos_mode_field) w.character(e.pos_mode);
  if (e.v4) w.character('V');  // navStatus: u-blox always sends V
  emit(w);
}

// VTG cogt,T,cogm,M,sogn,N,sogk,K[,posMode]; all units empty without a fix (ref §6).
void write_vtg(const Epoch& e, const Emit& emit) {
  SentenceWriter w(Address(e.main, "VTG"));
  if (e.has_fix) {
    if (e.course_valid) {
      w.fixed(e.course_deg, 2);
    } else {
      w.empty();
    }
    w.character('T');
    w.empty();
    w.character('M');
    w.fixed(e.speed_m_s * kKnotsPerMps, 3);
    w.character('N');
    w.fixed(e.speed_m_s * kKmhPerMps, 3);
    w.character('K');
  } else {
    for (int i = 0; i < 8; ++i) w.empty();
  }
  if (e.pos_mode_field) w.character(e.pos_mode);
  emit(w);
}

// GNS posMode characters: GPS, GLONASS up to 4.0; + Galileo, BeiDou in 4.10;
// + QZSS, NavIC in 4.11 (the systems each NMEA version defines; docs/nmea.md).
int gns_mode_chars(NmeaVersion v) {
  return v == NmeaVersion::k411 ? 6 : v == NmeaVersion::k410 ? 4 : 2;
}

// GNS time,lat,NS,lon,EW,posMode,numSV,HDOP,alt,sep,diffAge,diffStation[,navStatus]
// (ref §3). numSV is not capped (a u-blox M8 log shows 16 and 19 beside GGA's 12).
void write_gns(const Epoch& e, const NmeaSky& sky, const Emit& emit) {
  SentenceWriter w(Address(e.main, "GNS"));
  put_time(w, e);
  put_position(w, e);
  std::array<char, 6> mode{};
  const int chars = gns_mode_chars(e.version);
  for (int k = 0; k < chars; ++k) {
    const auto s = static_cast<NmeaSystem>(k);
    const bool listed = k < kNumNmeaSystems && sky.present(s);
    char c = 'N';
    if (e.pos_mode == 'E') {
      c = listed ? 'E' : 'N';
    } else if (e.pos_mode != 'N' && listed && sky.used(s) > 0) {
      c = e.pos_mode;
    }
    mode[static_cast<std::size_t>(k)] = c;
  }
  w.text(std::string_view(mode.data(), static_cast<std::size_t>(chars)));
  w.integer(sky.total_used(), 2);
  w.fixed(e.hdop, 2);
  if (e.has_fix) {
    // Deeper than -9999.9 m MSL is off the Earth; the clamp keeps 4.11's six
    // mode characters within 82 characters.
    w.fixed(std::max(e.alt_msl_m, -9999.9), 1);
    w.fixed(e.geoid_sep_m, 1);
  } else {
    w.empty();
    w.empty();
  }
  w.empty();  // no differential corrections
  w.empty();
  if (e.v4) w.character('V');
  emit(w);
}

// GGA time,lat,NS,lon,EW,quality,numSV,HDOP,alt,M,sep,M,diffAge,diffStation.
// u-blox reports quality 1 for both 2D and 3D fixes (ref §4).
void write_gga(const Epoch& e, const NmeaSky& sky, const Emit& emit) {
  SentenceWriter w(Address(e.main, "GGA"));
  put_time(w, e);
  put_position(w, e);
  w.integer(e.quality, 1);
  w.integer(std::min(sky.total_used(), kMaxGgaSats), 2);
  w.fixed(e.hdop, 2);
  if (e.has_fix) {
    w.fixed(e.alt_msl_m, 1);
    w.character('M');
    w.fixed(e.geoid_sep_m, 1);
    w.character('M');
  } else {
    for (int i = 0; i < 4; ++i) w.empty();
  }
  if (e.diff_age_s >= 0.0) {
    w.fixed(e.diff_age_s, 1);
  } else {
    w.empty();
  }
  if (e.diff_station >= 0) {
    w.integer(e.diff_station, 4);
  } else {
    w.empty();
  }
  emit(w);
}

// GSA opMode,navMode,sv1..sv12,PDOP,HDOP,VDOP[,systemId]: one per NMEA system
// (the M8 in 4.0 mode too, without systemId: ublox-8.log); the first 12 used,
// fewer if twelve three-digit numbers (extended SBAS/QZSS) would pass 82 characters.
SentenceWriter gsa_sentence(const Epoch& e, const NmeaSky& sky, NmeaSystem s, int max_listed) {
  SentenceWriter w(Address(e.main, "GSA"));
  w.character('A');
  w.integer(e.nav_mode, 1);
  int slot = 0;
  const ReportedSv* sv = sky.begin(s);
  for (int i = 0; i < sky.count(s) && slot < max_listed; ++i) {
    if (!sv[i].used) continue;
    w.integer(sv[i].number, 2);
    ++slot;
  }
  for (; slot < NmeaSky::kGsaSlots; ++slot) w.empty();
  w.fixed(e.pdop, 2);
  w.fixed(e.hdop, 2);
  w.fixed(e.vdop, 2);
  if (e.v4) w.integer(system_id(s), 1);
  return w;
}

void write_gsa(const Epoch& e, const NmeaSky& sky, const Emit& emit) {
  for (int k = 0; k < kNumNmeaSystems; ++k) {
    const auto s = static_cast<NmeaSystem>(k);
    if (!sky.present(s)) continue;
    int listed = NmeaSky::kGsaSlots;
    SentenceWriter w = gsa_sentence(e, sky, s, listed);
    while (w.finished_size() > kMaxSentenceLength && listed > 0) w = gsa_sentence(e, sky, s, --listed);
    emit(w);
  }
}

void put_sv(SentenceWriter& w, const ReportedSv& r) {
  const SatInfo& s = *r.sat;
  w.integer(r.number, 2);
  if (std::isfinite(s.el_rad) && std::isfinite(s.az_rad)) {
    w.integer(std::clamp(rounded_deg(s.el_rad), 0, 90), 2);
    int az = rounded_deg(s.az_rad) % 360;
    if (az < 0) az += 360;
    w.integer(az, 3);
  } else {  // position unknown (u-blox: "39,,,42")
    w.empty();
    w.empty();
  }
  if (s.tracked && std::isfinite(s.cn0_dbhz)) {
    w.integer(std::clamp(static_cast<int>(std::lround(s.cn0_dbhz)), 0, 99), 2);
  } else {
    w.empty();
  }
}

// GSV numMsg,msgNum,numSV,{svid,elv,az,cno}x1..4[,signalId]; cno empty when
// not tracked. One group per NMEA system, in the system's talker (ref §2).
void write_gsv(const Epoch& e, const NmeaSky& sky, const NmeaSettings& cfg, const Emit& emit) {
  constexpr GnssSystem kSignalOf[kNumNmeaSystems] = {GnssSystem::kGps, GnssSystem::kGlonass, GnssSystem::kGalileo,
                                                     GnssSystem::kBeiDou, GnssSystem::kQzss};
  for (int k = 0; k < kNumNmeaSystems; ++k) {
    const auto s = static_cast<NmeaSystem>(k);
    if (!sky.present(s)) continue;
    const Talker talker = cfg.gsv_talker == GsvTalker::kMain ? e.main : system_talker(s, cfg);
    const int n = sky.count(s);
    const int num_msg = std::max(1, (n + kSatsPerGsv - 1) / kSatsPerGsv);
    for (int m = 0; m < num_msg; ++m) {
      SentenceWriter w(Address(talker, "GSV"));
      w.integer(num_msg, 1);
      w.integer(m + 1, 1);
      w.integer(n, 2);
      const int first = m * kSatsPerGsv;
      const int last = std::min(first + kSatsPerGsv, n);
      for (int i = first; i < last; ++i) put_sv(w, sky.begin(s)[i]);
      if (e.v4) w.integer(l1_signal_id(kSignalOf[k], cfg.device), 1);
      emit(w);
    }
  }
}

// GLL lat,NS,lon,EW,time,status[,posMode].
void write_gll(const Epoch& e, const Emit& emit) {
  SentenceWriter w(Address(e.main, "GLL"));
  put_position(w, e);
  put_time(w, e);
  w.character(e.status);
  if (e.pos_mode_field) w.character(e.pos_mode);
  emit(w);
}

void put_sigmas(SentenceWriter& w, const Fix& fix) {
  w.fixed(clamp_finite(fix.sigma_n_m, 0.0, kMaxSigma_m), 1);
  w.fixed(clamp_finite(fix.sigma_e_m, 0.0, kMaxSigma_m), 1);
  w.fixed(clamp_finite(fix.sigma_u_m, 0.0, kMaxSigma_m), 1);
}

// A GST value: the M8 prints one decimal (ref §3); the NEO-M9N and ZED-F9P
// two below 1 m, one below 10 m and none above (M9N "837,2.5,2.4,126,0.98,
// 1.0,3.1", F9P rangeRms "43"; receiver-logs/gpsd).
void put_gst_value(SentenceWriter& w, double v, NmeaDevice device) {
  v = clamp_finite(v, 0.0, kMaxSigma_m);
  if (device == NmeaDevice::kM8) return w.fixed(v, 1);
  const int decimals = std::round(v * 100.0) < 100.0 ? 2 : std::round(v * 10.0) < 100.0 ? 1 : 0;
  w.fixed(v, decimals);
}

// sqrt(chi2(2 dof, 0.95)) = sqrt(-2 ln 0.05): the NEO-M9N's ellipse axes are
// 2.45 times its stdLat/stdLong (2.5,2.4 beside 0.98,1.0 in every epoch of
// ublox-neo-m9n-nmea.log), the 95 % ellipse of the same covariance.
constexpr double kEllipse95 = 2.4477468306808166;

// stdMajor, stdMinor, orient (degrees from true north, [0, 180)) of the
// east-north covariance, or three empty fields.
void put_ellipse(SentenceWriter& w, const Fix& fix, NmeaDevice device) {
  const double ee = fix.sigma_e_m * fix.sigma_e_m, nn = fix.sigma_n_m * fix.sigma_n_m, en = fix.cov_en_m2;
  if (device != NmeaDevice::kM9 || !std::isfinite(ee + nn + en)) {
    for (int i = 0; i < 3; ++i) w.empty();
    return;
  }
  const double mean = 0.5 * (ee + nn), r = std::hypot(0.5 * (nn - ee), en);
  put_gst_value(w, kEllipse95 * std::sqrt(mean + r), device);
  put_gst_value(w, kEllipse95 * std::sqrt(std::max(mean - r, 0.0)), device);
  double orient_deg = 0.5 * std::atan2(2.0 * en, nn - ee) * kRadToDeg;
  if (orient_deg < 0.0) orient_deg += 180.0;
  if (std::round(orient_deg) >= 180.0) orient_deg = 0.0;
  w.fixed(orient_deg, 0);
}

// GST time,rangeRms,stdMajor,stdMinor,orient,stdLat,stdLong,stdAlt. The
// ellipse is empty on the M8 (ref §3) and the ZED-F9P (its log), the 95 %
// ellipse on the NEO-M9N. Empty values without a fix.
void write_gst(const Epoch& e, const Fix& fix, const Emit& emit) {
  SentenceWriter w(Address(e.main, "GST"));
  put_time(w, e);
  if (e.has_fix) {
    put_gst_value(w, fix.range_rms_m, e.device);
    put_ellipse(w, fix, e.device);
    put_gst_value(w, fix.sigma_n_m, e.device);
    put_gst_value(w, fix.sigma_e_m, e.device);
    put_gst_value(w, fix.sigma_u_m, e.device);
  } else {
    for (int i = 0; i < 7; ++i) w.empty();
  }
  emit(w);
}

// ZDA time,day,month,year,ltzh,ltzn (local zone always 00,00).
void write_zda(const Epoch& e, const Emit& emit) {
  SentenceWriter w(Address(e.main, "ZDA"));
  put_time(w, e);
  if (e.has_time) {
    w.integer(e.utc.day, 2);
    w.integer(e.utc.month, 2);
    w.integer(e.utc.year, 4);
  } else {
    for (int i = 0; i < 3; ++i) w.empty();
  }
  w.integer(0, 2);
  w.integer(0, 2);
  emit(w);
}

// GBS time,errLat,errLon,errAlt,svid,prob,bias,stddev[,systemId,signalId]:
// the expected errors are GST's sigmas (the NEO-M9N and ZED-F9P logs print
// the same values in both); no satellite is flagged, so the rest is empty
// as in every real epoch.
void write_gbs(const Epoch& e, const Fix& fix, const Emit& emit) {
  SentenceWriter w(Address(e.main, "GBS"));
  put_time(w, e);
  if (e.has_fix) {
    put_sigmas(w, fix);
  } else {
    for (int i = 0; i < 3; ++i) w.empty();
  }
  for (int i = 0; i < (e.v4 ? 6 : 4); ++i) w.empty();
  emit(w);
}

}  // namespace

NmeaEncoder::NmeaEncoder(const NmeaConfig& config) : config_(config) {
  if (!std::isfinite(config_.course_min_speed_m_s) || config_.course_min_speed_m_s < 0.0) {
    throw Error("NMEA course_min_speed_m_s must be a finite value >= 0");
  }
}

}  // namespace gnssemu::protocol::nmea

namespace gnssemu::protocol::nmea {

std::size_t NmeaEncoder::encode_epoch(const receiver::Fix& fix, std::string& out) const {
  return encode_epoch(fix, config_.sentences, out);
}

std::size_t NmeaEncoder::encode_epoch(const receiver::Fix& fix, SentenceSet set, std::string& out,
                                      SentenceSink* sink, FixOverride reported) const {
  const std::size_t before = out.size();
  Epoch e = derive(fix, config_, reported);
  const NmeaSky sky(fix, config_, e.has_fix);
  e.main = main_talker(sky, config_);
  const auto emit = [&](Sentence s) { return Emit{out, sink, s}; };
  // u-blox epoch order (ref §6; GNS between VTG and GGA, GBS last: docs/nmea.md).
  if (set.has(Sentence::kRmc)) write_rmc(e, emit(Sentence::kRmc));
  if (set.has(Sentence::kVtg)) write_vtg(e, emit(Sentence::kVtg));
  if (set.has(Sentence::kGns)) write_gns(e, sky, emit(Sentence::kGns));
  if (set.has(Sentence::kGga)) write_gga(e, sky, emit(Sentence::kGga));
  if (set.has(Sentence::kGsa)) write_gsa(e, sky, emit(Sentence::kGsa));
  if (set.has(Sentence::kGsv)) write_gsv(e, sky, config_, emit(Sentence::kGsv));
  if (set.has(Sentence::kGll)) write_gll(e, emit(Sentence::kGll));
  if (set.has(Sentence::kGst)) write_gst(e, fix, emit(Sentence::kGst));
  if (set.has(Sentence::kZda)) write_zda(e, emit(Sentence::kZda));
  if (set.has(Sentence::kGbs)) write_gbs(e, fix, emit(Sentence::kGbs));
  return out.size() - before;
}

}  // namespace gnssemu::protocol::nmea
