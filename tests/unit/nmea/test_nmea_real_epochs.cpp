// SPDX-License-Identifier: Apache-2.0
// One epoch of each real u-blox log (tests/data/receiver-logs: MAX-M8Q at
// NMEA 4.0, NEO-M9N and ZED-F9P at 4.10) is parsed into a Fix with the same
// satellites, DOP, position, speed and sigmas, encoded with the matching
// device settings and compared sentence by sentence: the sequence of
// addresses, every field count, and every field byte for byte except the
// ones listed per log with the reason we cannot match them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/protocol/nmea/nmea_encoder.hpp"
#include "core/protocol/nmea/nmea_numbering.hpp"
#include "nmea_test_util.hpp"

namespace gnssemu::protocol::nmea {
namespace {

using test::parse_sentence;
using test::Sentence;

std::vector<Sentence> first_epoch(const std::string& name) {
  const std::string path = std::string(GNSSEMU_TEST_DATA) + "/receiver-logs/" + name;
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.good()) << path;
  std::stringstream ss;
  ss << in.rdbuf();
  std::vector<Sentence> epoch;
  for (const auto& l : test::split_lines(ss.str())) {
    if (l.empty() || l[0] != '$') continue;
    Sentence s = parse_sentence(l);
    if (s.type == "RMC" && !epoch.empty()) break;
    if (s.type == "RMC" || !epoch.empty()) epoch.push_back(s);
  }
  return epoch;
}

double coordinate_deg(const std::string& v, const std::string& hemi, int deg_digits) {
  const double deg = std::stod(v.substr(0, static_cast<std::size_t>(deg_digits))) +
                     std::stod(v.substr(static_cast<std::size_t>(deg_digits))) / 60.0;
  return (hemi == "S" || hemi == "W") ? -deg : deg;
}

/// The satellite a real GSV entry names (talker, number) at NMEA version v.
SatId sat_of(const std::string& talker, int n, NmeaVersion v) {
  const bool v4 = has_system_ids(v);
  if (talker == "GL") return SatId(GnssSystem::kGlonass, n - 64);
  if (talker == "GA") return SatId(GnssSystem::kGalileo, v4 ? n : n - 300);
  if (talker == "GB") return SatId(GnssSystem::kBeiDou, v4 ? n : n - 400);
  if (talker == "GQ") return SatId(GnssSystem::kQzss, n);
  if (n <= 32) return SatId::gps(n);
  if (n <= 64) return *SatId::from_prn(GnssSystem::kSbas, n + 87);
  if (n >= 193) return *SatId::from_prn(GnssSystem::kQzss, n);
  return *SatId::from_prn(GnssSystem::kSbas, n);
}

/// GSV groups of the signal the emulated L1 receiver tracks (the F9P adds a
/// second group per talker for its L2/E5b/B2I signal).
bool l1_group(const Sentence& s) {
  if (s.fields.size() % 4 != 0) return true;  // before 4.10: no signalId
  return s.fields.back() == (s.talker() == "GA" ? "7" : "1");
}

struct Parsed {
  receiver::Fix fix;
  SystemSet systems;
  std::vector<Sentence> compared;  // the real sentences we mean to reproduce
};

Parsed fix_from_epoch(const std::vector<Sentence>& epoch, NmeaVersion v) {
  Parsed p;
  receiver::Fix& f = p.fix;
  std::map<std::pair<std::string, int>, receiver::SatInfo> sats;
  std::vector<std::vector<int>> gsa_used;
  for (const Sentence& s : epoch) {
    const auto& x = s.fields;
    if (s.type == "GSV" && !l1_group(s)) continue;
    p.compared.push_back(s);
    if (s.type == "RMC") {
      const int day = std::stoi(x[8].substr(0, 2)), month = std::stoi(x[8].substr(2, 2));
      const int year = 2000 + std::stoi(x[8].substr(4, 2));
      const int hh = std::stoi(x[0].substr(0, 2)), mm = std::stoi(x[0].substr(2, 2));
      const double ss = std::stod(x[0].substr(4));
      f.leap_seconds = 18;
      f.t = time::GpsTime::from_calendar({year, month, day, hh, mm, ss + f.leap_seconds});
      f.time_valid = true;
      f.speed_m_s = std::stod(x[6]) * 1852.0 / 3600.0;
    } else if (s.type == "GGA") {
      f.lla.lat_rad = coordinate_deg(x[1], x[2], 2) * kDegToRad;
      f.lla.lon_rad = coordinate_deg(x[3], x[4], 3) * kDegToRad;
      f.geoid_sep_m = std::stod(x[10]);
      f.lla.height_m = std::stod(x[8]) + f.geoid_sep_m;
      f.type = receiver::FixType::k3D;
      // Quality 2 without RTK: an SBAS fix, as the receiver reports one
      // (receiver.cpp sbas_fix_flags: station 0, no age).
      if (x[5] == "2") {
        f.diff_soln = f.sbas_soln = true;
        f.ref_station_id = x[13].empty() ? -1 : std::stoi(x[13]);
        f.corr_age_s = x[12].empty() ? -1.0 : std::stod(x[12]);
      }
    } else if (s.type == "GSA") {
      f.dop.pdop = std::stod(x[14]);
      f.dop.hdop = std::stod(x[15]);
      f.dop.vdop = std::stod(x[16]);
      gsa_used.emplace_back();
      for (int k = 2; k < 14; ++k) {
        if (!x[static_cast<std::size_t>(k)].empty()) gsa_used.back().push_back(std::stoi(x[static_cast<std::size_t>(k)]));
      }
    } else if (s.type == "GSV") {
      for (std::size_t i = 0; i < (x.size() - 3) / 4; ++i) {
        const std::size_t k = 3 + 4 * i;
        const int n = std::stoi(x[k]);
        receiver::SatInfo si;
        si.sat = sat_of(s.talker(), n, v);
        si.el_rad = std::stod(x[k + 1]) * kDegToRad;
        si.az_rad = std::stod(x[k + 2]) * kDegToRad;
        si.tracked = !x[k + 3].empty();
        si.cn0_dbhz = si.tracked ? std::stod(x[k + 3]) : 0.0;
        si.healthy = si.above_mask = true;
        sats[{s.talker(), n}] = si;
        p.systems = p.systems.with(si.sat.system);
      }
    } else if (s.type == "GST") {
      f.range_rms_m = std::stod(x[1]);
      f.sigma_n_m = std::stod(x[5]);
      f.sigma_e_m = std::stod(x[6]);
      f.sigma_u_m = std::stod(x[7]);
      if (!x[2].empty()) {  // the 95 % ellipse (M9N) gives the east-north covariance
        const double a = std::stod(x[2]) / 2.4477468306808166, b = std::stod(x[3]) / 2.4477468306808166;
        const double th = std::stod(x[4]) * kDegToRad;
        f.cov_en_m2 = (a * a - b * b) * std::sin(th) * std::cos(th);
      }
    }
  }
  // GSA i lists system i+1 (4.10: its systemId; 4.0: the same order).
  const char* const kTalkerOfGsa[] = {"GP", "GL", "GA", "GB"};
  for (std::size_t i = 0; i < gsa_used.size() && i < 4; ++i) {
    for (int n : gsa_used[i]) {
      auto it = sats.find({kTalkerOfGsa[i], n});
      EXPECT_NE(it, sats.end()) << "used SV " << n << " not in GSV";
      if (it != sats.end()) it->second.used = true;
    }
  }
  std::vector<receiver::SatInfo> list;
  for (const auto& [key, si] : sats) list.push_back(si);
  std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.sat < b.sat; });
  for (const auto& si : list) {
    f.sats[static_cast<std::size_t>(f.num_sats++)] = si;
    f.num_used += si.used ? 1 : 0;
  }
  return p;
}

/// A field we cannot reproduce: "GST:1" (one field) with the reason.
struct Known {
  std::string field;
  std::string why;
};

struct Case {
  const char* log;
  NmeaDevice device;
  NmeaVersion version;
  std::vector<Known> known;
};

std::string field_key(const Sentence& s, std::size_t k) { return s.type + ":" + std::to_string(k); }

void compare(const Case& c) {
  SCOPED_TRACE(c.log);
  const std::vector<Sentence> epoch = first_epoch(c.log);
  ASSERT_GT(epoch.size(), 8u);
  Parsed p = fix_from_epoch(epoch, c.version);
  NmeaConfig cfg;
  static_cast<NmeaSettings&>(cfg) = factory_settings(c.device);
  cfg.version = c.version;
  cfg.systems = p.systems;
  cfg.sentences = SentenceSet();
  for (const Sentence& s : p.compared) cfg.sentences.set(*sentence_by_name(s.type));
  std::string out;
  NmeaEncoder(cfg).encode_epoch(p.fix, out);
  std::vector<Sentence> ours;
  for (const auto& l : test::split_lines(out)) ours.push_back(parse_sentence(l));

  // Structure: the same addresses in the same order.
  std::string want, got;
  for (const auto& s : p.compared) want += s.address + " ";
  for (const auto& s : ours) got += s.address + " ";
  ASSERT_EQ(got, want);

  std::map<std::string, std::string> known;
  for (const Known& k : c.known) known[k.field] = k.why;
  std::set<std::string> differing;
  int equal_fields = 0;
  for (std::size_t i = 0; i < ours.size(); ++i) {
    const Sentence& a = ours[i];
    const Sentence& r = p.compared[i];
    ASSERT_EQ(a.fields.size(), r.fields.size()) << r.address << " #" << i;
    if (a.type == "GSA") {  // u-blox lists used SVs in channel order, we in number order
      std::multiset<std::string> sa(a.fields.begin() + 2, a.fields.begin() + 14);
      std::multiset<std::string> sr(r.fields.begin() + 2, r.fields.begin() + 14);
      EXPECT_EQ(sa, sr) << r.address;
    }
    for (std::size_t k = 0; k < r.fields.size(); ++k) {
      if (a.type == "GSA" && k >= 2 && k < 14) continue;
      if (a.fields[k] == r.fields[k]) {
        ++equal_fields;
        continue;
      }
      const std::string key = field_key(r, k);
      differing.insert(key);
      EXPECT_TRUE(known.count(key)) << key << ": ours " << a.fields[k] << ", real " << r.fields[k];
    }
  }
  // Every listed exception is still needed (else the list is stale).
  for (const Known& k : c.known) EXPECT_TRUE(differing.count(k.field)) << "no longer differs: " << k.field;
  std::printf("%s: %zu sentences, %d fields equal, %zu differ knowingly\n", c.log, ours.size(), equal_fields,
              differing.size());
}

const char* const kRangeRms = "GST rangeRms is a firmware artefact (228650, 235111 m)";
const char* const kKmh = "km/h computed from the unrounded speed on the receiver, from the printed knots here";

TEST(NmeaRealEpochs, Ublox8MaxM8qNmea40) {
  compare({"ublox-8-excerpt.log", NmeaDevice::kM8, NmeaVersion::k40, {}});
}

TEST(NmeaRealEpochs, NeoM9nNmea410) {
  compare({"ublox-neo-m9n-nmea-excerpt.log",
           NmeaDevice::kM9,
           NmeaVersion::k410,
           {{"VTG:6", kKmh},
            {"GST:1", kRangeRms},
            {"GST:4", "orientation: the two-digit stdLat/stdLong (0.98, 1.0) fix it only to several degrees"}}});
}

TEST(NmeaRealEpochs, ZedF9pNmea410) {
  compare({"ublox-zed-f9p-nmea-excerpt.log", NmeaDevice::kF9, NmeaVersion::k410,
           {{"GST:1", kRangeRms}, {"VTG:6", kKmh}}});
}

}  // namespace
}  // namespace gnssemu::protocol::nmea
