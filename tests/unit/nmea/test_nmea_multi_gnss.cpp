// SPDX-License-Identifier: Apache-2.0
// Multi-GNSS rules of the encoder: numbering per version and svNumbering,
// talkers, GSA per system, GSV per talker, CFG-NMEA limits and flags, and
// the invariants NMEA consumers rely on (used <= in view, 82 characters).
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/protocol/nmea/nmea_encoder.hpp"
#include "core/protocol/nmea/nmea_format.hpp"
#include "core/protocol/nmea/nmea_numbering.hpp"
#include "nmea_test_util.hpp"

namespace gnssemu::protocol::nmea {
namespace {

using test::parse_sentence;
using test::Sentence;

SatId sat_named(const char* name) { return *parse_sat(name); }

// Tables: shared/reference/multi-gnss.md §7 and u-blox's satellite numbering
// appendix (docs/nmea.md §Satellite numbers).
TEST(NmeaNumbering, PerVersionAndMode) {
  const auto num = [](const char* s, NmeaVersion v, SvNumbering m) { return nmea_sv_number(sat_named(s), v, m); };
  constexpr auto kStrict = SvNumbering::kStrict;
  constexpr auto kExt = SvNumbering::kExtended;
  for (NmeaVersion v : {NmeaVersion::k21, NmeaVersion::k23, NmeaVersion::k40, NmeaVersion::k410, NmeaVersion::k411}) {
    EXPECT_EQ(num("G01", v, kStrict), 1);
    EXPECT_EQ(num("G32", v, kStrict), 32);
    EXPECT_EQ(num("R01", v, kStrict), 65);
    EXPECT_EQ(num("R24", v, kStrict), 88);
    EXPECT_EQ(num("S20", v, kStrict), 33);  // PRN 120
    EXPECT_EQ(num("S51", v, kStrict), 64);  // PRN 151
    EXPECT_EQ(num("S52", v, kStrict), 0);   // PRN 152: no NMEA number
    EXPECT_EQ(num("S52", v, kExt), 152);
    EXPECT_EQ(num("S58", v, kExt), 158);
  }
  EXPECT_EQ(num("E01", NmeaVersion::k40, kStrict), 0);
  EXPECT_EQ(num("E01", NmeaVersion::k40, kExt), 301);
  EXPECT_EQ(num("E36", NmeaVersion::k23, kExt), 336);
  EXPECT_EQ(num("E36", NmeaVersion::k410, kStrict), 36);
  EXPECT_EQ(num("C01", NmeaVersion::k40, kExt), 401);
  EXPECT_EQ(num("C37", NmeaVersion::k40, kExt), 437);
  EXPECT_EQ(num("C38", NmeaVersion::k40, kExt), 0);
  EXPECT_EQ(num("C40", NmeaVersion::k410, kStrict), 40);
  EXPECT_EQ(num("J01", NmeaVersion::k40, kStrict), 0);
  EXPECT_EQ(num("J01", NmeaVersion::k410, kStrict), 0);
  EXPECT_EQ(num("J01", NmeaVersion::k410, kExt), 193);
  EXPECT_EQ(num("J01", NmeaVersion::k411, kStrict), 1);
  EXPECT_EQ(nmea_system(GnssSystem::kSbas, NmeaVersion::k411), NmeaSystem::kGps);
  EXPECT_EQ(nmea_system(GnssSystem::kQzss, NmeaVersion::k410), NmeaSystem::kGps);
  EXPECT_EQ(nmea_system(GnssSystem::kQzss, NmeaVersion::k411), NmeaSystem::kQzss);
  EXPECT_EQ(l1_signal_id(GnssSystem::kGalileo, NmeaDevice::kM9), 7);
  EXPECT_EQ(l1_signal_id(GnssSystem::kGlonass, NmeaDevice::kM9), 1);
  EXPECT_EQ(l1_signal_id(GnssSystem::kGalileo, NmeaDevice::kM8), 0);
}

TEST(NmeaSettings, FactoryDefaultsPerDevice) {
  const NmeaSettings m8 = factory_settings(NmeaDevice::kM8);
  EXPECT_EQ(m8.version, NmeaVersion::k40);
  EXPECT_TRUE(m8.systems.has(GnssSystem::kGlonass));
  EXPECT_FALSE(m8.systems.has(GnssSystem::kGalileo));
  const NmeaSettings m9 = factory_settings(NmeaDevice::kM9);
  EXPECT_EQ(m9.version, NmeaVersion::k410);
  EXPECT_TRUE(m9.systems.has(GnssSystem::kBeiDou) && m9.systems.has(GnssSystem::kGalileo));
  for (const NmeaSettings& s : {m8, m9}) {
    EXPECT_EQ(s.sv_numbering, SvNumbering::kStrict);
    EXPECT_EQ(s.max_svs, 0);
    EXPECT_EQ(s.main_talker, MainTalker::kAuto);
    EXPECT_EQ(s.gsv_talker, GsvTalker::kPerSystem);
  }
}

/// A 3D fix with the given satellites, every one in view, tracked and used.
receiver::Fix fix_with(const std::vector<const char*>& names, bool used = true) {
  receiver::Fix f = test::sample_fix_3d();
  f.num_sats = 0;
  int i = 0;
  for (const char* n : names) {
    receiver::SatInfo& s = f.sats[static_cast<std::size_t>(f.num_sats++)];
    s.sat = sat_named(n);
    s.el_rad = (10.0 + (i * 7) % 80) * kDegToRad;
    s.az_rad = ((i * 37) % 360) * kDegToRad;
    s.cn0_dbhz = 30.0 + i % 15;
    s.healthy = s.above_mask = s.tracked = true;
    s.used = used;
    ++i;
  }
  return f;
}

std::vector<Sentence> encode_parsed(const receiver::Fix& f, const NmeaConfig& c) {
  std::string out;
  NmeaEncoder(c).encode_epoch(f, out);
  std::vector<Sentence> v;
  for (const auto& l : test::split_lines(out)) {
    EXPECT_LE(l.size() + 2, kMaxSentenceLength) << l;
    EXPECT_TRUE(nmea_checksum_ok(l)) << l;
    v.push_back(parse_sentence(l));
  }
  return v;
}

std::string address_list(const std::vector<Sentence>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : " ") + x.address;
  return s;
}

NmeaConfig device_config(NmeaDevice d) {
  NmeaConfig c;
  static_cast<NmeaSettings&>(c) = factory_settings(d);
  return c;
}

TEST(NmeaMultiGnss, M8GpsGlonassAtNmea40) {
  const auto v = encode_parsed(fix_with({"G03", "G07", "R01", "R10", "S31"}), device_config(NmeaDevice::kM8));
  // ublox-8.log: GN position sentences, one GNGSA per system without systemId.
  EXPECT_EQ(address_list(v), "GNRMC GNVTG GNGGA GNGSA GNGSA GPGSV GLGSV GNGLL");
  EXPECT_EQ(v[0].fields.size(), 12u);  // no navStatus before 4.10
  EXPECT_EQ(v[3].fields.size(), 17u);  // no systemId
  EXPECT_EQ(v[3].fields[2] + v[3].fields[3] + v[3].fields[4], "030744");  // SBAS 131 -> 44 under GPS
  EXPECT_EQ(v[4].fields[2] + v[4].fields[3], "6574");
  EXPECT_EQ(v[5].fields[2], "03");
  EXPECT_EQ(v[5].fields.size(), 3u + 3u * 4u);  // no signalId
}

TEST(NmeaMultiGnss, M9FourSystemsAtNmea410) {
  const auto v = encode_parsed(fix_with({"G03", "R01", "E11", "C19", "J02", "S23"}), device_config(NmeaDevice::kM9));
  // ublox-neo-m9n-nmea.log: four GNGSA with systemId 1-4; QZSS enabled but
  // strict numbering hides it; GSV per talker with signalId 1/1/7/1.
  EXPECT_EQ(address_list(v), "GNRMC GNVTG GNGGA GNGSA GNGSA GNGSA GNGSA GPGSV GLGSV GAGSV GBGSV GNGLL");
  EXPECT_EQ(v[0].fields.back(), "V");
  for (int k = 0; k < 4; ++k) EXPECT_EQ(v[static_cast<std::size_t>(3 + k)].fields.back(), std::to_string(k + 1));
  EXPECT_EQ(v[3].fields[2] + v[3].fields[3], "0336");  // S23 = PRN 123 -> 36
  EXPECT_EQ(v[3].fields[4], "");                        // J02 not output (strict)
  EXPECT_EQ(v[6].fields[2], "19");
  EXPECT_EQ(v[7].fields.back(), "1");
  EXPECT_EQ(v[9].fields.back(), "7");
  EXPECT_EQ(v[9].fields[3], "11");
  EXPECT_EQ(v[2].fields[6], "05");  // GGA: 5 reported used (QZSS hidden)
}

TEST(NmeaMultiGnss, EnabledSystemsWithoutSatellitesStillReport) {
  // ublox-rs#54 (M8, 4.0): "$GLGSV,1,1,00*65" with GLONASS enabled and none in view.
  const auto v = encode_parsed(fix_with({"G03", "G07"}), device_config(NmeaDevice::kM8));
  EXPECT_EQ(address_list(v), "GNRMC GNVTG GNGGA GNGSA GNGSA GPGSV GLGSV GNGLL");
  EXPECT_EQ(v[6].fields, (std::vector<std::string>{"1", "1", "00"}));
  EXPECT_EQ(v[4].fields[2], "");
}

TEST(NmeaMultiGnss, SingleSystemUsesItsOwnTalker) {
  NmeaConfig c;
  c.systems = SystemSet::only(GnssSystem::kGlonass);
  EXPECT_EQ(address_list(encode_parsed(fix_with({"R01", "R02"}), c)), "GLRMC GLVTG GLGGA GLGSA GLGSV GLGLL");
  c.systems = SystemSet::only(GnssSystem::kGalileo);
  EXPECT_EQ(address_list(encode_parsed(fix_with({"E01"}), c)), "GARMC GAVTG GAGGA GAGSA GAGSV GAGLL");
  c.systems = SystemSet::only(GnssSystem::kBeiDou);
  EXPECT_EQ(address_list(encode_parsed(fix_with({"C01"}), c)), "GBRMC GBVTG GBGGA GBGSA GBGSV GBGLL");
  c.beidou_talker = {'B', 'D'};
  EXPECT_EQ(address_list(encode_parsed(fix_with({"C01"}), c)), "BDRMC BDVTG BDGGA BDGSA BDGSV BDGLL");
  // SBAS is GPS for NMEA; QZSS too before 4.11.
  c.systems = SystemSet::only(GnssSystem::kGps).with(GnssSystem::kSbas).with(GnssSystem::kQzss);
  c.version = NmeaVersion::k410;
  EXPECT_EQ(address_list(encode_parsed(fix_with({"G01", "S23"}), c)), "GPRMC GPVTG GPGGA GPGSA GPGSV GPGLL");
  // 4.11: QZSS has its own talker (GQ), numbers 1-10 and systemId 5.
  c.version = NmeaVersion::k411;
  const auto v = encode_parsed(fix_with({"G01", "J03"}), c);
  EXPECT_EQ(address_list(v), "GNRMC GNVTG GNGGA GNGSA GNGSA GPGSV GQGSV GNGLL");
  EXPECT_EQ(v[4].fields[2], "03");
  EXPECT_EQ(v[4].fields.back(), "5");
  EXPECT_EQ(v[6].fields[3], "03");
}

TEST(NmeaMultiGnss, ExtendedNumberingBeforeNmea410) {
  NmeaConfig c = device_config(NmeaDevice::kM8);
  c.systems = c.systems.with(GnssSystem::kGalileo).with(GnssSystem::kBeiDou);
  const auto strict = encode_parsed(fix_with({"G01", "E05", "C11", "J02"}), c);
  // Strict: Galileo, BeiDou and QZSS have no NMEA 4.0 number and are not output.
  std::map<std::string, std::string> total;
  for (const auto& s : strict) {
    if (s.type == "GSV") total[s.talker()] = s.fields[2];
  }
  EXPECT_EQ(total["GP"], "01");
  EXPECT_EQ(total["GA"], "00");
  EXPECT_EQ(total["GB"], "00");
  c.sv_numbering = SvNumbering::kExtended;
  const auto ext = encode_parsed(fix_with({"G01", "E05", "C11", "J02"}), c);
  std::vector<std::string> numbers;
  for (const auto& s : ext) {
    if (s.type == "GSV" && s.fields.size() > 3) numbers.push_back(s.fields[3]);
  }
  EXPECT_EQ(numbers, (std::vector<std::string>{"01", "305", "411"}));
  std::string gps_gsa = ext[3].fields[2] + "," + ext[3].fields[3];
  EXPECT_EQ(gps_gsa, "01,194");  // QZSS J02 = PRN 194 under GPS
}

TEST(NmeaMultiGnss, ConfiguredTalkersOverride) {
  NmeaConfig c = device_config(NmeaDevice::kM9);
  c.main_talker = MainTalker::kGp;
  auto v = encode_parsed(fix_with({"G01", "R01"}), c);
  EXPECT_EQ(v[0].address, "GPRMC");
  EXPECT_EQ(v[3].address, "GPGSA");
  c.gsv_talker = GsvTalker::kMain;
  v = encode_parsed(fix_with({"G01", "R01"}), c);
  for (const auto& s : v) EXPECT_EQ(s.talker(), "GP") << s.address;
}

TEST(NmeaMultiGnss, GgaCapsAtTwelveGnsDoesNot) {
  NmeaConfig c = device_config(NmeaDevice::kM9);
  c.sentences.set(nmea::Sentence::kGns);
  std::vector<const char*> names{"G01", "G02", "G03", "G04", "G05", "G06", "G07", "G08", "G09", "G10",
                                 "R01", "R02", "R03", "R04", "R05", "R06", "E01", "E02", "E03", "E04",
                                 "C01", "C02", "C03", "C04", "C05"};
  const auto v = encode_parsed(fix_with(names), c);
  ASSERT_EQ(v[2].type, "GNS");
  EXPECT_EQ(v[2].fields[6], "25");
  EXPECT_EQ(v[2].fields[5], "AAAA");  // 4.10: GPS, GLONASS, Galileo, BeiDou
  EXPECT_EQ(v[2].fields.back(), "V");
  EXPECT_EQ(v[2].fields.size(), 13u);
  EXPECT_EQ(v[3].fields[6], "12");  // GGA as every u-blox log: 12 with 25 used
  // 4.0: two mode characters (GPS, GLONASS), no navStatus.
  c.version = NmeaVersion::k40;
  const auto v40 = encode_parsed(fix_with({"G01", "E01"}), c);
  EXPECT_EQ(v40[2].fields[5], "AN");
  EXPECT_EQ(v40[2].fields.size(), 12u);
}

TEST(NmeaMultiGnss, GnsWithoutFix) {
  // The no-fix GNS of a GPS + GLONASS receiver at 4.0 in a public parser test:
  // "$GNGNS,181604.00,,,,,NN,00,99.99,,,,*59".
  NmeaConfig c = device_config(NmeaDevice::kM8);
  c.sentences = SentenceSet();
  c.sentences.set(nmea::Sentence::kGns);
  receiver::Fix f;
  f.t = time::GpsTime::from_calendar({2019, 11, 6, 18, 16, 4.0 + 18.0});
  f.time_valid = true;
  std::string out;
  NmeaEncoder(c).encode_epoch(f, out);
  EXPECT_EQ(out, "$GNGNS,181604.00,,,,,NN,00,99.99,,,,*59\r\n");
}

TEST(NmeaMultiGnss, M8NoFixEpochAsTheRealOne) {
  // The M8 no-fix epoch of ref §6 (GPS + GLONASS, time known), every checksum
  // as there; its GSV lists tracked satellites without a position, which a Fix
  // never has, and its RMC is from the next second.
  receiver::Fix f;
  f.t = time::GpsTime::from_calendar({2019, 11, 6, 18, 42, 8.0 + 18.0});
  f.time_valid = true;
  std::string out;
  NmeaEncoder(device_config(NmeaDevice::kM8)).encode_epoch(f, out);
  const auto lines = test::split_lines(out);
  ASSERT_EQ(lines.size(), 8u);
  EXPECT_EQ(lines[1], "$GNVTG,,,,,,,,,N*2E");
  EXPECT_EQ(lines[2], "$GNGGA,184208.00,,,,,0,00,99.99,,,,,,*7F");
  EXPECT_EQ(lines[3], "$GNGSA,A,1,,,,,,,,,,,,,99.99,99.99,99.99*2E");
  EXPECT_EQ(lines[4], "$GNGSA,A,1,,,,,,,,,,,,,99.99,99.99,99.99*2E");
  EXPECT_EQ(lines[7], "$GNGLL,,,,,184208.00,V,N*53");
}

TEST(NmeaMultiGnss, GsaListsTheFirstTwelveUsedPerSystem) {
  std::vector<const char*> names{"R01", "R02", "R03", "R04", "R05", "R06", "R07", "R08", "R09", "R10", "R11", "R12",
                                 "R13", "R14"};
  const auto v = encode_parsed(fix_with(names), device_config(NmeaDevice::kM9));
  const Sentence& glo = v[4];
  ASSERT_EQ(glo.fields.back(), "2");
  EXPECT_EQ(glo.fields[2], "65");
  EXPECT_EQ(glo.fields[13], "76");
}

TEST(NmeaMultiGnss, MaxSvsPerTalkerKeepsUsedOnes) {
  NmeaConfig c = device_config(NmeaDevice::kM9);
  c.max_svs = 8;
  receiver::Fix f = fix_with({"G01", "G02", "G03", "G04", "G05", "G06", "G07", "G08", "G09", "G10", "G11", "G12"});
  for (int i = 0; i < 6; ++i) f.sats[static_cast<std::size_t>(i)].used = false;  // G07-G12 used
  const auto v = encode_parsed(f, c);
  int listed = 0;
  for (const auto& s : v) {
    if (s.type == "GSV" && s.talker() == "GP") {
      EXPECT_EQ(s.fields[2], "08");
      listed += static_cast<int>((s.fields.size() - 3) / 4);
    }
  }
  EXPECT_EQ(listed, 8);
  EXPECT_EQ(v[2].fields[6], "06");
  EXPECT_EQ(v[3].fields[2], "07");  // used ones kept, in number order
}

TEST(NmeaMultiGnss, ConsideringModeCountsExcludedSatellites) {
  receiver::Fix f = fix_with({"G01", "G02", "G03"});
  f.sats[1].used = false;
  f.sats[1].excluded = true;  // removed by the RAIM residual test
  NmeaConfig c = device_config(NmeaDevice::kM9);
  c.consider = false;
  EXPECT_EQ(encode_parsed(f, c)[2].fields[6], "02");
  c.consider = true;
  EXPECT_EQ(encode_parsed(f, c)[2].fields[6], "03");
}

TEST(NmeaMultiGnss, FilteredSystemsAreNotOutput) {
  NmeaConfig c = device_config(NmeaDevice::kM9);
  c.filtered = SystemSet::only(GnssSystem::kSbas);
  const auto v = encode_parsed(fix_with({"G01", "S23"}), c);
  EXPECT_EQ(v[3].fields[2] + v[3].fields[3], "01");
}

TEST(NmeaMultiGnss, Nmea21DropsPosModeAndDeadReckoningQuality) {
  NmeaConfig c;
  c.version = NmeaVersion::k21;
  receiver::Fix f = test::sample_fix_3d();
  f.type = receiver::FixType::kDeadReckoning;
  const auto v = encode_parsed(f, c);
  EXPECT_EQ(v[0].fields.size(), 11u);  // RMC without posMode
  EXPECT_EQ(v[1].fields.size(), 8u);   // VTG
  EXPECT_EQ(v[2].fields[5], "1");      // GGA quality 1, not 6
  EXPECT_EQ(v.back().fields.size(), 6u);  // GLL
}

TEST(NmeaMultiGnss, GbsCarriesGstSigmas) {
  NmeaConfig c = device_config(NmeaDevice::kM9);
  c.sentences.set(nmea::Sentence::kGst);
  c.sentences.set(nmea::Sentence::kZda);
  c.sentences.set(nmea::Sentence::kGbs);
  receiver::Fix f = fix_with({"G01", "R01", "E01", "C01"});
  f.sigma_n_m = 1.04;
  f.sigma_e_m = 0.96;
  f.sigma_u_m = 3.1;
  const auto v = encode_parsed(f, c);
  // ublox-neo-m9n-nmea.log order: ... GLL GST ZDA GBS; "$GNGBS,223745.00,1.0,1.0,3.1,,,,,,".
  ASSERT_EQ(v.back().address, "GNGBS");
  EXPECT_EQ(v[v.size() - 2].address, "GNZDA");
  EXPECT_EQ(v[v.size() - 3].address, "GNGST");
  EXPECT_EQ(v.back().fields, (std::vector<std::string>{v.back().fields[0], "1.0", "1.0", "3.1", "", "", "", "", "", ""}));
  c.version = NmeaVersion::k40;
  EXPECT_EQ(encode_parsed(f, c).back().fields.size(), 8u);
}

// Random multi-GNSS skies: used <= in view in every sentence, GSV counts
// per talker consistent, every sentence within 82 characters.
TEST(NmeaMultiGnss, UsedNeverExceedsInViewAndSentencesFit) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    NmeaConfig c = device_config(trial % 2 ? NmeaDevice::kM9 : NmeaDevice::kM8);
    c.version = static_cast<NmeaVersion>(trial % 5);
    c.sv_numbering = trial % 3 ? SvNumbering::kExtended : SvNumbering::kStrict;
    c.max_svs = (trial % 4) * 4 + (trial % 4 ? 4 : 0);  // 0, 8, 12, 16
    c.consider = trial % 2 == 0;
    c.sentences.set(nmea::Sentence::kGns);
    c.sentences.set(nmea::Sentence::kGst);
    c.sentences.set(nmea::Sentence::kZda);
    c.sentences.set(nmea::Sentence::kGbs);
    receiver::Fix f = test::sample_fix_3d();
    f.num_sats = 0;
    for (int i = 0; i < kNumSats && f.num_sats < kMaxSatsInView; ++i) {
      if (u(rng) > 0.45) continue;
      receiver::SatInfo& s = f.sats[static_cast<std::size_t>(f.num_sats++)];
      s.sat = SatId::from_index(i);
      s.el_rad = (u(rng) * 95.0 - 5.0) * kDegToRad;
      s.az_rad = u(rng) * 2.0 * kPi;
      s.healthy = u(rng) < 0.95;
      s.tracked = u(rng) < 0.8;
      s.cn0_dbhz = s.tracked ? 20.0 + 30.0 * u(rng) : 0.0;
      s.used = s.tracked && s.healthy && s.el_rad > 0.0 && u(rng) < 0.7;
      s.excluded = s.tracked && !s.used && u(rng) < 0.2;
    }
    std::string out;
    out.reserve(kMaxEpochBytes);
    NmeaEncoder(c).encode_epoch(f, out);
    EXPECT_LE(out.size(), kMaxEpochBytes);
    std::map<std::string, int> in_view, listed;  // per GSV talker
    std::map<std::string, int> used;             // per GSA (by order)
    int gga_used = -1, gns_used = -1, gsa_total = 0, gsv_total = 0;
    std::set<std::string> gsv_numbers;
    std::vector<std::string> gsa_numbers;
    for (const auto& l : test::split_lines(out)) {
      ASSERT_LE(l.size() + 2, kMaxSentenceLength) << l;
      const Sentence s = parse_sentence(l);
      if (s.type == "GGA") gga_used = std::stoi(s.fields[6]);
      if (s.type == "GNS") gns_used = std::stoi(s.fields[6]);
      if (s.type == "GSA") {
        for (int k = 2; k < 14; ++k) {
          if (!s.fields[static_cast<std::size_t>(k)].empty()) {
            ++gsa_total;
            gsa_numbers.push_back(s.talker() + s.fields[static_cast<std::size_t>(k)]);
          }
        }
      }
      if (s.type == "GSV") {
        const int n = std::stoi(s.fields[2]);
        if (s.fields[1] == "1") {
          in_view[s.address] = n;
          gsv_total += n;
        }
        const int here = static_cast<int>((s.fields.size() - 3) / 4);
        listed[s.address] += here;
        for (int k = 0; k < here; ++k) gsv_numbers.insert(s.fields[static_cast<std::size_t>(3 + 4 * k)]);
        EXPECT_EQ(std::stoi(s.fields[0]), std::max(1, (n + 3) / 4)) << l;
        if (c.max_svs > 0) {
          EXPECT_LE(n, c.max_svs);
        }
      }
    }
    for (const auto& [talker, n] : in_view) EXPECT_EQ(listed[talker], n) << talker;
    EXPECT_LE(gga_used, 12);
    EXPECT_EQ(gga_used, std::min(gns_used, 12));
    EXPECT_LE(gns_used, gsv_total);
    EXPECT_LE(gsa_total, gns_used);
    for (const std::string& g : gsa_numbers) EXPECT_TRUE(gsv_numbers.count(g.substr(2))) << g;
  }
}

TEST(NmeaMultiGnss, LongestSentencesStayWithin82Characters) {
  // Twelve three-digit numbers in one GSA (Galileo, NMEA 4.0 extended) and
  // four three-digit SVs per GSV with 4.10 fields: the longest u-blox forms.
  NmeaConfig c = device_config(NmeaDevice::kM8);
  c.sv_numbering = SvNumbering::kExtended;
  c.systems = SystemSet::only(GnssSystem::kGps).with(GnssSystem::kGalileo);
  std::vector<const char*> gal{"E01", "E02", "E03", "E04", "E05", "E07", "E08", "E09", "E11", "E12", "E13", "E14"};
  receiver::Fix f = fix_with(gal);
  f.dop.pdop = f.dop.hdop = f.dop.vdop = 99.99;
  for (NmeaVersion v : {NmeaVersion::k40, NmeaVersion::k410}) {
    c.version = v;
    c.sentences.set(nmea::Sentence::kGns);
    encode_parsed(f, c);  // checks every length
  }
  // Twelve used with three-digit numbers under GPS at 4.10 (SBAS 152-158 and
  // QZSS 193-202, extended): GSA lists those that fit in 82 characters.
  c.version = NmeaVersion::k410;
  c.systems = SystemSet::only(GnssSystem::kGps).with(GnssSystem::kSbas).with(GnssSystem::kQzss);
  receiver::Fix many = fix_with({"J01", "J02", "J03", "J04", "J05", "J06", "J07", "S52", "S53", "S54", "S55", "S56"});
  many.dop.pdop = many.dop.hdop = many.dop.vdop = 12.5;
  const auto v = encode_parsed(many, c);
  const Sentence& gsa = v[4];
  ASSERT_EQ(gsa.type, "GSA");
  int listed = 0;
  for (int k = 2; k < 14; ++k) listed += gsa.fields[static_cast<std::size_t>(k)].empty() ? 0 : 1;
  EXPECT_EQ(listed, 11);  // 11 + 11 * 4 + 1 + 3 * 6 + 2 + 5 = 81; a twelfth would make 85
  EXPECT_EQ(gsa.fields[2], "152");
  // GNS at 4.11 (six mode characters) with the most negative heights.
  c.version = NmeaVersion::k411;
  c.sentences.set(nmea::Sentence::kGns);
  receiver::Fix deep = fix_with({"G01"});
  deep.lla.height_m = -1e6;
  deep.geoid_sep_m = -1e6;
  deep.speed_m_s = 1e6;
  encode_parsed(deep, c);
}

TEST(NmeaMultiGnss, SettingsChangeBetweenEpochs) {
  NmeaEncoder enc(device_config(NmeaDevice::kM8));
  const receiver::Fix f = fix_with({"G01", "R01"});
  std::string a, b;
  enc.encode_epoch(f, a);
  NmeaSettings s = enc.config();
  s.version = NmeaVersion::k410;
  enc.set_settings(s);
  enc.encode_epoch(f, b);
  EXPECT_EQ(parse_sentence(test::split_lines(a)[0]).fields.size(), 12u);
  EXPECT_EQ(parse_sentence(test::split_lines(b)[0]).fields.size(), 13u);
  EXPECT_EQ(enc.config().sentences, SentenceSet::ublox_default());
}

}  // namespace
}  // namespace gnssemu::protocol::nmea
