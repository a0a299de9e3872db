// SPDX-License-Identifier: Apache-2.0
#include "core/protocol/ubx/wire/ubx_pubx.hpp"

#include <charconv>

#include "core/protocol/nmea/nmea_sentences.hpp"
#include "core/protocol/ubx/config/ubx_ports.hpp"

namespace gnssemu::protocol::ubx {

namespace {

/// Fields between "$" and "*hh", split at commas into fields[0..n).
struct Fields {
  static constexpr std::size_t kMax = 12;
  std::string_view f[kMax];
  std::size_t n = 0;
};

bool split(std::string_view sentence, Fields& out) noexcept {
  if (sentence.size() < 4 || sentence.front() != '$' || sentence[sentence.size() - 3] != '*') return false;
  std::string_view body = sentence.substr(1, sentence.size() - 4);
  while (true) {
    if (out.n == Fields::kMax) return false;
    const std::size_t comma = body.find(',');
    out.f[out.n++] = body.substr(0, comma);
    if (comma == std::string_view::npos) return true;
    body.remove_prefix(comma + 1);
  }
}

template <class T>
bool parse_uint(std::string_view s, T& v, int base = 10) noexcept {
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v, base);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

}  // namespace

int nmea_msg_id(std::string_view formatter) noexcept {
  if (const auto s = nmea::sentence_by_name(formatter)) return nmea::info(*s).msg_id;
  // Formatters u-blox rates that the encoder does not write (UBX-13003221
  // §31.1 "NMEA messages overview").
  static constexpr struct {
    std::string_view name;
    std::uint8_t id;
  } kOthers[] = {{"GRS", 0x06}, {"GBS", 0x09}, {"DTM", 0x0A}, {"GNS", 0x0D}, {"THS", 0x0E}, {"VLW", 0x0F}, {"TXT", 0x41}};
  for (const auto& o : kOthers) {
    if (o.name == formatter) return o.id;
  }
  return -1;
}

std::optional<Pubx41> parse_pubx41(std::string_view sentence) noexcept {
  Fields fl;
  if (!split(sentence, fl) || fl.n != 7 || fl.f[0] != "PUBX" || fl.f[1] != "41") return std::nullopt;
  Pubx41 p;
  unsigned port = 0, autob = 0;
  if (!parse_uint(fl.f[2], port) || port > 5) return std::nullopt;
  if (!parse_uint(fl.f[3], p.in_proto_mask, 16) || !parse_uint(fl.f[4], p.out_proto_mask, 16)) return std::nullopt;
  if (!parse_uint(fl.f[5], p.baud_bps) || !is_ubx_baud(p.baud_bps)) return std::nullopt;
  if (!parse_uint(fl.f[6], autob) || autob > 1) return std::nullopt;
  p.port_id = static_cast<std::uint8_t>(port);
  p.autobauding = autob == 1;
  return p;
}

std::optional<Pubx40> parse_pubx40(std::string_view sentence) noexcept {
  Fields fl;
  if (!split(sentence, fl) || fl.n < 8 || fl.n > 9 || fl.f[0] != "PUBX" || fl.f[1] != "40") return std::nullopt;
  const int id = nmea_msg_id(fl.f[2]);
  if (id < 0) return std::nullopt;
  Pubx40 p;
  p.nmea_id = static_cast<std::uint8_t>(id);
  for (std::size_t i = 0; i + 3 < fl.n; ++i) {
    if (!parse_uint(fl.f[3 + i], p.rates[i])) return std::nullopt;
  }
  return p;
}

}  // namespace gnssemu::protocol::ubx
