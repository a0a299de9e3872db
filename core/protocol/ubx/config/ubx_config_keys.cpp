// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/ubx/config/ubx_config_keys.hpp"

#include <algorithm>
#include <limits>

#include "core/protocol/ubx/config/ubx_ports.hpp"

namespace gnssemu::protocol::ubx {

namespace {

constexpr std::int64_t kU1 = 0xFF, kU2 = 0xFFFF, kU4 = 0xFFFFFFFF;
constexpr std::int64_t kI4Min = std::numeric_limits<std::int32_t>::min(), kI4Max = std::numeric_limits<std::int32_t>::max();

constexpr ConfigKey plain(std::uint32_t id, std::string_view name, std::uint8_t slot, std::uint64_t dflt,
                          std::int64_t max) {
  ConfigKey k{id, name};
  k.slot = slot;
  k.plain_default = dflt;
  k.max = max;
  return k;
}

/// A key only the ZED-F9P knows.
constexpr ConfigKey f9p(ConfigKey k) {
  k.generations = kF9POnly;
  return k;
}

/// A plain F9P enum in [min, max].
constexpr ConfigKey f9p_enum(std::uint32_t id, std::string_view name, std::uint8_t slot, std::uint64_t dflt,
                             std::int64_t min, std::int64_t max) {
  ConfigKey k = plain(id, name, slot, dflt, max);
  k.min = min;
  return f9p(k);
}

/// A plain F9P key holding a signed value in [min, max] (I1/I4).
constexpr ConfigKey f9p_signed(std::uint32_t id, std::string_view name, std::uint8_t slot, std::int64_t min,
                               std::int64_t max) {
  ConfigKey k = plain(id, name, slot, 0, max);
  k.min = min;
  k.is_signed = true;
  return f9p(k);
}

/// inProtoMask/outProtoMask bit (proto:: bit index) of a port.
constexpr ConfigKey prot(std::uint32_t id, std::string_view name, KeyStore s, std::uint8_t port, std::uint8_t bit) {
  ConfigKey k{id, name, s, port};
  k.shift = bit;
  k.width = 1;
  return k;
}

/// A field of CFG-RATE / CFG-NAV5 / a stored block: width bits from bit shift
/// of the little-endian field at byte offset.
constexpr ConfigKey field(std::uint32_t id, std::string_view name, KeyStore s, MsgId block, std::uint8_t offset,
                          std::uint8_t shift, std::uint8_t width, std::int64_t min, std::int64_t max,
                          std::uint64_t allowed = 0, bool is_signed = false) {
  ConfigKey k{id, name, s, 0, block, offset, shift, width, is_signed, min, max, allowed};
  return k;
}

/// A port's infMsgMask in the stored CFG-INF block of protocolID index.
constexpr ConfigKey inf(std::uint32_t id, std::string_view name, std::uint8_t index, std::uint8_t port_id) {
  ConfigKey k = field(id, name, KeyStore::kBlock, msg::kCfgInf, static_cast<std::uint8_t>(4 + port_id), 0, 8, 0, 0xFF);
  k.port = index;
  return k;
}

constexpr ConfigKey gnss(std::uint32_t id, std::string_view name, std::uint8_t gnss_id, std::uint8_t bit) {
  return field(id, name, KeyStore::kGnss, msg::kCfgGnss, gnss_id, bit, 1, 0, 1);
}

constexpr std::uint64_t bits_of(std::initializer_list<int> values) {
  std::uint64_t m = 0;
  for (const int v : values) m |= std::uint64_t{1} << v;
  return m;
}

constexpr MsgId kRxmRtcm{0x02, 0x32};

/// CFG-MSGOUT messages: I2C key id (UART1 +1, UART2 +2, USB +3, SPI +4),
/// name, message (pyubx2 ubxtypes_configdb.py; SEC-SIG: PX4-GPSDrivers ubx.h).
struct MsgOutRow {
  std::uint32_t i2c_id;
  std::string_view name;
  MsgId msg;
  GenerationSet generations = kGen9;
};
constexpr MsgOutRow kMsgOutRows[] = {
    {0x20910006, "CFG-MSGOUT-UBX_NAV_PVT", msg::kNavPvt},
    {0x20910029, "CFG-MSGOUT-UBX_NAV_POSLLH", msg::kNavPosllh},
    {0x20910042, "CFG-MSGOUT-UBX_NAV_VELNED", msg::kNavVelned},
    {0x2091001A, "CFG-MSGOUT-UBX_NAV_STATUS", msg::kNavStatus},
    {0x20910038, "CFG-MSGOUT-UBX_NAV_DOP", msg::kNavDop},
    {0x2091005B, "CFG-MSGOUT-UBX_NAV_TIMEUTC", msg::kNavTimeutc},
    {0x20910047, "CFG-MSGOUT-UBX_NAV_TIMEGPS", msg::kNavTimegps},
    {0x20910015, "CFG-MSGOUT-UBX_NAV_SAT", msg::kNavSat},
    {0x20910345, "CFG-MSGOUT-UBX_NAV_SIG", msg::kNavSig},
    {0x2091004C, "CFG-MSGOUT-UBX_NAV_TIMEGLO", msg::kNavTimeglo},
    {0x20910056, "CFG-MSGOUT-UBX_NAV_TIMEGAL", msg::kNavTimegal},
    {0x20910051, "CFG-MSGOUT-UBX_NAV_TIMEBDS", msg::kNavTimebds},
    {0x209101B9, "CFG-MSGOUT-UBX_MON_HW2", msg::kMonHw2},
    {0x2091015F, "CFG-MSGOUT-UBX_NAV_EOE", msg::kNavEoe},
    {0x209101B4, "CFG-MSGOUT-UBX_MON_HW", msg::kMonHw},
    {0x20910359, "CFG-MSGOUT-UBX_MON_RF", msg::kMonRf},
    {0x20910634, "CFG-MSGOUT-UBX_SEC_SIG", msg::kSecSig},
    {0x20910268, "CFG-MSGOUT-UBX_RXM_RTCM", kRxmRtcm},
    {0x209102A4, "CFG-MSGOUT-UBX_RXM_RAWX", msg::kRxmRawx},
    {0x20910231, "CFG-MSGOUT-UBX_RXM_SFRBX", msg::kRxmSfrbx},
    // The ZED-F9P's high-precision and RTK messages (SparkFun u-blox_config_keys.h, HPG 1.32).
    {0x20910033, "CFG-MSGOUT-UBX_NAV_HPPOSLLH", msg::kNavHpposllh, kF9POnly},
    {0x2091002E, "CFG-MSGOUT-UBX_NAV_HPPOSECEF", msg::kNavHpposecef, kF9POnly},
    {0x2091008D, "CFG-MSGOUT-UBX_NAV_RELPOSNED", msg::kNavRelposned, kF9POnly},
    {0x209106B6, "CFG-MSGOUT-UBX_RXM_COR", msg::kRxmCor, kF9POnly},
    // RTCM 3 output of a base or moving base (CFG-MSG class 0xF5, id = the number's low byte).
    {0x209102BD, "CFG-MSGOUT-RTCM_3X_TYPE1005", MsgId{0xF5, 0x05}, kF9POnly},
    {0x2091035E, "CFG-MSGOUT-RTCM_3X_TYPE1074", MsgId{0xF5, 0x4A}, kF9POnly},
    {0x209102CC, "CFG-MSGOUT-RTCM_3X_TYPE1077", MsgId{0xF5, 0x4D}, kF9POnly},
    {0x20910363, "CFG-MSGOUT-RTCM_3X_TYPE1084", MsgId{0xF5, 0x54}, kF9POnly},
    {0x209102D1, "CFG-MSGOUT-RTCM_3X_TYPE1087", MsgId{0xF5, 0x57}, kF9POnly},
    {0x20910368, "CFG-MSGOUT-RTCM_3X_TYPE1094", MsgId{0xF5, 0x5E}, kF9POnly},
    {0x20910318, "CFG-MSGOUT-RTCM_3X_TYPE1097", MsgId{0xF5, 0x61}, kF9POnly},
    {0x2091036D, "CFG-MSGOUT-RTCM_3X_TYPE1124", MsgId{0xF5, 0x7C}, kF9POnly},
    {0x209102D6, "CFG-MSGOUT-RTCM_3X_TYPE1127", MsgId{0xF5, 0x7F}, kF9POnly},
    {0x20910303, "CFG-MSGOUT-RTCM_3X_TYPE1230", MsgId{0xF5, 0xE6}, kF9POnly},
    {0x209102FE, "CFG-MSGOUT-RTCM_3X_TYPE4072_0", MsgId{0xF5, 0xFE}, kF9POnly},
    {0x20910381, "CFG-MSGOUT-RTCM_3X_TYPE4072_1", MsgId{0xF5, 0xFD}, kF9POnly},
    {0x209100BA, "CFG-MSGOUT-NMEA_ID_GGA", msg::kNmeaGga},
    {0x209100C9, "CFG-MSGOUT-NMEA_ID_GLL", msg::kNmeaGll},
    {0x209100BF, "CFG-MSGOUT-NMEA_ID_GSA", msg::kNmeaGsa},
    {0x209100C4, "CFG-MSGOUT-NMEA_ID_GSV", msg::kNmeaGsv},
    {0x209100AB, "CFG-MSGOUT-NMEA_ID_RMC", msg::kNmeaRmc},
    {0x209100B0, "CFG-MSGOUT-NMEA_ID_VTG", msg::kNmeaVtg},
    {0x209100D3, "CFG-MSGOUT-NMEA_ID_GST", msg::kNmeaGst},
    {0x209100D8, "CFG-MSGOUT-NMEA_ID_ZDA", msg::kNmeaZda},
};
constexpr std::size_t kMsgOutPorts = kMsgOutPortSuffix.size();

using enum KeyStore;
// CFG-NAV5 byte offsets (UBX-13003221 CFG-NAV5).
constexpr std::uint8_t kNav5Dyn = 2, kNav5FixMode = 3, kNav5FixedAlt = 4, kNav5FixedAltVar = 8, kNav5MinElev = 12,
                       kNav5PDop = 14, kNav5TDop = 16, kNav5PAcc = 18, kNav5TAcc = 20, kNav5HoldThresh = 22,
                       kNav5DgnssTo = 23, kNav5CnoNumSvs = 24, kNav5Cno = 25, kNav5HoldDist = 28, kNav5Utc = 30;
constexpr MsgId kNone{};

constexpr ConfigKey kFixedKeys[] = {
    // Ports: protocol masks (UBX bit 0, NMEA bit 1, RTCM3 bit 5 of CFG-PRT).
    prot(0x10710001, "CFG-I2CINPROT-UBX", kInProto, kPortDdc, 0),
    prot(0x10710002, "CFG-I2CINPROT-NMEA", kInProto, kPortDdc, 1),
    prot(0x10710004, "CFG-I2CINPROT-RTCM3X", kInProto, kPortDdc, 5),
    prot(0x10720001, "CFG-I2COUTPROT-UBX", kOutProto, kPortDdc, 0),
    prot(0x10720002, "CFG-I2COUTPROT-NMEA", kOutProto, kPortDdc, 1),
    prot(0x10720004, "CFG-I2COUTPROT-RTCM3X", kOutProto, kPortDdc, 5),
    prot(0x10730001, "CFG-UART1INPROT-UBX", kInProto, kPortUart1, 0),
    prot(0x10730002, "CFG-UART1INPROT-NMEA", kInProto, kPortUart1, 1),
    prot(0x10730004, "CFG-UART1INPROT-RTCM3X", kInProto, kPortUart1, 5),
    prot(0x10740001, "CFG-UART1OUTPROT-UBX", kOutProto, kPortUart1, 0),
    prot(0x10740002, "CFG-UART1OUTPROT-NMEA", kOutProto, kPortUart1, 1),
    prot(0x10740004, "CFG-UART1OUTPROT-RTCM3X", kOutProto, kPortUart1, 5),
    prot(0x10770001, "CFG-USBINPROT-UBX", kInProto, kPortUsb, 0),
    prot(0x10770002, "CFG-USBINPROT-NMEA", kInProto, kPortUsb, 1),
    prot(0x10770004, "CFG-USBINPROT-RTCM3X", kInProto, kPortUsb, 5),
    prot(0x10780001, "CFG-USBOUTPROT-UBX", kOutProto, kPortUsb, 0),
    prot(0x10780002, "CFG-USBOUTPROT-NMEA", kOutProto, kPortUsb, 1),
    prot(0x10780004, "CFG-USBOUTPROT-RTCM3X", kOutProto, kPortUsb, 5),
    prot(0x10790001, "CFG-SPIINPROT-UBX", kInProto, kPortSpi, 0),
    prot(0x10790002, "CFG-SPIINPROT-NMEA", kInProto, kPortSpi, 1),
    prot(0x10790004, "CFG-SPIINPROT-RTCM3X", kInProto, kPortSpi, 5),
    prot(0x107A0001, "CFG-SPIOUTPROT-UBX", kOutProto, kPortSpi, 0),
    prot(0x107A0002, "CFG-SPIOUTPROT-NMEA", kOutProto, kPortSpi, 1),
    prot(0x107A0004, "CFG-SPIOUTPROT-RTCM3X", kOutProto, kPortSpi, 5),
    // UART1 line: a standard baud, 8N1 only (what the emulated line can run; CFG-PRT alike).
    ConfigKey{0x40520001, "CFG-UART1-BAUDRATE", kUartBaud, kPortUart1, kNone, 0, 0, 32, false, 0, kU4},
    // STOPBITS 1 = one, DATABITS 0 = eight, PARITY 0 = none.
    ConfigKey{0x20520002, "CFG-UART1-STOPBITS", kUartFraming, kPortUart1, kNone, 2, 0, 8, false, 1, 1},
    ConfigKey{0x20520003, "CFG-UART1-DATABITS", kUartFraming, kPortUart1, kNone, 3, 0, 8, false, 0, 0},
    ConfigKey{0x20520004, "CFG-UART1-PARITY", kUartFraming, kPortUart1, kNone, 4, 0, 8, false, 0, 0},
    plain(0x10520005, "CFG-UART1-ENABLED", 0, 1, 1),
    plain(0x10510003, "CFG-I2C-ENABLED", 1, 1, 1),
    plain(0x10650001, "CFG-USB-ENABLED", 2, 1, 1),
    plain(0x10640006, "CFG-SPI-ENABLED", 3, 0, 1),
    plain(0x20640001, "CFG-SPI-MAXFF", 4, 50, 63),
    // CFG-RATE (measRate >= 25 ms as CFG-RATE takes it, navRate 1..127, timeRef 0..4).
    field(0x30210001, "CFG-RATE-MEAS", kRate, kNone, 0, 0, 16, 25, kU2),
    field(0x30210002, "CFG-RATE-NAV", kRate, kNone, 2, 0, 16, 1, 127),
    field(0x20210003, "CFG-RATE-TIMEREF", kRate, kNone, 4, 0, 16, 0, 4),
    // CFG-NAVSPG: the CFG-NAV5 fields (dynModel 0, 2..9; fixMode 1..3; utcStandard 0, 3, 5, 6, 7).
    field(0x20110011, "CFG-NAVSPG-FIXMODE", kNav5, kNone, kNav5FixMode, 0, 8, 1, 3),
    field(0x2011001C, "CFG-NAVSPG-UTCSTANDARD", kNav5, kNone, kNav5Utc, 0, 8, 0, 7, bits_of({0, 3, 5, 6, 7})),
    field(0x20110021, "CFG-NAVSPG-DYNMODEL", kNav5, kNone, kNav5Dyn, 0, 8, 0, 9, bits_of({0, 2, 3, 4, 5, 6, 7, 8, 9})),
    plain(0x201100A1, "CFG-NAVSPG-INFIL_MINSVS", 5, 3, kU1),
    plain(0x201100A2, "CFG-NAVSPG-INFIL_MAXSVS", 6, 32, kU1),
    plain(0x201100A3, "CFG-NAVSPG-INFIL_MINCNO", 7, 6, kU1),
    field(0x201100A4, "CFG-NAVSPG-INFIL_MINELEV", kNav5, kNone, kNav5MinElev, 0, 8, -90, 90, 0, true),
    field(0x201100AA, "CFG-NAVSPG-INFIL_NCNOTHRS", kNav5, kNone, kNav5CnoNumSvs, 0, 8, 0, kU1),
    field(0x201100AB, "CFG-NAVSPG-INFIL_CNOTHRS", kNav5, kNone, kNav5Cno, 0, 8, 0, kU1),
    field(0x301100B1, "CFG-NAVSPG-OUTFIL_PDOP", kNav5, kNone, kNav5PDop, 0, 16, 0, kU2),
    field(0x301100B2, "CFG-NAVSPG-OUTFIL_TDOP", kNav5, kNone, kNav5TDop, 0, 16, 0, kU2),
    field(0x301100B3, "CFG-NAVSPG-OUTFIL_PACC", kNav5, kNone, kNav5PAcc, 0, 16, 0, kU2),
    field(0x301100B4, "CFG-NAVSPG-OUTFIL_TACC", kNav5, kNone, kNav5TAcc, 0, 16, 0, kU2),
    field(0x401100C1, "CFG-NAVSPG-CONSTR_ALT", kNav5, kNone, kNav5FixedAlt, 0, 32,
          std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max(), 0, true),
    field(0x401100C2, "CFG-NAVSPG-CONSTR_ALTVAR", kNav5, kNone, kNav5FixedAltVar, 0, 32, 0, kU4),
    field(0x201100C4, "CFG-NAVSPG-CONSTR_DGNSSTO", kNav5, kNone, kNav5DgnssTo, 0, 8, 0, kU1),
    // CFG-MOT: the static hold of CFG-NAV5 (cm/s, m).
    field(0x20250038, "CFG-MOT-GNSSSPEED_THRS", kNav5, kNone, kNav5HoldThresh, 0, 8, 0, kU1),
    field(0x3025003B, "CFG-MOT-GNSSDIST_THRS", kNav5, kNone, kNav5HoldDist, 0, 16, 0, kU2),
    // CFG-ODO: the CFG-ODO block (flags byte 4, odoCfg byte 5, speeds and gains 12..17).
    field(0x10220001, "CFG-ODO-USE_ODO", kBlock, msg::kCfgOdo, 4, 0, 1, 0, 1),
    field(0x10220002, "CFG-ODO-USE_COG", kBlock, msg::kCfgOdo, 4, 1, 1, 0, 1),
    field(0x10220003, "CFG-ODO-OUTLPVEL", kBlock, msg::kCfgOdo, 4, 2, 1, 0, 1),
    field(0x10220004, "CFG-ODO-OUTLPCOG", kBlock, msg::kCfgOdo, 4, 3, 1, 0, 1),
    field(0x20220005, "CFG-ODO-PROFILE", kBlock, msg::kCfgOdo, 5, 0, 3, 0, 4),
    field(0x20220021, "CFG-ODO-COGMAXSPEED", kBlock, msg::kCfgOdo, 12, 0, 8, 0, kU1),
    field(0x20220022, "CFG-ODO-COGMAXPOSACC", kBlock, msg::kCfgOdo, 13, 0, 8, 0, kU1),
    field(0x20220031, "CFG-ODO-VELLPGAIN", kBlock, msg::kCfgOdo, 16, 0, 8, 0, kU1),
    field(0x20220032, "CFG-ODO-COGLPGAIN", kBlock, msg::kCfgOdo, 17, 0, 8, 0, kU1),
    // CFG-INFMSG: the infMsgMask byte of each port (4 + port id) in the stored
    // CFG-INF blocks, protocolID 0 UBX and 1 NMEA; bits ERROR, WARNING, NOTICE,
    // TEST, DEBUG (UBX-18010854 CFG-INFMSG, UBX-13003221 CFG-INF).
    inf(0x20920001, "CFG-INFMSG-UBX_I2C", 0, kPortDdc),
    inf(0x20920002, "CFG-INFMSG-UBX_UART1", 0, kPortUart1),
    inf(0x20920003, "CFG-INFMSG-UBX_UART2", 0, kPortUart2),
    inf(0x20920004, "CFG-INFMSG-UBX_USB", 0, kPortUsb),
    inf(0x20920005, "CFG-INFMSG-UBX_SPI", 0, kPortSpi),
    inf(0x20920006, "CFG-INFMSG-NMEA_I2C", 1, kPortDdc),
    inf(0x20920007, "CFG-INFMSG-NMEA_UART1", 1, kPortUart1),
    inf(0x20920008, "CFG-INFMSG-NMEA_UART2", 1, kPortUart2),
    inf(0x20920009, "CFG-INFMSG-NMEA_USB", 1, kPortUsb),
    inf(0x2092000A, "CFG-INFMSG-NMEA_SPI", 1, kPortSpi),
    // CFG-ITFM: config (bbThreshold b0-3, cwThreshold b4-8, enable b31) and config2 (antSetting b12-13).
    field(0x20410001, "CFG-ITFM-BBTHRESHOLD", kBlock, msg::kCfgItfm, 0, 0, 4, 0, 15),
    field(0x20410002, "CFG-ITFM-CWTHRESHOLD", kBlock, msg::kCfgItfm, 0, 4, 5, 0, 31),
    field(0x1041000D, "CFG-ITFM-ENABLE", kBlock, msg::kCfgItfm, 0, 31, 1, 0, 1),
    field(0x20410010, "CFG-ITFM-ANTSETTING", kBlock, msg::kCfgItfm, 4, 12, 2, 0, 2),
    // CFG-SBAS: mode b1 test, usage b0 range, b1 diffCorr, b2 integrity.
    field(0x10360002, "CFG-SBAS-USE_TESTMODE", kBlock, msg::kCfgSbas, 0, 1, 1, 0, 1),
    field(0x10360003, "CFG-SBAS-USE_RANGING", kBlock, msg::kCfgSbas, 1, 0, 1, 0, 1),
    field(0x10360004, "CFG-SBAS-USE_DIFFCORR", kBlock, msg::kCfgSbas, 1, 1, 1, 0, 1),
    field(0x10360005, "CFG-SBAS-USE_INTEGRITY", kBlock, msg::kCfgSbas, 1, 2, 1, 0, 1),
    // CFG-SIGNAL: CFG-GNSS enable (flags b0) and signal (sigCfgMask b16) per gnssId. No
    // QZSS_L1S_ENA: a NEO-M9N does not know it and NAKs a VALSET carrying it (PX4-GPSDrivers#225).
    gnss(0x1031001F, "CFG-SIGNAL-GPS_ENA", 0, 0),
    gnss(0x10310001, "CFG-SIGNAL-GPS_L1CA_ENA", 0, 16),
    gnss(0x10310020, "CFG-SIGNAL-SBAS_ENA", 1, 0),
    gnss(0x10310005, "CFG-SIGNAL-SBAS_L1CA_ENA", 1, 16),
    gnss(0x10310021, "CFG-SIGNAL-GAL_ENA", 2, 0),
    gnss(0x10310007, "CFG-SIGNAL-GAL_E1_ENA", 2, 16),
    gnss(0x10310022, "CFG-SIGNAL-BDS_ENA", 3, 0),
    gnss(0x1031000D, "CFG-SIGNAL-BDS_B1_ENA", 3, 16),
    gnss(0x10310024, "CFG-SIGNAL-QZSS_ENA", 5, 0),
    gnss(0x10310012, "CFG-SIGNAL-QZSS_L1CA_ENA", 5, 16),
    gnss(0x10310025, "CFG-SIGNAL-GLO_ENA", 6, 0),
    gnss(0x10310018, "CFG-SIGNAL-GLO_L1_ENA", 6, 16),
    // The F9P's second band (sigCfgMask bits 4/5 = flags bits 20/21) and QZSS L1S (bit 2).
    f9p(gnss(0x10310003, "CFG-SIGNAL-GPS_L2C_ENA", 0, 20)),
    f9p(gnss(0x1031000A, "CFG-SIGNAL-GAL_E5B_ENA", 2, 21)),
    f9p(gnss(0x1031000E, "CFG-SIGNAL-BDS_B2_ENA", 3, 20)),
    f9p(gnss(0x10310014, "CFG-SIGNAL-QZSS_L1S_ENA", 5, 18)),
    f9p(gnss(0x10310015, "CFG-SIGNAL-QZSS_L2C_ENA", 5, 20)),
    f9p(gnss(0x1031001A, "CFG-SIGNAL-GLO_L2_ENA", 6, 20)),
    // CFG-NAVHPG-DGNSSMODE: 2 RTK float (no ambiguity fixing), 3 RTK fixed (factory).
    f9p_enum(0x20140011, "CFG-NAVHPG-DGNSSMODE", 8, 3, 2, 3),
    // UART2 (the F9P's second UART: RTCM between a moving base and its rover).
    f9p(prot(0x10750001, "CFG-UART2INPROT-UBX", kInProto, kPortUart2, 0)),
    f9p(prot(0x10750002, "CFG-UART2INPROT-NMEA", kInProto, kPortUart2, 1)),
    f9p(prot(0x10750004, "CFG-UART2INPROT-RTCM3X", kInProto, kPortUart2, 5)),
    f9p(prot(0x10760001, "CFG-UART2OUTPROT-UBX", kOutProto, kPortUart2, 0)),
    f9p(prot(0x10760002, "CFG-UART2OUTPROT-NMEA", kOutProto, kPortUart2, 1)),
    f9p(prot(0x10760004, "CFG-UART2OUTPROT-RTCM3X", kOutProto, kPortUart2, 5)),
    f9p(ConfigKey{0x40530001, "CFG-UART2-BAUDRATE", kUartBaud, kPortUart2, kNone, 0, 0, 32, false, 0, kU4}),
    f9p(ConfigKey{0x20530002, "CFG-UART2-STOPBITS", kUartFraming, kPortUart2, kNone, 2, 0, 8, false, 1, 1}),
    f9p(ConfigKey{0x20530003, "CFG-UART2-DATABITS", kUartFraming, kPortUart2, kNone, 3, 0, 8, false, 0, 0}),
    f9p(ConfigKey{0x20530004, "CFG-UART2-PARITY", kUartFraming, kPortUart2, kNone, 4, 0, 8, false, 0, 0}),
    f9p(plain(0x10530005, "CFG-UART2-ENABLED", 9, 1, 1)),
    // CFG-TMODE: the base station's survey-in or fixed position (cm, 0.1 mm HP parts,
    // 1e-7 deg; accuracies 0.1 mm; survey-in duration s).
    f9p(plain(0x20030001, "CFG-TMODE-MODE", 10, 0, 2)),
    f9p(plain(0x20030002, "CFG-TMODE-POS_TYPE", 11, 0, 1)),
    f9p_signed(0x40030003, "CFG-TMODE-ECEF_X", 12, kI4Min, kI4Max),
    f9p_signed(0x40030004, "CFG-TMODE-ECEF_Y", 13, kI4Min, kI4Max),
    f9p_signed(0x40030005, "CFG-TMODE-ECEF_Z", 14, kI4Min, kI4Max),
    f9p_signed(0x20030006, "CFG-TMODE-ECEF_X_HP", 15, -99, 99),
    f9p_signed(0x20030007, "CFG-TMODE-ECEF_Y_HP", 16, -99, 99),
    f9p_signed(0x20030008, "CFG-TMODE-ECEF_Z_HP", 17, -99, 99),
    f9p_signed(0x40030009, "CFG-TMODE-LAT", 18, -900000000, 900000000),
    f9p_signed(0x4003000A, "CFG-TMODE-LON", 19, -1800000000, 1800000000),
    f9p_signed(0x4003000B, "CFG-TMODE-HEIGHT", 20, kI4Min, kI4Max),
    f9p_signed(0x2003000C, "CFG-TMODE-LAT_HP", 21, -99, 99),
    f9p_signed(0x2003000D, "CFG-TMODE-LON_HP", 22, -99, 99),
    f9p_signed(0x2003000E, "CFG-TMODE-HEIGHT_HP", 23, -99, 99),
    f9p(plain(0x4003000F, "CFG-TMODE-FIXED_POS_ACC", 24, 100, kU4)),
    f9p(plain(0x40030010, "CFG-TMODE-SVIN_MIN_DUR", 25, 60, kU4)),
    f9p(plain(0x40030011, "CFG-TMODE-SVIN_ACC_LIMIT", 26, 500, kU4)),
    // CFG-NMEA-PROTVER: 21, 23, 40, 41, 42 (= 4.11) for nmeaVersion 0x21 .. 0x4B.
    field(0x20930001, "CFG-NMEA-PROTVER", kNmeaProtver, msg::kCfgNmea, 1, 0, 8, 21, 42, bits_of({21, 23, 40, 41, 42})),
    // The other CFG-NMEA fields (legacy CFG-NMEA v1: filter 0, numSV 2, flags 3, gnssToFilter 4,
    // svNumbering 8, mainTalkerId 9, gsvTalkerId 10, bdsTalkerId 12).
    field(0x20930002, "CFG-NMEA-MAXSVS", kBlock, msg::kCfgNmea, 2, 0, 8, 0, 16, bits_of({0, 8, 12, 16})),
    field(0x10930003, "CFG-NMEA-COMPAT", kBlock, msg::kCfgNmea, 3, 0, 1, 0, 1),
    field(0x10930004, "CFG-NMEA-CONSIDER", kBlock, msg::kCfgNmea, 3, 1, 1, 0, 1),
    field(0x10930005, "CFG-NMEA-LIMIT82", kBlock, msg::kCfgNmea, 3, 2, 1, 0, 1),
    field(0x10930006, "CFG-NMEA-HIGHPREC", kBlock, msg::kCfgNmea, 3, 3, 1, 0, 1),
    field(0x20930007, "CFG-NMEA-SVNUMBERING", kBlock, msg::kCfgNmea, 8, 0, 8, 0, 1),
    field(0x10930011, "CFG-NMEA-FILT_GPS", kBlock, msg::kCfgNmea, 4, 0, 1, 0, 1),
    field(0x10930012, "CFG-NMEA-FILT_SBAS", kBlock, msg::kCfgNmea, 4, 1, 1, 0, 1),
    field(0x10930013, "CFG-NMEA-FILT_GAL", kBlock, msg::kCfgNmea, 4, 2, 1, 0, 1),
    field(0x10930015, "CFG-NMEA-FILT_QZSS", kBlock, msg::kCfgNmea, 4, 4, 1, 0, 1),
    field(0x10930016, "CFG-NMEA-FILT_GLO", kBlock, msg::kCfgNmea, 4, 5, 1, 0, 1),
    field(0x10930017, "CFG-NMEA-FILT_BDS", kBlock, msg::kCfgNmea, 4, 6, 1, 0, 1),
    field(0x10930021, "CFG-NMEA-OUT_INVFIX", kBlock, msg::kCfgNmea, 0, 0, 1, 0, 1),
    field(0x10930022, "CFG-NMEA-OUT_MSKFIX", kBlock, msg::kCfgNmea, 0, 1, 1, 0, 1),
    field(0x10930023, "CFG-NMEA-OUT_INVTIME", kBlock, msg::kCfgNmea, 0, 2, 1, 0, 1),
    field(0x10930024, "CFG-NMEA-OUT_INVDATE", kBlock, msg::kCfgNmea, 0, 3, 1, 0, 1),
    field(0x10930025, "CFG-NMEA-OUT_ONLYGPS", kBlock, msg::kCfgNmea, 0, 4, 1, 0, 1),
    field(0x10930026, "CFG-NMEA-OUT_FROZENCOG", kBlock, msg::kCfgNmea, 0, 5, 1, 0, 1),
    field(0x20930031, "CFG-NMEA-MAINTALKERID", kBlock, msg::kCfgNmea, 9, 0, 8, 0, 7, bits_of({0, 1, 2, 3, 4, 5, 7})),
    field(0x20930032, "CFG-NMEA-GSVTALKERID", kBlock, msg::kCfgNmea, 10, 0, 8, 0, 1),
    field(0x30930033, "CFG-NMEA-BDSTALKERID", kBlock, msg::kCfgNmea, 12, 0, 16, 0, kU2),
};

constexpr std::size_t kNumKeys = std::size(kFixedKeys) + std::size(kMsgOutRows) * kMsgOutPorts;

constexpr std::array<ConfigKey, kNumKeys> kKeys = [] {
  std::array<ConfigKey, kNumKeys> keys{};
  std::size_t n = 0;
  for (const ConfigKey& k : kFixedKeys) keys[n++] = k;
  for (const MsgOutRow& m : kMsgOutRows) {
    for (std::uint8_t port = 0; port < kMsgOutPorts; ++port) {
      ConfigKey k{m.i2c_id + port, m.name, KeyStore::kMsgOut, port, m.msg};
      k.max = kU1;
      k.generations = m.generations;
      keys[n++] = k;
    }
  }
  return keys;
}();

constexpr bool keys_consistent() {
  for (std::size_t i = 0; i < kKeys.size(); ++i) {
    const ConfigKey& k = kKeys[i];
    const std::size_t bytes = k.value_bytes();
    if (bytes == 0 || k.min > k.max) return false;
    if ((k.id >> 28 & 0x7) == 1 && k.max > 1) return false;  // L: one bit
    if (bytes < 8 && !k.is_signed && k.max > (std::int64_t{1} << (8 * bytes)) - 1) return false;
    if (k.store == KeyStore::kPlain && k.slot >= kMaxPlainValues) return false;
    for (std::size_t j = i + 1; j < kKeys.size(); ++j) {
      if (kKeys[j].id == k.id) return false;
    }
  }
  return true;
}
static_assert(keys_consistent(), "config keys: a size nibble, range, slot or duplicate id is wrong");

/// Row of key id in kKeys (kKeys.size() when absent), for rows code reads by name.
constexpr std::size_t key_row(std::uint32_t id) {
  for (std::size_t i = 0; i < kKeys.size(); ++i) {
    if (kKeys[i].id == id) return i;
  }
  return kKeys.size();
}
constexpr std::size_t kItfmEnableRow = key_row(0x1041000D), kItfmBbRow = key_row(0x20410001),
                      kItfmCwRow = key_row(0x20410002);
static_assert(kItfmEnableRow < kNumKeys && kItfmBbRow < kNumKeys && kItfmCwRow < kNumKeys);
static_assert(kNumKeys <= sizeof(ValTransaction::pending) / sizeof(ValTransaction::Pending),
              "a transaction holds every key once");

constexpr std::uint64_t mask_of(std::uint8_t width) noexcept {
  return width >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << width) - 1;
}

/// Bytes of the little-endian field holding k's bits, or 0 when it lies outside size.
std::size_t field_bytes(const ConfigKey& k, std::size_t size) noexcept {
  const std::size_t n = (k.shift + k.width + 7u) / 8u;
  return k.offset + n <= size ? n : 0;
}

/// width bits from shift of the little-endian field at offset of bytes (0 when outside).
std::uint64_t get_bits(std::span<const std::uint8_t> bytes, const ConfigKey& k) noexcept {
  const std::size_t n = field_bytes(k, bytes.size());
  return n == 0 ? 0 : load_le(bytes, k.offset, n) >> k.shift & mask_of(k.width);
}

bool set_bits(std::span<std::uint8_t> bytes, const ConfigKey& k, std::uint64_t value) noexcept {
  const std::size_t n = field_bytes(k, bytes.size());
  if (n == 0) return false;
  const std::uint64_t m = mask_of(k.width) << k.shift;
  const std::uint64_t v = (load_le(bytes, k.offset, n) & ~m) | ((value << k.shift) & m);
  store_le(bytes, k.offset, n, v);
  return true;
}

template <class T>
std::span<std::uint8_t> bytes_of(T& wire) noexcept {
  return {reinterpret_cast<std::uint8_t*>(&wire), sizeof wire};
}
template <class T>
std::span<const std::uint8_t> bytes_of(const T& wire) noexcept {
  return {reinterpret_cast<const std::uint8_t*>(&wire), sizeof wire};
}

/// Byte offset of the flags of gnssId in a CFG-GNSS payload, or 0 when absent.
std::size_t gnss_flags_offset(std::span<const std::uint8_t> p, std::uint8_t gnss_id) noexcept {
  if (p.size() < 4) return 0;
  for (std::size_t b = 0; b < p[3] && 4 + 8 * b + 8 <= p.size(); ++b) {
    if (p[4 + 8 * b] == gnss_id) return 4 + 8 * b + 4;
  }
  return 0;
}

/// CFG-NMEA nmeaVersion <-> CFG-NMEA-PROTVER.
constexpr std::uint8_t kNmeaHex[] = {0x21, 0x23, 0x40, 0x41, 0x4B};
constexpr std::uint8_t kNmeaDec[] = {21, 23, 40, 41, 42};

std::int64_t as_signed(std::uint64_t v, std::size_t bytes) noexcept {
  if (bytes >= 8) return static_cast<std::int64_t>(v);
  const std::uint64_t sign = std::uint64_t{1} << (8 * bytes - 1);
  const std::uint64_t m = (std::uint64_t{1} << (8 * bytes)) - 1;
  v &= m;
  return static_cast<std::int64_t>((v ^ sign)) - static_cast<std::int64_t>(sign);
}

}  // namespace

std::span<const ConfigKey> config_keys() noexcept { return kKeys; }

ItfmSettings itfm_settings(const DeviceConfig& c) noexcept {
  ItfmSettings s;
  s.enabled = read_config_key(kKeys[kItfmEnableRow], c, 0) != 0;
  s.bb_threshold_db = static_cast<double>(read_config_key(kKeys[kItfmBbRow], c, 0));
  s.cw_threshold_db = static_cast<double>(read_config_key(kKeys[kItfmCwRow], c, 0));
  return s;
}

const ConfigKey* find_config_key(std::uint32_t key_id) noexcept {
  for (const ConfigKey& k : kKeys) {
    if (k.id == key_id) return &k;
  }
  return nullptr;
}

const ConfigKey* find_config_key(std::uint32_t key_id, Generation g) noexcept {
  const ConfigKey* k = find_config_key(key_id);
  return k != nullptr && k->exists_on(g) ? k : nullptr;
}

std::string config_key_name(const ConfigKey& k) {
  std::string s(k.name);
  if (k.store == KeyStore::kMsgOut) s += kMsgOutPortSuffix[k.port];
  return s;
}

std::uint64_t read_config_key(const ConfigKey& k, const DeviceConfig& c, std::size_t uart) noexcept {
  const auto port = [&]() -> const PortSettings& { return c.port(c.column(uart, k.port)); };
  switch (k.store) {
    case KeyStore::kPlain: return c.plain_value(k.slot);
    case KeyStore::kInProto: return port().in_proto_mask >> k.shift & 1u;
    case KeyStore::kOutProto: return port().out_proto_mask >> k.shift & 1u;
    case KeyStore::kUartBaud: return port().baud_bps;
    case KeyStore::kUartFraming:
      // The emulated lines run 8N1 (CFG-PRT mode 0x8C0): one stop bit (1), eight data bits (0), no parity (0).
      return k.offset == 2 ? 1 : 0;
    case KeyStore::kMsgOut: return c.message_rate(c.column(uart, k.port), k.msg);
    case KeyStore::kRate: return get_bits(bytes_of(c.rate), k);
    case KeyStore::kNav5: return get_bits(bytes_of(c.nav5), k);
    case KeyStore::kBlock: {
      const StoredBlock* b = c.stored(k.msg, k.port);
      return b != nullptr ? get_bits(b->payload(), k) : 0;
    }
    case KeyStore::kGnss: {
      const StoredBlock* b = c.stored(k.msg);
      if (b == nullptr) return 0;
      const std::size_t off = gnss_flags_offset(b->payload(), k.offset);
      if (off == 0) return 0;
      ConfigKey at = k;
      at.offset = static_cast<std::uint8_t>(off);
      return get_bits(b->payload(), at);
    }
    case KeyStore::kNmeaProtver: {
      const StoredBlock* b = c.stored(k.msg);
      if (b == nullptr || b->size <= k.offset) return 0;
      for (std::size_t i = 0; i < std::size(kNmeaHex); ++i) {
        if (b->bytes[k.offset] == kNmeaHex[i]) return kNmeaDec[i];
      }
      return 0;
    }
  }
  return 0;
}

bool valid_config_value(const ConfigKey& k, std::uint64_t value) noexcept {
  const std::size_t bytes = k.value_bytes();
  if (bytes < 8 && (value >> (8 * bytes)) != 0) return false;
  if (k.store == KeyStore::kUartBaud) return is_ubx_baud(static_cast<std::uint32_t>(value));
  if (k.is_signed) {
    const std::int64_t s = as_signed(value, bytes);
    return s >= k.min && s <= k.max;
  }
  if (value > static_cast<std::uint64_t>(k.max) || static_cast<std::int64_t>(value) < k.min) return false;
  return k.allowed == 0 || (value < 64 && (k.allowed >> value & 1u));
}

bool write_config_key(const ConfigKey& k, DeviceConfig& c, std::size_t uart, std::uint64_t value) noexcept {
  const auto port = [&]() -> PortSettings& { return c.port(c.column(uart, k.port)); };
  const auto set_bit = [&](std::uint16_t& mask) {
    mask = static_cast<std::uint16_t>((mask & ~(1u << k.shift)) | ((value & 1u) << k.shift));
  };
  switch (k.store) {
    case KeyStore::kPlain: c.set_plain_value(k.slot, value); return true;
    case KeyStore::kInProto: set_bit(port().in_proto_mask); return true;
    case KeyStore::kOutProto: set_bit(port().out_proto_mask); return true;
    case KeyStore::kUartBaud: port().baud_bps = static_cast<std::uint32_t>(value); return true;
    case KeyStore::kUartFraming: return true;  // only 8N1 is valid, and that is what the line runs
    case KeyStore::kMsgOut:
      return c.set_message_rate(c.column(uart, k.port), k.msg, static_cast<std::uint8_t>(value));
    case KeyStore::kRate: return set_bits(bytes_of(c.rate), k, value);
    case KeyStore::kNav5: {
      const bool ok = set_bits(bytes_of(c.nav5), k, value);
      c.nav5.mask = 0xFFFF;  // as after a CFG-NAV5 set: a poll reports every field
      return ok;
    }
    case KeyStore::kBlock:
    case KeyStore::kGnss:
    case KeyStore::kNmeaProtver: {
      const std::uint8_t index = k.store == KeyStore::kBlock ? k.port : 0;
      const StoredBlock* b = c.stored(k.msg, index);
      if (b == nullptr) return false;
      std::array<std::uint8_t, kMaxStoredBytes> bytes = b->bytes;
      const std::span<std::uint8_t> payload{bytes.data(), b->size};
      ConfigKey at = k;
      if (k.store == KeyStore::kGnss) {
        const std::size_t off = gnss_flags_offset(payload, k.offset);
        if (off == 0) return false;
        at.offset = static_cast<std::uint8_t>(off);
      }
      if (k.store == KeyStore::kNmeaProtver) {
        const auto* dec = std::find(std::begin(kNmeaDec), std::end(kNmeaDec), value);
        if (dec == std::end(kNmeaDec) || b->size <= k.offset) return false;
        payload[k.offset] = kNmeaHex[dec - std::begin(kNmeaDec)];
      } else if (!set_bits(payload, at, value)) {
        return false;
      }
      return c.store(k.msg, index, payload);
    }
  }
  return false;
}

void set_plain_defaults(DeviceConfig& c) noexcept {
  for (const ConfigKey& k : kKeys) {
    if (k.store == KeyStore::kPlain) c.set_plain_value(k.slot, k.plain_default);
  }
}

}  // namespace gnssemu::protocol::ubx
