#include "config/message_names.hpp"

#include <array>

namespace gnssemu::config {
namespace {

constexpr std::array<MessageName, 11> kUbx{{
    {"NAV-PVT", 0x01, 0x07},
    {"NAV-POSLLH", 0x01, 0x02},
    {"NAV-VELNED", 0x01, 0x12},
    {"NAV-STATUS", 0x01, 0x03},
    {"NAV-DOP", 0x01, 0x04},
    {"NAV-SOL", 0x01, 0x06},
    {"NAV-TIMEUTC", 0x01, 0x21},
    {"NAV-SAT", 0x01, 0x35},
    {"NAV-SVINFO", 0x01, 0x30},
    {"MON-HW", 0x0A, 0x09},
    {"NAV-EOE", 0x01, 0x61},
}};

constexpr std::array<MessageName, 8> kNmea{{
    {"RMC", kNmeaClass, 0x04},
    {"VTG", kNmeaClass, 0x05},
    {"GGA", kNmeaClass, 0x00},
    {"GSA", kNmeaClass, 0x02},
    {"GSV", kNmeaClass, 0x03},
    {"GLL", kNmeaClass, 0x01},
    {"GST", kNmeaClass, 0x07},
    {"ZDA", kNmeaClass, 0x08},
}};

}  // namespace

std::span<const MessageName> ubx_periodic_messages() { return kUbx; }
std::span<const MessageName> nmea_sentences() { return kNmea; }

std::optional<MessageName> message_by_name(std::string_view name) {
  for (const std::span<const MessageName> table : {ubx_periodic_messages(), nmea_sentences()}) {
    for (const MessageName& m : table) {
      if (m.name == name) return m;
    }
  }
  return std::nullopt;
}

std::string_view message_name(uint8_t msg_class, uint8_t msg_id) {
  for (const std::span<const MessageName> table : {ubx_periodic_messages(), nmea_sentences()}) {
    for (const MessageName& m : table) {
      if (m.msg_class == msg_class && m.msg_id == msg_id) return m.name;
    }
  }
  return {};
}

}  // namespace gnssemu::config
