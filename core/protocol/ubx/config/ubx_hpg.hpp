// SPDX-License-Identifier: Apache-2.0
#pragma once
// The ZED-F9P's high-precision (HPG) side: the settings of its RTK engine,
// base mode and second UART as CFG-NAVHPG-*, CFG-NAVSPG-CONSTR_DGNSSTO,
// CFG-TMODE-* and CFG-UART2* leave them (for the receiver and the daemon to
// read), and the messages only HPG firmware sends: NAV-HPPOSLLH,
// NAV-HPPOSECEF, NAV-RELPOSNED (version 1) and RXM-COR. Layouts: ZED-F9P
// interface description UBX-22008968 (HPG 1.32) §3.15, §3.17; docs/ubx.md
// §ZED-F9P.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/protocol/ubx/config/ubx_device_config.hpp"
#include "core/receiver/fix.hpp"

namespace gnssemu::protocol::ubx {

namespace wire {
#pragma pack(push, 1)

/// NAV-HPPOSLLH 0x01 0x14 (36 bytes): position = coarse + Hp part.
struct NavHpposllh {
  std::uint8_t version;      ///< 0
  std::uint8_t reserved0[2];
  std::uint8_t flags;        ///< b0 invalidLlh
  std::uint32_t iTOW;        ///< ms
  std::int32_t lon, lat;     ///< 1e-7 deg
  std::int32_t height, hMSL; ///< mm
  std::int8_t lonHp, latHp;  ///< 1e-9 deg, [-99, 99]
  std::int8_t heightHp, hMSLHp;  ///< 0.1 mm, [-9, 9]
  std::uint32_t hAcc, vAcc;  ///< 0.1 mm
};
static_assert(sizeof(NavHpposllh) == 36);

/// NAV-HPPOSECEF 0x01 0x13 (28 bytes).
struct NavHpposecef {
  std::uint8_t version;      ///< 0
  std::uint8_t reserved0[3];
  std::uint32_t iTOW;        ///< ms
  std::int32_t ecefX, ecefY, ecefZ;  ///< cm
  std::int8_t ecefXHp, ecefYHp, ecefZHp;  ///< 0.1 mm, [-99, 99]
  std::uint8_t flags;        ///< b0 invalidEcef
  std::uint32_t pAcc;        ///< 0.1 mm
};
static_assert(sizeof(NavHpposecef) == 28);

/// NAV-RELPOSNED 0x01 0x3C version 1 (64 bytes; protocol 27.11 and later).
struct NavRelposnedV1 {
  std::uint8_t version;      ///< 1
  std::uint8_t reserved0;
  std::uint16_t refStationId;///< 0..4095
  std::uint32_t iTOW;        ///< ms
  std::int32_t relPosN, relPosE, relPosD;  ///< cm
  std::int32_t relPosLength; ///< cm
  std::int32_t relPosHeading;///< 1e-5 deg
  std::uint8_t reserved1[4];
  std::int8_t relPosHPN, relPosHPE, relPosHPD, relPosHPLength;  ///< 0.1 mm, [-99, 99]
  std::uint32_t accN, accE, accD, accLength;  ///< 0.1 mm
  std::uint32_t accHeading;  ///< 1e-5 deg
  std::uint8_t reserved2[4];
  /// b0 gnssFixOK, b1 diffSoln, b2 relPosValid, b3-4 carrSoln, b5 isMoving,
  /// b6 refPosMiss, b7 refObsMiss, b8 relPosHeadingValid, b9 relPosNormalized
  std::uint32_t flags;
};
static_assert(sizeof(NavRelposnedV1) == 64);

/// RXM-COR 0x02 0x34 (12 bytes): one correction message received.
struct RxmCor {
  std::uint8_t version;      ///< 1
  std::uint8_t ebno;         ///< 2^-3 dB; 0 for corrections not from L-band
  std::uint8_t reserved0[2];
  /// b0-4 protocol (1 RTCM3, 2 SPARTN), b5-6 errStatus (1 error-free, 2 erroneous),
  /// b7-8 msgUsed (1 not used, 2 used), b9-24 correctionId, b25 msgTypeValid,
  /// b26 msgSubTypeValid, b27 msgInputHandle, b28-29 msgEncrypted, b30-31 msgDecrypted
  std::uint32_t statusInfo;
  std::uint16_t msgType;     ///< RTCM 3 message number
  std::uint16_t msgSubType;  ///< 4072 sub-type
};
static_assert(sizeof(RxmCor) == 12);

#pragma pack(pop)
}  // namespace wire

/// CFG-NAVHPG-DGNSSMODE.
enum class DgnssMode : std::uint8_t {
  kRtkFloat = 2,  ///< ambiguities estimated, never fixed
  kRtkFixed = 3,  ///< fixed whenever possible (factory)
};

/// CFG-TMODE-MODE.
enum class TimeMode : std::uint8_t { kDisabled = 0, kSurveyIn = 1, kFixed = 2 };

/// The settings of the F9P's RTK engine, base mode and UART2 as the
/// configuration holds them now (the factory values on other generations).
struct HpgSettings {
  DgnssMode dgnss_mode = DgnssMode::kRtkFixed;
  /// CFG-NAVSPG-CONSTR_DGNSSTO: corrections older than this are not used, s.
  double dgnss_timeout_s = 60.0;
  struct Uart2 {
    bool enabled = true;       ///< CFG-UART2-ENABLED
    std::uint32_t baud_bps = 38400;
    std::uint16_t in_proto_mask = 0;   ///< proto:: bits (UBX, NMEA, RTCM3)
    std::uint16_t out_proto_mask = 0;
    bool operator==(const Uart2&) const = default;
  } uart2;
  struct Tmode {
    TimeMode mode = TimeMode::kDisabled;
    bool llh = false;          ///< CFG-TMODE-POS_TYPE: the fixed position is given as LLH (else ECEF)
    double ecef_m[3] = {0.0, 0.0, 0.0};  ///< fixed position, ECEF, m (ECEF_* + ECEF_*_HP)
    double lat_deg = 0.0, lon_deg = 0.0, height_m = 0.0;  ///< fixed position, LLH (LAT/LON/HEIGHT + HP)
    double fixed_pos_acc_m = 0.01;   ///< accuracy of the fixed position, m
    double svin_min_dur_s = 60.0;    ///< survey-in minimum duration, s
    double svin_acc_limit_m = 0.05;  ///< survey-in position accuracy limit, m
    bool operator==(const Tmode&) const = default;
  } tmode;

  bool operator==(const HpgSettings&) const = default;
};

/// The HPG settings of c (a configuration of any generation).
HpgSettings hpg_settings(const DeviceConfig& c) noexcept;

/// NAV-HPPOSLLH / NAV-HPPOSECEF of fix (no fix: invalid flag set, zeros).
std::size_t nav_hpposllh(const receiver::Fix& fix, std::string& out);
std::size_t nav_hpposecef(const receiver::Fix& fix, std::string& out);
/// NAV-RELPOSNED version 1 from fix.rel_pos (gnssFixOK and diffSoln from the fix).
std::size_t nav_relposned(const receiver::Fix& fix, std::string& out);
/// RXM-COR for one RTCM 3 message (msg_type 1..4095, sub_type for 4072)
/// that arrived error-free (crc_ok) and was used or not.
std::size_t rxm_cor_rtcm(std::uint16_t msg_type, std::uint16_t sub_type, bool crc_ok, bool used, std::string& out);

/// A value split as u-blox sends high-precision fields: total = round(value
/// / fine) units; coarse = trunc(total / ratio) (units of ratio * fine), hp
/// = the rest, |hp| < ratio, same sign as coarse. Saturates at the I4 range.
struct HpSplit {
  std::int32_t coarse = 0;
  std::int8_t hp = 0;
};
HpSplit hp_split(double value, double fine, int ratio = 100) noexcept;

}  // namespace gnssemu::protocol::ubx
