// SPDX-License-Identifier: Apache-2.0
#pragma once
// UBX wire structs for u-blox M8 (protocol 18-23): packed, little-endian, the
// u-blox field names and scalings of UBX-13003221 §32 (shared/reference/ubx.md
// §3-4). Sizes are asserted; encoders fill them and memcpy them into a frame.
#include <cstddef>
#include <cstdint>

namespace gnssemu::protocol::ubx::wire {

#pragma pack(push, 1)

/// NAV-PVT 0x01 0x07 (92 bytes).
struct NavPvt {
  std::uint32_t iTOW;      ///< GPS time of week of the navigation epoch, ms
  std::uint16_t year;      ///< UTC
  std::uint8_t month, day, hour, min, sec;
  std::uint8_t valid;      ///< b0 validDate, b1 validTime, b2 fullyResolved, b3 validMag
  std::uint32_t tAcc;      ///< ns
  std::int32_t nano;       ///< fraction of second, ns [-1e9, 1e9]
  std::uint8_t fixType;    ///< 0 none, 1 DR, 2 2D, 3 3D, 4 GNSS+DR, 5 time only
  std::uint8_t flags;      ///< b0 gnssFixOK, b1 diffSoln, b2-4 psmState, b5 headVehValid, b6-7 carrSoln
  std::uint8_t flags2;     ///< b5 confirmedAvai, b6 confirmedDate, b7 confirmedTime
  std::uint8_t numSV;
  std::int32_t lon;        ///< 1e-7 deg
  std::int32_t lat;        ///< 1e-7 deg
  std::int32_t height;     ///< above ellipsoid, mm
  std::int32_t hMSL;       ///< above mean sea level, mm
  std::uint32_t hAcc;      ///< mm
  std::uint32_t vAcc;      ///< mm
  std::int32_t velN, velE, velD;  ///< mm/s
  std::int32_t gSpeed;     ///< mm/s
  std::int32_t headMot;    ///< 1e-5 deg
  std::uint32_t sAcc;      ///< mm/s
  std::uint32_t headAcc;   ///< 1e-5 deg
  std::uint16_t pDOP;      ///< 0.01
  std::uint8_t flags3;     ///< b0 invalidLlh
  std::uint8_t reserved1[5];
  std::int32_t headVeh;    ///< 1e-5 deg
  std::int16_t magDec;     ///< 1e-2 deg
  std::uint16_t magAcc;    ///< 1e-2 deg
};
static_assert(sizeof(NavPvt) == 92);
static_assert(offsetof(NavPvt, lon) == 24 && offsetof(NavPvt, pDOP) == 76 && offsetof(NavPvt, headVeh) == 84);

/// NAV-POSLLH 0x01 0x02 (28 bytes).
struct NavPosllh {
  std::uint32_t iTOW;      ///< ms
  std::int32_t lon, lat;   ///< 1e-7 deg
  std::int32_t height;     ///< mm
  std::int32_t hMSL;       ///< mm
  std::uint32_t hAcc, vAcc;///< mm
};
static_assert(sizeof(NavPosllh) == 28);

/// NAV-STATUS 0x01 0x03 (16 bytes).
struct NavStatus {
  std::uint32_t iTOW;      ///< ms
  std::uint8_t gpsFix;     ///< as NavPvt::fixType
  std::uint8_t flags;      ///< b0 gpsFixOk, b1 diffSoln, b2 wknSet, b3 towSet
  std::uint8_t fixStat;    ///< b0 diffCorr, b6-7 mapMatching
  std::uint8_t flags2;     ///< b0-1 psmState, b3-4 spoofDetState
  std::uint32_t ttff;      ///< time to first fix, ms
  std::uint32_t msss;      ///< ms since start-up or reset
};
static_assert(sizeof(NavStatus) == 16);

/// NAV-DOP 0x01 0x04 (18 bytes), all DOPs scaled 0.01.
struct NavDop {
  std::uint32_t iTOW;
  std::uint16_t gDOP, pDOP, tDOP, vDOP, hDOP, nDOP, eDOP;
};
static_assert(sizeof(NavDop) == 18);

/// NAV-SOL 0x01 0x06 (52 bytes).
struct NavSol {
  std::uint32_t iTOW;      ///< ms
  std::int32_t fTOW;       ///< ns, iTOW*1e-3 + fTOW*1e-9 = precise TOW
  std::int16_t week;       ///< GPS week (continuous)
  std::uint8_t gpsFix;
  std::uint8_t flags;      ///< b0 gpsFixOK, b1 diffSoln, b2 WKNSET, b3 TOWSET
  std::int32_t ecefX, ecefY, ecefZ;  ///< cm
  std::uint32_t pAcc;      ///< 3D position accuracy, cm
  std::int32_t ecefVX, ecefVY, ecefVZ;  ///< cm/s
  std::uint32_t sAcc;      ///< cm/s
  std::uint16_t pDOP;      ///< 0.01
  std::uint8_t reserved1;
  std::uint8_t numSV;
  std::uint8_t reserved2[4];
};
static_assert(sizeof(NavSol) == 52);

/// NAV-VELNED 0x01 0x12 (36 bytes); cm/s unlike NAV-PVT.
struct NavVelned {
  std::uint32_t iTOW;
  std::int32_t velN, velE, velD;  ///< cm/s
  std::uint32_t speed;     ///< 3-D speed, cm/s
  std::uint32_t gSpeed;    ///< ground speed, cm/s
  std::int32_t heading;    ///< 1e-5 deg
  std::uint32_t sAcc;      ///< cm/s
  std::uint32_t cAcc;      ///< 1e-5 deg
};
static_assert(sizeof(NavVelned) == 36);

/// NAV-TIMEGPS 0x01 0x20 (16 bytes).
struct NavTimegps {
  std::uint32_t iTOW;
  std::int32_t fTOW;       ///< ns
  std::int16_t week;
  std::int8_t leapS;       ///< GPS - UTC, s
  std::uint8_t valid;      ///< b0 towValid, b1 weekValid, b2 leapSValid
  std::uint32_t tAcc;      ///< ns
};
static_assert(sizeof(NavTimegps) == 16);

/// NAV-TIMEUTC 0x01 0x21 (20 bytes).
struct NavTimeutc {
  std::uint32_t iTOW;
  std::uint32_t tAcc;      ///< ns
  std::int32_t nano;       ///< ns
  std::uint16_t year;
  std::uint8_t month, day, hour, min, sec;
  std::uint8_t valid;      ///< b0 validTOW, b1 validWKN, b2 validUTC, b4-7 utcStandard
};
static_assert(sizeof(NavTimeutc) == 20);

/// NAV-TIMEGLO 0x01 0x23 (20 bytes).
struct NavTimeglo {
  std::uint32_t iTOW;
  std::uint32_t TOD;       ///< GLONASS time of day, s
  std::int32_t fTOD;       ///< ns, +-500000000
  std::uint16_t Nt;        ///< day in the four-year period, 1..1461
  std::uint8_t N4;         ///< four-year period since 1996 (1 = 1996-1999)
  std::uint8_t valid;      ///< b0 todValid, b1 dateValid
  std::uint32_t tAcc;      ///< ns
};
static_assert(sizeof(NavTimeglo) == 20);

/// NAV-TIMEGAL 0x01 0x25 and NAV-TIMEBDS 0x01 0x24 (20 bytes, same layout).
struct NavTimeSow {
  std::uint32_t iTOW;
  std::uint32_t sow;       ///< galTow / SOW: whole seconds of the system's week
  std::int32_t fSow;       ///< ns, +-500000000
  std::int16_t week;       ///< galWno / week of the system
  std::int8_t leapS;       ///< system time - UTC, s
  std::uint8_t valid;      ///< b0 towValid, b1 weekValid, b2 leapSValid
  std::uint32_t tAcc;      ///< ns
};
static_assert(sizeof(NavTimeSow) == 20);

/// NAV-SIG 0x01 0x43: header (8 bytes) then numSigs NavSigSig (M9 and later).
struct NavSigHeader {
  std::uint32_t iTOW;
  std::uint8_t version;    ///< 0
  std::uint8_t numSigs;
  std::uint8_t reserved0[2];
};
static_assert(sizeof(NavSigHeader) == 8);
struct NavSigSig {
  std::uint8_t gnssId, svId, sigId, freqId;  ///< freqId: GLONASS k + 7
  std::int16_t prRes;      ///< 0.1 m
  std::uint8_t cno;        ///< dB-Hz
  std::uint8_t qualityInd;
  std::uint8_t corrSource; ///< 0 none, 1 SBAS, ...
  std::uint8_t ionoModel;  ///< 0 none, 1 Klobuchar GPS, 2 SBAS, 3 Klobuchar BeiDou, 8 dual frequency
  std::uint16_t sigFlags;  ///< b0-1 health, b2 prSmoothed, b3 prUsed, b4 crUsed, b5 doUsed, b6-8 corrections used
  std::uint8_t reserved1[4];
};
static_assert(sizeof(NavSigSig) == 16);

/// NAV-SAT 0x01 0x35: header (8 bytes) then numSvs NavSatSv.
struct NavSatHeader {
  std::uint32_t iTOW;
  std::uint8_t version;    ///< 1
  std::uint8_t numSvs;
  std::uint8_t reserved1[2];
};
static_assert(sizeof(NavSatHeader) == 8);
struct NavSatSv {
  std::uint8_t gnssId;     ///< 0 GPS
  std::uint8_t svId;
  std::uint8_t cno;        ///< dB-Hz
  std::int8_t elev;        ///< deg, -90..90
  std::int16_t azim;       ///< deg, 0..360
  std::int16_t prRes;      ///< 0.1 m
  std::uint32_t flags;     ///< b0-2 qualityInd, b3 svUsed, b4-5 health, b8-10 orbitSource, b11 ephAvail, b12 almAvail
};
static_assert(sizeof(NavSatSv) == 12);

/// NAV-SVINFO 0x01 0x30: header (8 bytes) then numCh NavSvinfoCh.
struct NavSvinfoHeader {
  std::uint32_t iTOW;
  std::uint8_t numCh;
  std::uint8_t globalFlags;  ///< b0-2 chipGen (4 = u-blox 8 / M8)
  std::uint8_t reserved1[2];
};
static_assert(sizeof(NavSvinfoHeader) == 8);
struct NavSvinfoCh {
  std::uint8_t chn;
  std::uint8_t svid;
  std::uint8_t flags;      ///< b0 svUsed, b1 diffCorr, b2 orbitAvail, b3 orbitEph, b4 unhealthy, b5 orbitAlm
  std::uint8_t quality;    ///< b0-3 qualityInd
  std::uint8_t cno;        ///< dB-Hz
  std::int8_t elev;        ///< deg
  std::int16_t azim;       ///< deg
  std::int32_t prRes;      ///< cm
};
static_assert(sizeof(NavSvinfoCh) == 12);

/// NAV-EOE 0x01 0x61 (4 bytes): end of the epoch's navigation messages.
struct NavEoe {
  std::uint32_t iTOW;
};
static_assert(sizeof(NavEoe) == 4);

/// ACK-ACK / ACK-NAK 0x05 0x01 / 0x00 (2 bytes).
struct Ack {
  std::uint8_t clsID, msgID;
};
static_assert(sizeof(Ack) == 2);

/// MON-HW2 0x0A 0x0B (28 bytes).
struct MonHw2 {
  std::int8_t ofsI;        ///< I imbalance, -128..127
  std::uint8_t magI;       ///< I magnitude, 0..255
  std::int8_t ofsQ;
  std::uint8_t magQ;
  std::uint8_t cfgSource;  ///< 114 ROM, 111 OTP, 112 config pins, 102 flash image
  std::uint8_t reserved0[3];
  std::uint32_t lowLevCfg;
  std::uint8_t reserved1[8];
  std::uint32_t postStatus;
  std::uint8_t reserved2[4];
};
static_assert(sizeof(MonHw2) == 28);

/// MON-GNSS 0x0A 0x28 (8 bytes): bits 0 GPS, 1 GLONASS, 2 BeiDou, 3 Galileo.
struct MonGnss {
  std::uint8_t version;
  std::uint8_t supported, defaultGnss, enabled;
  std::uint8_t simultaneous;  ///< major GNSS the receiver tracks at once
  std::uint8_t reserved1[3];
};
static_assert(sizeof(MonGnss) == 8);

/// MON-VER 0x0A 0x04: fixed part, then N extension strings of 30 bytes.
struct MonVerHead {
  char swVersion[30];
  char hwVersion[10];
};
static_assert(sizeof(MonVerHead) == 40);
inline constexpr std::size_t kMonVerExtensionBytes = 30;

/// MON-HW 0x0A 0x09 (60 bytes).
struct MonHw {
  std::uint32_t pinSel, pinBank, pinDir, pinVal;
  std::uint16_t noisePerMS;  ///< noise level as measured by the GPS core
  std::uint16_t agcCnt;      ///< AGC monitor, 0..8191 = 0..100 %
  std::uint8_t aStatus;      ///< 0 INIT, 1 DONTKNOW, 2 OK, 3 SHORT, 4 OPEN
  std::uint8_t aPower;       ///< 0 OFF, 1 ON, 2 DONTKNOW
  std::uint8_t flags;        ///< b0 rtcCalib, b1 safeBoot, b2-3 jammingState (0 unknown, 1 ok, 2 warning, 3 critical), b4 xtalAbsent
  std::uint8_t reserved1;
  std::uint32_t usedMask;
  std::uint8_t VP[17];
  std::uint8_t jamInd;       ///< CW jamming indicator, 0 none .. 255 strong
  std::uint8_t reserved2[2];
  std::uint32_t pinIrq, pullH, pullL;
};
static_assert(sizeof(MonHw) == 60);

/// MON-RF 0x0A 0x38 (M9, protocol 27+): header then nBlocks MonRfBlock.
struct MonRfHeader {
  std::uint8_t version;      ///< 0
  std::uint8_t nBlocks;
  std::uint8_t reserved0[2];
};
static_assert(sizeof(MonRfHeader) == 4);
struct MonRfBlock {
  std::uint8_t blockId;      ///< 0: L1 (a NEO-M9N has one block)
  std::uint8_t flags;        ///< b0-1 jammingState (0 unknown, 1 ok, 2 warning, 3 critical)
  std::uint8_t antStatus;    ///< 0 INIT, 1 DONTKNOW, 2 OK, 3 SHORT, 4 OPEN
  std::uint8_t antPower;     ///< 0 OFF, 1 ON, 2 DONTKNOW
  std::uint32_t postStatus;  ///< POST status word
  std::uint8_t reserved1[4];
  std::uint16_t noisePerMS;  ///< noise level as measured by the GNSS core
  std::uint16_t agcCnt;      ///< AGC monitor, 0..8191 = 0..100 %
  std::uint8_t jamInd;       ///< CW jamming indicator (cwSuppression), 0 none .. 255 strong
  std::int8_t ofsI;          ///< I imbalance, -128..127
  std::uint8_t magI;         ///< I magnitude, 0..255
  std::int8_t ofsQ;          ///< Q imbalance, -128..127
  std::uint8_t magQ;         ///< Q magnitude, 0..255
  std::uint8_t reserved2[3];
};
static_assert(sizeof(MonRfBlock) == 24);

/// SEC-SIG 0x27 0x09 version 1 (12 bytes): the jamming and spoofing monitors.
struct SecSigV1 {
  std::uint8_t version;      ///< 1
  std::uint8_t reserved0[3];
  std::uint8_t jamFlags;     ///< b0 jamDetEnabled, b1-2 jammingState
  std::uint8_t reserved1[3];
  std::uint8_t spfFlags;     ///< b0 spfDetEnabled, b1-3 spoofingState
  std::uint8_t reserved2[3];
};
static_assert(sizeof(SecSigV1) == 12);

/// CFG-PRT 0x06 0x00 (20 bytes per port block).
struct CfgPrt {
  std::uint8_t portID;       ///< 0 DDC, 1 UART1, 2 UART2, 3 USB, 4 SPI
  std::uint8_t reserved1;
  std::uint16_t txReady;
  std::uint32_t mode;        ///< UART: b6-7 charLen, b9-11 parity, b12-13 nStopBits (0x8C0 = 8N1); DDC: b1-7 slaveAddr
  std::uint32_t baudRate;    ///< bit/s (UART only)
  std::uint16_t inProtoMask; ///< b0 UBX, b1 NMEA, b2 RTCM2, b5 RTCM3
  std::uint16_t outProtoMask;///< b0 UBX, b1 NMEA, b5 RTCM3
  std::uint16_t flags;       ///< b1 extendedTxTimeout
  std::uint8_t reserved2[2];
};
static_assert(sizeof(CfgPrt) == 20);

/// CFG-RATE 0x06 0x08 (6 bytes).
struct CfgRate {
  std::uint16_t measRate;    ///< ms between measurements
  std::uint16_t navRate;     ///< measurement cycles per navigation solution
  std::uint16_t timeRef;     ///< 0 UTC, 1 GPS, 2 GLONASS, 3 BeiDou, 4 Galileo
};
static_assert(sizeof(CfgRate) == 6);

/// CFG-NAV5 0x06 0x24 (36 bytes).
struct CfgNav5 {
  std::uint16_t mask;        ///< which fields to apply (b0 dyn, b1 minEl, b2 posFixMode, ...)
  std::uint8_t dynModel;     ///< 0 portable, 2 stationary, 3 pedestrian, 4 automotive, 5 sea, 6-8 airborne, 9 wrist
  std::uint8_t fixMode;      ///< 1 2D only, 2 3D only, 3 auto
  std::int32_t fixedAlt;     ///< 0.01 m
  std::uint32_t fixedAltVar; ///< 0.0001 m^2
  std::int8_t minElev;       ///< deg
  std::uint8_t drLimit;      ///< s
  std::uint16_t pDop, tDop;  ///< 0.1
  std::uint16_t pAcc, tAcc;  ///< m
  std::uint8_t staticHoldThresh;  ///< cm/s
  std::uint8_t dgnssTimeout; ///< s
  std::uint8_t cnoThreshNumSVs;
  std::uint8_t cnoThresh;    ///< dB-Hz
  std::uint8_t reserved1[2];
  std::uint16_t staticHoldMaxDist;  ///< m
  std::uint8_t utcStandard;
  std::uint8_t reserved2[5];
};
static_assert(sizeof(CfgNav5) == 36);

/// CFG-CFG 0x06 0x09 (12 bytes, or 13 with deviceMask).
struct CfgCfg {
  std::uint32_t clearMask, saveMask, loadMask;  ///< b0 ioPort, b1 msgConf, b2 infMsg, b3 navConf, b4 rxmConf, b8 senConf, b9 rinvConf, b10 antConf, b11 logConf, b12 ftsConf
};
static_assert(sizeof(CfgCfg) == 12);

/// CFG-RST 0x06 0x04 (4 bytes). Not acknowledged (the receiver resets).
struct CfgRst {
  std::uint16_t navBbrMask;  ///< 0x0000 hot, 0x0001 warm, 0xFFFF cold
  std::uint8_t resetMode;    ///< 0 HW watchdog, 1 SW, 2 SW (GNSS only), 4 HW after shutdown, 8 GNSS stop, 9 GNSS start
  std::uint8_t reserved1;
};
static_assert(sizeof(CfgRst) == 4);

#pragma pack(pop)

}  // namespace gnssemu::protocol::ubx::wire
