// SPDX-License-Identifier: Apache-2.0
// Host input to the emulated u-blox: bytes through one StreamDecoder per
// output into Device::handle_ubx / handle_nmea / handle_rtcm, on one to three outputs
// (and, on output 0, as seen from the chip's other ports), an M8 or an M9, with navigation
// epochs, idle resyncs and decoder resets in between, as the daemon's
// PortChannel drives them. The input's front is the byte stream (a recorded
// log works as it is), its back the control stream (fuzz_support.hpp).
// Oracles: every reply and every epoch message is whole, valid UBX frames
// or checksummed NMEA sentences; InputResult::bytes is what was appended;
// the epoch period stays within what the emulator runs; an epoch fits the
// MessageList reservation.
#include <array>
#include <string_view>
#include <optional>
#include <cstdlib>
#include <cstdio>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/common/constants.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/protocol/ubx/wire/ubx_decoder.hpp"
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "fuzz_support.hpp"

namespace {

using namespace gnssemu;
using namespace gnssemu::protocol::ubx;

bool hex_digit(char c, int& v) {
  if (c >= '0' && c <= '9') v = c - '0';
  else if (c >= 'A' && c <= 'F') v = c - 'A' + 10;
  else return false;
  return true;
}

// Length of the valid UBX frame or NMEA sentence (with CR LF, at most
// max_nmea bytes) at the start of b; 0 if none.
std::size_t frame_length(std::string_view b, std::size_t max_nmea) {
  if (b.size() >= kFrameOverheadBytes && static_cast<std::uint8_t>(b[0]) == kSync1 &&
      static_cast<std::uint8_t>(b[1]) == kSync2) {
    const std::size_t len = static_cast<std::uint8_t>(b[4]) | static_cast<std::size_t>(static_cast<std::uint8_t>(b[5])) << 8;
    if (b.size() < len + kFrameOverheadBytes) return 0;
    const Checksum ck = fletcher8({reinterpret_cast<const std::uint8_t*>(b.data()) + 2, len + 4});
    if (ck.ck_a != static_cast<std::uint8_t>(b[len + 6]) || ck.ck_b != static_cast<std::uint8_t>(b[len + 7])) return 0;
    return len + kFrameOverheadBytes;
  }
  if (!b.empty() && b[0] == '$') {
    const std::size_t end = b.find("\r\n");
    if (end == std::string_view::npos || end < 4 || end + 2 > max_nmea || b[end - 3] != '*') return 0;
    int hi = 0, lo = 0;
    if (!hex_digit(b[end - 2], hi) || !hex_digit(b[end - 1], lo)) return 0;
    unsigned sum = 0;
    for (std::size_t i = 1; i < end - 3; ++i) {
      const auto c = static_cast<unsigned char>(b[i]);
      if (c < 0x20 || c > 0x7e || c == '$' || c == '*') return 0;
      sum ^= c;
    }
    return sum == static_cast<unsigned>(hi * 16 + lo) ? end + 2 : 0;
  }
  return 0;
}

// NMEA 0183 sentences are at most 82 characters, '$' to LF.
constexpr std::size_t kMaxSentenceBytes = 82;

void expect_frames(std::string_view bytes, const char* what) {
  while (!bytes.empty()) {
    const std::size_t n = frame_length(bytes, kMaxSentenceBytes);
    gnssemu::fuzz::expect(n > 0, what);
    bytes.remove_prefix(n);
  }
}

// A fix within the documented ranges of receiver::Fix, steered by control bytes.
receiver::Fix make_fix(gnssemu::fuzz::InputSplitter& in, int epoch) {
  receiver::Fix f;
  const int kind = in.control_in(0, 3);
  const int week = in.control_in(0, 4000);  // week, then tow: named so the order is the language's, not the compiler's
  const int tow_s = in.control_in(0, 604799);
  f.t = time::GpsTime(week, tow_s + 0.1 * (epoch % 10));
  f.leap_seconds = in.control_in(0, 40);
  f.in_leap_second = in.control_in(0, 15) == 0;
  f.time_valid = kind != 0;
  f.type = kind == 3 ? receiver::FixType::k3D : kind == 2 ? receiver::FixType::k2D : receiver::FixType::kNone;
  f.lla = Lla{(in.control_in(0, 18000) - 9000) * 0.01 * kDegToRad, (in.control_in(0, 36000) - 18000) * 0.01 * kDegToRad,
              in.control_in(0, 20000) - 1000.0};
  f.pos_m = Ecef(6378137.0, 0.0, 0.0);
  f.geoid_sep_m = in.control_in(0, 200) - 100.0;
  f.speed_m_s = in.control_in(0, 1000);
  f.course_rad = in.control_in(0, 359) * kDegToRad;
  f.vel_enu_m_s = Enu(f.speed_m_s * std::sin(f.course_rad), f.speed_m_s * std::cos(f.course_rad), in.control_in(0, 20) - 10.0);
  f.vel_m_s = Ecef(f.vel_enu_m_s);
  f.climb_m_s = f.vel_enu_m_s.z;
  f.dop = kind >= 2 ? receiver::Dop{2.0, 1.7, 0.9, 1.4, 0.8} : receiver::Dop{};
  f.h_acc_m = in.control_in(0, 10000) * 0.1;
  f.v_acc_m = f.h_acc_m * 1.5;
  f.noise_rise_db = in.control_in(0, 60);
  f.num_sats = in.control_in(0, kMaxSatsInView);
  for (int k = 0; k < f.num_sats; ++k) {
    receiver::SatInfo& s = f.sats[static_cast<std::size_t>(k)];
    s.sat = SatId::from_index(k * (kNumSats / kMaxSatsInView));  // every system, in SatId order
    s.glonass_channel = s.sat.system == GnssSystem::kGlonass ? in.control_in(0, 13) - 7 : 0;
    s.el_rad = (in.control_in(0, 180) - 90) * kDegToRad;
    s.az_rad = in.control_in(0, 359) * kDegToRad;
    s.healthy = true;
    s.above_mask = s.el_rad > 0.0;
    s.cn0_dbhz = s.above_mask ? in.control_in(0, 55) : 0.0;
    s.tracked = s.cn0_dbhz > 0.0;
    s.used = s.tracked && kind >= 2;
    f.num_visible += s.above_mask;
    f.num_tracked += s.tracked;
    f.num_used += s.used;
  }
  return f;
}

/// The raw measurements of fix's tracked satellites (every system; phase
/// locks, half cycles and lock times steered by control bytes).
void make_raw(gnssemu::fuzz::InputSplitter& in, const receiver::Fix& fix, receiver::RawEpoch& raw) {
  raw.t_rx = fix.t;
  raw.time_valid = fix.time_valid;
  raw.num_meas = 0;
  for (int k = 0; k < fix.num_sats; ++k) {
    const receiver::SatInfo& s = fix.sats[static_cast<std::size_t>(k)];
    if (!s.tracked) continue;
    receiver::RawMeasurement& m = raw.meas[static_cast<std::size_t>(raw.num_meas++)];
    m.sat = s.sat;
    m.signal = *signal_of(s.sat.system, 0);
    m.glonass_channel = s.glonass_channel;
    m.pseudorange_m = 2.0e7 + in.control_in(0, 65535) * 100.0;
    m.carrier_phase_cycles = m.pseudorange_m / kL1Wavelength_m;
    m.doppler_hz = in.control_in(0, 10000) - 5000.0;
    m.cn0_dbhz = s.cn0_dbhz;
    m.lock_time_s = in.control_in(0, 100);
    m.pseudorange_sigma_m = in.control_in(0, 1000) * 0.01;
    m.carrier_sigma_cycles = in.control_in(0, 100) * 0.001;
    m.doppler_sigma_hz = in.control_in(0, 100) * 0.01;
    const int flags = in.control_in(0, 15);
    m.pseudorange_valid = (flags & 1) != 0;
    m.carrier_valid = (flags & 2) != 0;
    m.half_cycle_resolved = (flags & 4) != 0;
    m.half_cycle_subtracted = (flags & 8) != 0;
    // The second band (an F9P's L2/E5b/B2I/G2) beside it, as the receiver lists it: right after band 0.
    const std::optional<SignalId> second = signal_of(s.sat.system, 1);
    if (in.control_in(1, 2) == 2 && second && raw.num_meas < receiver::kMaxRawMeasurements) {
      receiver::RawMeasurement& m2 = raw.meas[static_cast<std::size_t>(raw.num_meas++)];
      m2 = m;
      m2.signal = *second;
      m2.pseudorange_m += in.control_in(0, 255) * 0.01;
      m2.carrier_phase_cycles = m2.pseudorange_m * signal_carrier_hz(*second, m.glonass_channel) / kSpeedOfLight_m_s;
      m2.doppler_hz = m.doppler_hz * signal_carrier_hz(*second, m.glonass_channel) /
                      signal_carrier_hz(m.signal, m.glonass_channel);
    }
  }
}

/// With GNSSEMU_FUZZ_STATS set (a replay, not a fuzzing run): what the epochs
/// composed, printed at exit, so a seed that stopped reaching the raw
/// messages fails its replay test (fuzz_replay.ubx_device_raw_seed).
struct RawStats {
  bool on = std::getenv("GNSSEMU_FUZZ_STATS") != nullptr;
  int rawx = 0, rawx_band1 = 0;
  std::array<int, 8> sfrbx_by_gnss{};  // UBX gnssId
  void count(std::string_view b) {
    for (std::size_t i = 0; i + 8 <= b.size();) {
      if (static_cast<std::uint8_t>(b[i]) != kSync1 || static_cast<std::uint8_t>(b[i + 1]) != kSync2) {
        ++i;
        continue;
      }
      const std::size_t len = static_cast<std::uint8_t>(b[i + 4]) | static_cast<std::size_t>(static_cast<std::uint8_t>(b[i + 5])) << 8;
      if (i + 8 + len > b.size()) break;
      const std::string_view p = b.substr(i + 6, len);
      if (b[i + 2] == 0x02 && b[i + 3] == 0x15 && len >= 16) {
        ++rawx;
        // sigId (IDF9 §5.15.3 signal table): 2 and up are second-band signals (L2, E5b, B2I, L2OF).
        for (std::size_t k = 16; k + 32 <= len; k += 32) rawx_band1 += static_cast<std::uint8_t>(p[k + 22]) >= 2;
      } else if (b[i + 2] == 0x02 && b[i + 3] == 0x13 && len >= 8) {
        ++sfrbx_by_gnss[static_cast<std::uint8_t>(p[0]) & 7];
      }
      i += 8 + len;
    }
  }
  ~RawStats() {
    if (!on) return;
    static constexpr char kLetter[8] = {'G', 'S', 'E', 'C', '?', 'J', 'R', '?'};
    std::string systems;
    for (int g = 0; g < 8; ++g)
      if (sfrbx_by_gnss[static_cast<std::size_t>(g)] > 0) systems += kLetter[g];
    std::fprintf(stderr, "raw stats: RAWX %d, second-band entries %d, SFRBX systems %s (G %d R %d E %d C %d J %d)\n", rawx,
                 rawx_band1, systems.c_str(), sfrbx_by_gnss[0], sfrbx_by_gnss[6], sfrbx_by_gnss[2], sfrbx_by_gnss[3],
                 sfrbx_by_gnss[5]);
  }
};
RawStats g_raw_stats;

/// One ephemeris per GPS, QZSS, Galileo, BeiDou (GEOs included) and GLONASS
/// satellite, with orbits of each system's size (kept in use after toe): the
/// sets SFRBX re-encodes as LNAV subframes, I/NAV pages, D1/D2 subframes and
/// GLONASS strings.
const orbit::EphemerisStore& fuzz_store() {
  static const orbit::EphemerisStore store = [] {
    const time::GpsTime toe(2190, 7200.0);  // the raw_epochs seed's time
    std::vector<orbit::Ephemeris> sets;
    for (const GnssSystem sys : {GnssSystem::kGps, GnssSystem::kQzss, GnssSystem::kGalileo, GnssSystem::kBeiDou,
                                 GnssSystem::kGlonass}) {
      for (int n = numbering(sys).first; n <= numbering(sys).last; ++n) {
        orbit::Ephemeris e;
        e.sat = SatId(sys, n);
        e.toe = e.toc = toe;
        e.iode = e.iodc = n % 256;
        e.e = 0.01;
        e.m0_rad = 0.1 * n;
        e.i0_rad = 0.96;
        e.af0_s = 1e-5 * (n % 7 - 3);
        e.tgd_s = e.tgd2_s = -2e-9;
        switch (sys) {
          case GnssSystem::kGalileo:
            e.sqrt_a_sqrtm = 5440.6;
            e.gal_data_sources = orbit::kGalInavE1b | orbit::kGalClockE5b;
            break;
          case GnssSystem::kBeiDou:  // C01-C05 and C59-C63 geostationary
            e.sqrt_a_sqrtm = (n <= 5 || n >= 59) ? 6493.4 : 5282.6;
            e.i0_rad = (n <= 5 || n >= 59) ? 0.01 : 0.96;
            e.e = 0.0005;
            break;
          case GnssSystem::kGlonass: {
            const double a = 0.3 * n;
            e.pos_m = Ecef{2.55e7 * std::cos(a), 2.55e7 * std::sin(a), 1.0e6};
            e.vel_m_s = Ecef{-2.9e3 * std::sin(a), 2.9e3 * std::cos(a), 1.0e3};
            e.acc_m_s2 = Ecef{1e-6, -1e-6, 2e-6};
            e.tau_n_s = 1e-5 * (n % 5 - 2);
            e.gamma_n = 1e-12;
            e.glo_channel = n % 14 - 7;
            e.toe = e.toc = toe + 18.0;  // 05:00 Moscow time (UTC + 3 h, 18 leap seconds): tb index 20
            e.iode = 20;
            break;
          }
          default:
            e.sqrt_a_sqrtm = 5153.7;
            break;
        }
        sets.push_back(e);
      }
    }
    return orbit::EphemerisStore(sets, orbit::StoreOptions{true});
  }();
  return store;
}

class Host final : public DecoderSink {
public:
  Host(Device& device, Link link) : device_(device), link_(link) {}
  void on_ubx(const FrameView& frame) override {
    const std::size_t before = out_.size();
    const InputResult r = device_.handle_ubx(link_, frame, now_s, out_);
    check(r, before);
  }
  void on_nmea(std::string_view sentence) override {
    const std::size_t before = out_.size();
    const InputResult r = device_.handle_nmea(link_, sentence, out_);
    check(r, before);
  }
  void on_rtcm(std::span<const std::uint8_t> payload, bool crc_ok) override {
    const std::size_t before = out_.size();
    const InputResult r = device_.handle_rtcm(link_, payload, crc_ok, out_);
    check(r, before);
  }
  double now_s = 0.0;

private:
  void check(const InputResult& r, std::size_t before) {
    gnssemu::fuzz::expect(out_.size() - before == r.bytes, "InputResult::bytes is what was appended");
    expect_frames(std::string_view(out_).substr(before), "reply is whole valid frames");
    const double p = device_.epoch_period_s();
    gnssemu::fuzz::expect(p >= kMinEpochPeriodS - 1e-12 && p <= kMaxEpochPeriodS + 1e-12, "epoch period in range");
    out_.clear();
  }
  Device& device_;
  Link link_;
  std::string out_;
};

constexpr std::array<std::uint32_t, 5> kBauds = {0, 9600, 38400, 115200, 230400};
constexpr std::array<MsgId, 14> kRated = {msg::kNavPvt,        msg::kNavStatus,     msg::kNavDop,     msg::kNavSat,
                                          msg::kNavSvinfo,     msg::kNavTimeutc,    msg::kNmeaGga,    msg::kNmeaGsv,
                                          msg::kRxmRawx,       msg::kRxmSfrbx,      msg::kNavHpposllh, msg::kNavHpposecef,
                                          msg::kNavRelposned,  msg::kNavSig};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gnssemu::fuzz::InputSplitter in(data, size);
  DeviceSetup setup;
  // b0: ACK unknown CFG ids; b1: an M9, which answers CFG-VALSET/VALGET/VALDEL;
  // b2: raw-data firmware (RXM-RAWX, RXM-SFRBX); b3: a ZED-F9P (its keys,
  // CFG-DGNSS/TMODE3, the high-precision messages), whatever b1 says.
  const int identity = in.control_in(0, 15);
  setup.raw_firmware = (identity & 4) != 0;
  setup.ack_unknown_cfg = (identity & 1) != 0;
  setup.mon_ver = mon_ver_of((identity & 8) != 0   ? Generation::kF9P
                             : (identity & 2) != 0 ? Generation::kM9
                                                   : Generation::kM8);
  setup.nav_period_s = 1.0 / in.control_in(1, 10);
  const int outputs = in.control_in(1, 3);
  for (int k = 0; k < outputs; ++k) {
    OutputSetup o;
    o.baud_bps = kBauds[static_cast<std::size_t>(in.control_in(0, kBauds.size() - 1))];
    o.protocols_in = static_cast<std::uint16_t>(in.control_in(0, 3));
    if (o.protocols_in == 3) o.protocols_in |= proto::kRtcm3;  // a port taking all three
    o.protocols_out = static_cast<std::uint16_t>(in.control_in(0, 3));
    for (const MsgId id : kRated) {
      const int rate = in.control_in(0, 3);
      if (rate > 0) o.rates.push_back({id, static_cast<std::uint8_t>(rate)});
    }
    o.nmea_version = static_cast<protocol::nmea::NmeaVersion>(in.control_in(0, 2));
    setup.outputs.push_back(o);
  }
  Device device(setup);
  device.power_on(0.0);

  // Hosts on every output's UART1, and on output 0 as seen from DDC, USB, SPI.
  std::vector<std::unique_ptr<Host>> hosts;
  std::vector<std::unique_ptr<StreamDecoder>> decoders;
  for (int k = 0; k < outputs; ++k) hosts.push_back(std::make_unique<Host>(device, Link{static_cast<std::size_t>(k), kPortUart1}));
  for (const std::uint8_t port : {kPortDdc, kPortUsb, kPortSpi}) hosts.push_back(std::make_unique<Host>(device, Link{0, port}));
  for (std::size_t k = 0; k < hosts.size(); ++k) decoders.push_back(std::make_unique<StreamDecoder>());

  double now_s = 0.0;
  int epoch = 0;
  MessageList list;
  receiver::RawEpoch raw;
  while (in.remaining() > 0) {
    const int action = in.control_in(0, 15);
    const std::size_t who = static_cast<std::size_t>(in.control_in(0, 15)) % hosts.size();
    Host& host = *hosts[who];
    StreamDecoder& dec = *decoders[who];
    now_s += in.control_in(0, 255) * 0.01;
    host.now_s = now_s;
    if (action < 11) {
      dec.feed(in.take(static_cast<std::size_t>(in.control_in(1, 512))), host);
    } else if (action < 13) {
      dec.on_idle(host);
    } else if (action == 13) {
      dec.reset();
    } else {
      const receiver::Fix fix = make_fix(in, epoch++);
      make_raw(in, fix, raw);
      device.on_epoch(fix, now_s, RawSource{&raw, &fuzz_store(), {}});
      for (int k = 0; k < outputs; ++k) {
        list.clear();
        const Layout layout = action == 14 ? Layout::kLine : Layout::kPerProtocol;
        device.compose(Link{static_cast<std::size_t>(k), kPortUart1}, list, layout);
        gnssemu::fuzz::expect(list.messages().size() <= MessageList::kMaxMessages, "epoch within kMaxMessages");
        gnssemu::fuzz::expect(list.bytes().size() <= MessageList::kMaxBytes, "epoch within kMaxBytes");
        for (const auto& m : list.messages()) {
          gnssemu::fuzz::expect(!m.label.empty() && m.end > m.begin, "epoch message labelled and not empty");
          expect_frames(list.bytes(m), "epoch message is whole valid frames");
          if (g_raw_stats.on) g_raw_stats.count(list.bytes(m));
        }
      }
    }
  }
  return 0;
}
