// SPDX-License-Identifier: Apache-2.0
#pragma once
// RXM raw-data output: RXM-RAWX (the receiver's measurements, from a
// receiver::RawEpoch) and RXM-SFRBX (one subframe, string or page of a
// satellite's navigation message as the receiver decoded it). Layouts:
// u-blox ZED-F9P Interface Description UBX-18010854 §5.15.3 and §5.15.6
// (shared/reference/rtk-raw.md §1.1, §1.3); docs/raw-output.md.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "core/common/sat_id.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/protocol/navmsg/gps_lnav.hpp"
#include "core/orbit/nav_data.hpp"
#include "core/protocol/ubx/wire/ubx_frame.hpp"
#include "core/protocol/ubx/config/ubx_generation.hpp"
#include "core/protocol/ubx/wire/ubx_message_list.hpp"
#include "core/receiver/raw_measurements.hpp"

namespace gnssemu::protocol::ubx {

/// Payload bytes of RXM-RAWX: 16-byte header, 32 per measurement.
inline constexpr std::size_t kRawxHeaderBytes = 16;
inline constexpr std::size_t kRawxMeasBytes = 32;
/// locktime saturates here, ms (IDF9 §5.15.3).
inline constexpr std::uint16_t kRawxMaxLocktimeMs = 64500;
/// Most measurements one RAWX carries (numMeas is U1).
inline constexpr int kRawxMaxMeas = 255;

/// RAWX standard-deviation indices (IDF9 §5.15.3): prStdev 0.01 m * 2^n,
/// cpStdev 0.004 cycles * n (15 = invalid), doStdev 0.002 Hz * 2^n; the
/// nearest index to sigma, clamped to [0, 15] (cpStdev valid: [1, 14]).
std::uint8_t rawx_pr_stdev(double sigma_m) noexcept;
std::uint8_t rawx_cp_stdev(double sigma_cycles, bool valid) noexcept;
std::uint8_t rawx_do_stdev(double sigma_hz) noexcept;

/// RXM-RAWX version 1 from raw: one entry per measurement (at most
/// kRawxMaxMeas), sigId as generation g reports it (an M8's byte is
/// reserved and sent 0; an M9 the signal table's sigId, BeiDou GEOs + 1
/// for D2). Nothing when raw has no valid time. Returns bytes appended.
std::size_t rxm_rawx(const receiver::RawEpoch& raw, Generation g, std::string& out);

/// One RXM-SFRBX version 2: words (<= 10) of sat's navigation message on
/// the L1-band signal; GLONASS freqId = channel + 7. Returns bytes appended.
std::size_t rxm_sfrbx(SatId sat, int glonass_channel, std::span<const std::uint32_t> words, Generation g,
                      std::string& out);

/// What the raw messages of an epoch are made of; the pointers stay valid
/// until the epoch's messages are composed.
struct RawSource {
  const receiver::RawEpoch* epoch = nullptr;           ///< this epoch's measurements
  const orbit::EphemerisStore* ephemerides = nullptr;  ///< the sets the satellites broadcast
  navmsg::LnavIonoUtc iono;                            ///< GPS subframe 4 page 18; GLONASS and Galileo leap seconds, GST - UTC
  const orbit::NequickParams* galileo_nequick = nullptr;  ///< Galileo I/NAV word type 5; null: zeros
  const orbit::KlobucharParams* beidou_klobuchar = nullptr;  ///< BeiDou D1 subframe 1; null: zeros
};

/// One RXM-SFRBX, closed as "RXM-SFRBX", for every subframe (string, page
/// pair) a satellite tracked on its L1-band signal finished sending in the
/// period_s before src.epoch's time: its transmit time (receive time minus
/// the pseudorange) crossed the unit's end, and the carrier was locked for
/// the whole unit. Returns the messages added.
int rxm_sfrbx_due(const RawSource& src, double period_s, Generation g, MessageList& out);

}  // namespace gnssemu::protocol::ubx
