// SPDX-License-Identifier: Apache-2.0
#pragma once
// Names of the periodic messages a port can be configured to send, with their
// u-blox class and id (CFG-MSG addresses): the configuration's view of the
// core tables (ubx::kPeriodicMessages, nmea::kSentences).
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "core/protocol/nmea/nmea_sentences.hpp"

namespace gnssemu::config {

struct MessageName {
  std::string_view name;  ///< "NAV-PVT", "GGA"
  uint8_t msg_class;      ///< UBX class; 0xF0 for standard NMEA sentences
  uint8_t msg_id;
};

inline constexpr uint8_t kNmeaClass = protocol::nmea::kMsgClass;

/// Periodic UBX messages a port's ubx_messages may list, in configuration order.
std::span<const MessageName> ubx_periodic_messages();
/// NMEA sentences the encoder writes, in u-blox output order (RMC VTG GGA GSA GSV GLL GST ZDA).
std::span<const MessageName> nmea_sentences();

/// Entry by name (exact, case-sensitive) among both tables.
std::optional<MessageName> message_by_name(std::string_view name);
/// Name of (class, id), or "" when it is not one of the tables' messages.
std::string_view message_name(uint8_t msg_class, uint8_t msg_id);

/// Whether the NMEA sentence of CFG-MSG id msg_id is in sentences.
bool sentence_on(const protocol::nmea::SentenceSet& sentences, uint8_t msg_id);

}  // namespace gnssemu::config
