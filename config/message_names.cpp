// SPDX-License-Identifier: Apache-2.0
#include "config/message_names.hpp"

#include <array>

#include "core/protocol/nmea/nmea_sentences.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"

namespace gnssemu::config {
namespace {

namespace ubx = protocol::ubx;
namespace nmea = protocol::nmea;

constexpr std::size_t kNumConfigurable = [] {
  std::size_t n = 0;
  for (const ubx::PeriodicMessage& m : ubx::kPeriodicMessages) n += m.configurable ? 1 : 0;
  return n;
}();

constexpr std::array<MessageName, kNumConfigurable> kUbx = [] {
  std::array<MessageName, kNumConfigurable> out{};
  std::size_t n = 0;
  for (const ubx::PeriodicMessage& m : ubx::kPeriodicMessages) {
    if (m.configurable) out[n++] = {m.name, m.id.cls, m.id.id};
  }
  return out;
}();

constexpr std::array<MessageName, nmea::kNumSentences> kNmea = [] {
  std::array<MessageName, nmea::kNumSentences> out{};
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = {nmea::kSentences[i].name, kNmeaClass, nmea::kSentences[i].msg_id};
  return out;
}();

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

bool sentence_on(const protocol::nmea::SentenceSet& sentences, uint8_t msg_id) {
  const std::optional<protocol::nmea::Sentence> sentence = protocol::nmea::sentence_by_msg_id(msg_id);
  return sentence && sentences.has(*sentence);
}

}  // namespace gnssemu::config
