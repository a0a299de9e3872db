// SPDX-License-Identifier: Apache-2.0
// The saved configuration as text: what survives a power cycle of the
// emulated chip (its BBR/flash), written to and read from a state file by
// the daemon. One setting per line, little to parse, diffable:
//   gnssemu-ubx-state 1
//   port <column> <portId> <exists> <txReady> <mode> <baud> <inProto> <outProto> <flags> <autobauding>
//   rate <class> <id> <rate per column ...>
//   cfg-rate <measRate> <navRate> <timeRef>
//   nav5 <36 bytes hex>
//   block <class> <id> <index> <payload hex>
//   plain <slot> <value>
#include <charconv>
#include <cstring>
#include <vector>

#include "core/common/error.hpp"
#include "core/protocol/ubx/config/ubx_device_config.hpp"

namespace gnssemu::protocol::ubx {

namespace {

constexpr std::string_view kMagic = "gnssemu-ubx-state 1";

void hex(std::string& out, std::span<const std::uint8_t> bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  for (const std::uint8_t b : bytes) {
    out += kDigits[b >> 4];
    out += kDigits[b & 0xF];
  }
}

/// Words of one line.
std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> w;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t b = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > b) w.push_back(line.substr(b, i - b));
  }
  return w;
}

}  // namespace

std::string DeviceConfig::to_text() const {
  std::string out(kMagic);
  out += '\n';
  const auto num = [&out](std::uint64_t v) {
    out += ' ';
    out += std::to_string(v);
  };
  for (std::size_t c = 0; c < ports_.size(); ++c) {
    const PortSettings& p = ports_[c];
    out += "port";
    for (const std::uint64_t v : {std::uint64_t{c}, std::uint64_t{p.port_id}, std::uint64_t{p.exists},
                                  std::uint64_t{p.tx_ready}, std::uint64_t{p.mode}, std::uint64_t{p.baud_bps},
                                  std::uint64_t{p.in_proto_mask}, std::uint64_t{p.out_proto_mask},
                                  std::uint64_t{p.flags}, std::uint64_t{p.autobauding}}) {
      num(v);
    }
    out += '\n';
  }
  for (std::size_t r = 0; r < num_rates_; ++r) {
    out += "rate";
    num(rate_ids_[r].cls);
    num(rate_ids_[r].id);
    for (std::size_t c = 0; c < columns(); ++c) num(rates_[r * columns() + c]);
    out += '\n';
  }
  out += "cfg-rate";
  num(rate.measRate);
  num(rate.navRate);
  num(rate.timeRef);
  out += "\nnav5 ";
  hex(out, {reinterpret_cast<const std::uint8_t*>(&nav5), sizeof nav5});
  out += '\n';
  for (std::size_t i = 0; i < num_blocks_; ++i) {
    out += "block";
    num(blocks_[i].id.cls);
    num(blocks_[i].id.id);
    num(blocks_[i].index);
    out += ' ';
    hex(out, blocks_[i].payload());
    out += '\n';
  }
  for (std::size_t slot = 0; slot < plain_.size(); ++slot) {
    out += "plain";
    num(slot);
    num(plain_[slot]);
    out += '\n';
  }
  return out;
}

void DeviceConfig::read_text(std::string_view text, const std::string& source) {
  DeviceConfig c = *this;
  int line_no = 0;
  bool magic = false;
  while (!text.empty()) {
    const std::size_t nl = text.find('\n');
    const std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    ++line_no;
    const auto fail = [&](const std::string& why) { throw Error(source, line_no, why); };
    const std::vector<std::string_view> w = words(line);
    if (w.empty() || w[0].front() == '#') continue;
    if (!magic) {
      if (line.substr(0, kMagic.size()) != kMagic) fail("not a gnssemu u-blox state file (first line '" + std::string(kMagic) + "')");
      magic = true;
      continue;
    }
    const auto number = [&](std::size_t i, std::uint64_t max) {
      std::uint64_t v = 0;
      if (i >= w.size()) fail(std::string("missing field ").append(std::to_string(i)).append(" of ").append(w[0]));
      const auto [end, ec] = std::from_chars(w[i].data(), w[i].data() + w[i].size(), v);
      if (ec != std::errc{} || end != w[i].data() + w[i].size() || v > max) {
        fail(std::string(w[i]).append(" is not a number in [0, ").append(std::to_string(max)).append("]"));
      }
      return v;
    };
    const auto bytes = [&](std::size_t i, std::size_t max_bytes) {
      std::vector<std::uint8_t> b;
      if (i >= w.size() || w[i].size() % 2 != 0 || w[i].size() / 2 > max_bytes) fail("bad hex payload");
      for (std::size_t k = 0; k < w[i].size(); k += 2) {
        unsigned v = 0;
        const auto [end, ec] = std::from_chars(w[i].data() + k, w[i].data() + k + 2, v, 16);
        if (ec != std::errc{} || end != w[i].data() + k + 2) fail("bad hex payload");
        b.push_back(static_cast<std::uint8_t>(v));
      }
      return b;
    };
    const std::string_view kind = w[0];
    if (kind == "port") {
      const std::size_t col = number(1, 1000);
      if (col >= c.columns()) continue;  // an output this run does not have
      PortSettings p;
      p.port_id = static_cast<std::uint8_t>(number(2, kNumPorts - 1));
      p.exists = number(3, 1) != 0;
      p.tx_ready = static_cast<std::uint16_t>(number(4, 0xFFFF));
      p.mode = static_cast<std::uint32_t>(number(5, 0xFFFFFFFF));
      p.baud_bps = static_cast<std::uint32_t>(number(6, 0xFFFFFFFF));
      p.in_proto_mask = static_cast<std::uint16_t>(number(7, 0xFFFF));
      p.out_proto_mask = static_cast<std::uint16_t>(number(8, 0xFFFF));
      p.flags = static_cast<std::uint16_t>(number(9, 0xFFFF));
      p.autobauding = number(10, 1) != 0;
      if (p.exists != c.ports_[col].exists || p.port_id != c.ports_[col].port_id) fail("port " + std::to_string(col) + " is another port on this chip");
      c.ports_[col] = p;
    } else if (kind == "rate") {
      const MsgId id{static_cast<std::uint8_t>(number(1, 0xFF)), static_cast<std::uint8_t>(number(2, 0xFF))};
      for (std::size_t col = 0; col + 3 < w.size() && col < c.columns(); ++col) {
        if (!c.set_message_rate(col, id, static_cast<std::uint8_t>(number(col + 3, 0xFF)))) fail("rate table full");
      }
    } else if (kind == "cfg-rate") {
      c.rate.measRate = static_cast<std::uint16_t>(number(1, 0xFFFF));
      c.rate.navRate = static_cast<std::uint16_t>(number(2, 0xFFFF));
      c.rate.timeRef = static_cast<std::uint16_t>(number(3, 0xFFFF));
      if (c.rate.measRate < 25 || c.rate.navRate == 0) fail("cfg-rate: measRate >= 25 ms and navRate >= 1");
    } else if (kind == "nav5") {
      const std::vector<std::uint8_t> b = bytes(1, sizeof c.nav5);
      if (b.size() != sizeof c.nav5) fail("nav5: 36 bytes");
      std::memcpy(&c.nav5, b.data(), sizeof c.nav5);
    } else if (kind == "block") {
      const MsgId id{static_cast<std::uint8_t>(number(1, 0xFF)), static_cast<std::uint8_t>(number(2, 0xFF))};
      const std::uint8_t index = static_cast<std::uint8_t>(number(3, 0xFF));
      if (id.cls != cls::kCfg) fail("block: not a CFG message");
      if (!c.store(id, index, bytes(4, kMaxStoredBytes))) fail("block: too many stored blocks");
    } else if (kind == "plain") {
      const std::size_t slot = number(1, kMaxPlainValues - 1);
      c.plain_[slot] = number(2, ~std::uint64_t{0});
    } else {
      fail(std::string("unknown setting ").append(kind));
    }
  }
  if (!magic) throw Error(source, 0, "empty state file");
  *this = c;
}

}  // namespace gnssemu::protocol::ubx
