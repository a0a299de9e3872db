// SPDX-License-Identifier: Apache-2.0
// encode_epoch must not allocate once the output string has capacity. The
// global operator new of this test executable counts calls.
#include <gtest/gtest.h>

#include <string>

#include "core/protocol/nmea/nmea_encoder.hpp"
#include "tests/support/alloc_counter.hpp"
#include "nmea_test_util.hpp"


namespace gnssemu::protocol::nmea {
namespace {

TEST(NmeaAlloc, CounterSeesAllocations) {
  const long before = gnssemu::support::allocation_count();
  std::string s(1000, 'x');  // beyond the small-string buffer
  EXPECT_GT(gnssemu::support::allocation_count(), before);
}

TEST(NmeaAlloc, EncodeEpochDoesNotAllocateWithCapacity) {
  NmeaConfig c;
  c.sentences.set(Sentence::kGst);
  c.sentences.set(Sentence::kZda);
  for (NmeaVersion v : {NmeaVersion::k23, NmeaVersion::k410, NmeaVersion::k411}) {
    c.version = v;
    const NmeaEncoder enc(c);
    receiver::Fix fix = test::sample_fix_3d();
    receiver::Fix none;  // no time, no fix
    std::string out;
    out.reserve(kMaxEpochBytes);
    enc.encode_epoch(fix, out);  // warm-up
    const long before = gnssemu::support::allocation_count();
    for (int i = 0; i < 100; ++i) {
      out.clear();
      fix.t += 0.1;
      EXPECT_GT(enc.encode_epoch(fix, out), 500u);
      out.clear();
      EXPECT_GT(enc.encode_epoch(none, out), 200u);
    }
    EXPECT_EQ(gnssemu::support::allocation_count(), before);
  }
}

// The largest sky (kMaxSatsInView satellites of every system) with every
// sentence, on both devices and every version: still no allocation.
TEST(NmeaAlloc, FullMultiGnssSkyDoesNotAllocate) {
  receiver::Fix fix = test::sample_fix_3d();
  fix.num_sats = 0;
  for (int i = 0; i < kNumSats && fix.num_sats < kMaxSatsInView; i += 2) {
    receiver::SatInfo& s = fix.sats[static_cast<std::size_t>(fix.num_sats++)];
    s.sat = SatId::from_index(i);
    s.el_rad = 0.1 * (i % 15);
    s.az_rad = 0.05 * i;
    s.cn0_dbhz = 40.0;
    s.healthy = s.tracked = s.used = true;
  }
  for (NmeaDevice d : {NmeaDevice::kM8, NmeaDevice::kM9}) {
    for (int v = 0; v < 5; ++v) {
      NmeaConfig c;
      static_cast<NmeaSettings&>(c) = factory_settings(d);
      c.version = static_cast<NmeaVersion>(v);
      c.sv_numbering = SvNumbering::kExtended;
      for (const SentenceInfo& info : kSentences) c.sentences.set(info.sentence);
      const NmeaEncoder enc(c);
      std::string out;
      out.reserve(kMaxEpochBytes);
      enc.encode_epoch(fix, out);  // warm-up
      const long before = gnssemu::support::allocation_count();
      for (int i = 0; i < 20; ++i) {
        out.clear();
        EXPECT_LE(enc.encode_epoch(fix, out), kMaxEpochBytes);
      }
      EXPECT_EQ(gnssemu::support::allocation_count(), before);
    }
  }
}

}  // namespace
}  // namespace gnssemu::protocol::nmea
