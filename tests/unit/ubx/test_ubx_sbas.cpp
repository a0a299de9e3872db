// SPDX-License-Identifier: Apache-2.0
// An SBAS-corrected fix on the UBX wire: diffSoln in NAV-PVT, NAV-STATUS and
// NAV-SOL; per satellite NAV-SAT diffCorr/sbasCorrUsed, NAV-SVINFO diffCorr,
// NAV-SIG corrSource SBAS, ionoModel SBAS and prCorrUsed, only on the
// satellites the receiver corrected; nothing of it without corrections.
#include <gtest/gtest.h>

#include <cstring>

#include "core/protocol/ubx/wire/ubx_encoder.hpp"
#include "core/protocol/ubx/config/ubx_gnss.hpp"
#include "core/protocol/ubx/wire/ubx_messages.hpp"
#include "ubx_test_util.hpp"

namespace gnssemu::protocol::ubx {
namespace {

using Payload = std::vector<std::uint8_t>;

Payload encode(std::size_t (UbxEncoder::*fn)(const receiver::Fix&, std::string&) const, const receiver::Fix& f) {
  const UbxEncoder enc;
  std::string out;
  (enc.*fn)(f, out);
  const auto frames = test::split_frames(out);
  EXPECT_EQ(frames.size(), 1u);
  return frames.empty() ? Payload{} : frames[0].payload;
}

Payload nav_status(const receiver::Fix& f) {
  const UbxEncoder enc;
  std::string out;
  enc.nav_status(f, EpochInfo{}, out);
  const auto frames = test::split_frames(out);
  return frames.empty() ? Payload{} : frames[0].payload;
}

/// The first used GPS satellite of f (index in f.sats) and another used one.
std::pair<int, int> two_used(const receiver::Fix& f) {
  int a = -1, b = -1;
  for (int i = 0; i < f.num_sats; ++i) {
    if (!f.sats[i].used || f.sats[i].sat.system != GnssSystem::kGps) continue;
    (a < 0 ? a : b) = i;
    if (b >= 0) break;
  }
  return {a, b};
}

/// An entry's bytes in a per-satellite message: header, entry size, offset
/// of svId within it; nullptr when sat is not listed.
const std::uint8_t* entry(const Payload& p, std::size_t size, SatId sat) {
  for (std::size_t off = 8; off + size <= p.size(); off += size)
    if (p[off] == system_info(sat.system).ubx_gnss_id && p[off + 1] == ubx_sv_id(sat)) return &p[off];
  return nullptr;
}

receiver::Fix sbas_fix(int corrected) {
  receiver::Fix f = test::sample_fix();
  f.diff_soln = f.sbas_soln = true;
  f.ref_station_id = 0;
  f.sats[corrected].sbas_corr = f.sats[corrected].sbas_iono = true;
  return f;
}

TEST(UbxSbas, DiffSolnFlagsFollowTheFix) {
  const receiver::Fix plain = test::sample_fix();
  const auto [a, b] = two_used(plain);
  ASSERT_GE(b, 0);
  const receiver::Fix f = sbas_fix(a);
  EXPECT_EQ(encode(&UbxEncoder::nav_pvt, plain)[21] & 0x02, 0);
  EXPECT_EQ(encode(&UbxEncoder::nav_pvt, f)[21] & 0x02, 0x02);
  EXPECT_EQ(nav_status(plain)[5] & 0x02, 0);
  EXPECT_EQ(nav_status(f)[5] & 0x02, 0x02);
  EXPECT_EQ(encode(&UbxEncoder::nav_sol, plain)[11] & 0x02, 0);
  EXPECT_EQ(encode(&UbxEncoder::nav_sol, f)[11] & 0x02, 0x02);
}

TEST(UbxSbas, PerSatelliteFlagsOnlyWhereCorrected) {
  const auto [a, b] = two_used(test::sample_fix());
  ASSERT_GE(b, 0);
  const receiver::Fix f = sbas_fix(a);
  const SatId ca = f.sats[a].sat, cb = f.sats[b].sat;

  const Payload sat = encode(&UbxEncoder::nav_sat, f);
  const auto flags = [&](SatId s) {
    std::uint32_t v = 0;
    const std::uint8_t* e = entry(sat, sizeof(wire::NavSatSv), s);
    EXPECT_NE(e, nullptr);
    if (e != nullptr) std::memcpy(&v, e + 8, 4);
    return v;
  };
  EXPECT_EQ(flags(ca) & (1u << 6 | 1u << 16), 1u << 6 | 1u << 16);  // diffCorr, sbasCorrUsed
  EXPECT_EQ(flags(cb) & (1u << 6 | 1u << 16), 0u);

  const Payload svinfo = encode(&UbxEncoder::nav_svinfo, f);
  const auto sv_flags = [&](SatId s) {
    for (std::size_t off = 8; off + 12 <= svinfo.size(); off += 12)
      if (svinfo[off + 1] == svinfo_svid(s)) return svinfo[off + 2];
    ADD_FAILURE() << "not in NAV-SVINFO";
    return std::uint8_t{0};
  };
  EXPECT_EQ(sv_flags(ca) & 0x02, 0x02);
  EXPECT_EQ(sv_flags(cb) & 0x02, 0);

  const Payload sig = encode(&UbxEncoder::nav_sig, f);
  const std::uint8_t* sa = entry(sig, sizeof(wire::NavSigSig), ca);
  const std::uint8_t* sb = entry(sig, sizeof(wire::NavSigSig), cb);
  ASSERT_NE(sa, nullptr);
  ASSERT_NE(sb, nullptr);
  EXPECT_EQ(sa[8], 1);  // corrSource SBAS
  EXPECT_EQ(sa[9], 2);  // ionoModel SBAS
  EXPECT_EQ(sa[10] & 0x40, 0x40);  // prCorrUsed
  EXPECT_EQ(sb[8], 0);
  EXPECT_EQ(sb[9], 1);  // Klobuchar
  EXPECT_EQ(sb[10] & 0x40, 0);
}

TEST(UbxSbas, RtcmDifferentialKeepsItsCorrSource) {
  receiver::Fix f = test::sample_fix();
  f.diff_soln = true;  // RTCM, not SBAS
  const auto [a, b] = two_used(f);
  ASSERT_GE(a, 0);
  const Payload sig = encode(&UbxEncoder::nav_sig, f);
  const std::uint8_t* sa = entry(sig, sizeof(wire::NavSigSig), f.sats[a].sat);
  ASSERT_NE(sa, nullptr);
  EXPECT_EQ(sa[8], 4);
  EXPECT_EQ(sa[10] & 0x40, 0x40);
}

}  // namespace
}  // namespace gnssemu::protocol::ubx
