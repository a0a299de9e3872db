// SPDX-License-Identifier: Apache-2.0
// [base]: the RTCM reference station (docs/base-station.md). Its position,
// station id, messages, [base.ntrip] caster endpoint and [[base.output]] ports; any key of [receiver] on it overrides the top level's for the base
// alone (its own seed, profile, errors), as on a [[vehicle.receiver]].
#include "config/setup/base_station.hpp"
#include "config/keys/config_keys.hpp"

namespace gnssemu::config::detail {

namespace {

void read_messages(TableReader& t, const Field<BaseConfig>& f, BaseConfig& b) {
  const toml::node* n = t.find(f.key);
  if (n == nullptr) t.fail_missing(f.key, "string");
  const auto* s = n->as_string();
  if (s == nullptr) t.fail(*n, t.full_name(f.key) + ": expected a string like \"1005(10),1077,1230(5)\"");
  b.messages = parse_base_messages(s->get(), t.file(), line_of(*n));
}
void write_messages(TomlWriter& w, const Field<BaseConfig>& f, const BaseConfig& b) {
  std::string s;
  for (const BaseMessage& m : b.messages) {
    if (!s.empty()) s += ',';
    s += std::to_string(m.number) + "(" + number_text(m.interval_s) + ")";
  }
  w.key(f.key, string_text(s), f.note);
}

template <std::string NtripCasterConfig::*M>
void read_text(TableReader& t, const Field<NtripCasterConfig>& f, NtripCasterConfig& c) {
  c.*M = t.string(f.key, c.*M);
  for (unsigned char ch : c.*M) {
    if (ch <= 0x20 || ch == 0x7f || ch == ':' || ch == '/' || ch == '@') {
      t.fail(*t.find(f.key), t.full_name(f.key) + ": printable characters without space, ':', '/' or '@'");
    }
  }
}
template <std::string NtripCasterConfig::*M>
void write_text(TomlWriter& w, const Field<NtripCasterConfig>& f, const NtripCasterConfig& c) {
  w.key(f.key, string_text(c.*M));
}

constexpr Field<NtripCasterConfig> kNtripFields[] = {
    integer<&NtripCasterConfig::port>("port", 0, 65535, "TCP port on 127.0.0.1; 0 picks a free port (logged)"),
    custom<NtripCasterConfig>("mountpoint", "", "printable, no space `:` `/` `@`", "the caster's one mountpoint",
                              read_text<&NtripCasterConfig::mountpoint>, write_text<&NtripCasterConfig::mountpoint>)
        .default_doc("`\"GNSSEMU\"`"),
    custom<NtripCasterConfig>("user", "", "printable, no space `:` `/` `@`",
                              "HTTP Basic user a client must give; `\"\"`: no credentials asked",
                              read_text<&NtripCasterConfig::user>, write_text<&NtripCasterConfig::user>)
        .default_doc("`\"\"`"),
    custom<NtripCasterConfig>("password", "", "printable, no space `:` `/` `@`", "its password",
                              read_text<&NtripCasterConfig::password>, write_text<&NtripCasterConfig::password>)
        .default_doc("`\"\"`"),
};
constexpr Section<NtripCasterConfig> kNtrip{kNtripFields};

constexpr Field<BaseConfig> kBaseFields[] = {
    angle<&BaseConfig::position, &Lla::lat_rad>("lat_deg", Range{-90.0, 90.0, "deg"}, "base antenna latitude, WGS-84")
        .needed(),
    angle<&BaseConfig::position, &Lla::lon_rad>("lon_deg", Range{-180.0, 180.0, "deg"}, "base antenna longitude")
        .needed(),
    number<&BaseConfig::position, &Lla::height_m>("height_m", Range{-1000.0, 50000.0, "m"},
                                                  "antenna reference point above the WGS-84 ellipsoid")
        .needed(),
    integer<&BaseConfig::station_id>("station_id", 0, 4095, "RTCM reference station id (DF003)"),
    number<&BaseConfig::antenna_height_m>("antenna_height_m", Range{0.0, 6.5535, "m"},
                                          "antenna height above the marker, sent in 1006"),
    boolean<&BaseConfig::open_sky>("open_sky",
                                   "`true`: the base sees none of [scene]'s buildings (an antenna on a mast, a "
                                   "surveyed open site); `false`: it stands in the world's scene at its position"),
    custom<BaseConfig>("messages", "", "str2str `-msg` syntax",
                       "messages and intervals in s (default 1): `1005`/`1006`, `1230`, MSM4 or MSM7 of GPS, GLONASS, "
                       "Galileo, QZSS, BeiDou (`1074`/`1077` ... `1124`/`1127`: one type, one interval), ephemerides "
                       "`1019`, `1020`, `1042`, `1046`; another number is an error naming this line",
                       read_messages, write_messages)
        .needed(),
};
constexpr Section<BaseConfig> kBase{kBaseFields};

constexpr std::string_view kBaseTakes =
    "[base] takes lat_deg, lon_deg, height_m, station_id, antenna_height_m, open_sky, messages, [base.ntrip], "
    "[[base.output]] and the keys of [receiver]";

}  // namespace

void read_base(TableReader& t, const Field<Config>& f, Config& c) {
  std::optional<TableReader> bt = t.table(f.key, false);
  if (!bt) return;
  BaseConfig b;
  b.line = bt->line();
  for (const Field<BaseConfig>& row : kBase.fields) row.read(*bt, row, b);
  b.settings = receiver_overrides(*bt, c);
  if (std::optional<TableReader> n = bt->table("ntrip", false)) {
    b.ntrip.enabled = true;
    read_section(*n, kNtrip, b.ntrip);
  }
  for (TableReader& o : bt->table_array("output")) {
    OutputPortConfig port;
    read_section(o, kBaseOutputKeys, port);
    port.protocols_in = 0;  // the base's stream only leaves
    std::vector<OutputPortConfig> before = c.outputs;
    before.insert(before.end(), b.outputs.begin(), b.outputs.end());
    check_unique_port(o, before, port);
    b.outputs.push_back(std::move(port));
  }
  bt->finish(kBaseTakes);
  c.base = std::move(b);
}

void write_base(TomlWriter& w, const Field<Config>& f, const Config& c) {
  if (!c.base) return;
  const std::string outer = w.table();
  const std::string base = sub_table(w, f.key);
  w.set_table(base);
  w.header({});
  write_rows(w, kBase, *c.base);
  Config own = with_receiver_settings(Config{}, c.base->settings);
  write_rows(w, kReceiverKeys, own);
  if (c.base->ntrip.enabled) write_table(w, kNtrip, base + ".ntrip", {}, c.base->ntrip);
  for (const OutputPortConfig& o : c.base->outputs) write_table(w, kBaseOutputKeys, base + ".output", {}, o, true);
  w.set_table(outer);
}

void describe_base(KeyDocs& d, const Field<Config>& f, const Config&) {
  d.enter(f.key);
  describe_section(d, kBase, BaseConfig{});
  KeyDoc any{"<receiver key>", "", "the top level's", "as in `[receiver]`",
             "any key or sub-table of `[receiver]` (`profile`, `seed`, `constellations`, `[base.errors]` ...) "
             "overrides the top level's value for the base alone"};
  any.mirror = "receiver";
  d.add(std::move(any));
  d.enter("ntrip");
  describe_section(d, kNtrip, NtripCasterConfig{});
  d.leave();
  d.enter("output");  // name, type and baud of [[output]]
  describe_section(d, kBaseOutputKeys, OutputPortConfig{});
  d.leave();
  d.leave();
}

}  // namespace gnssemu::config::detail
