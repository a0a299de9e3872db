// SPDX-License-Identifier: Apache-2.0
// [[output]] (config/output_keys): port types and their own keys,
// protocols, message sets and rates; exact file:line errors, cross-port
// uniqueness and the to_toml round trip.
#include "config/message_names.hpp"
#include "test_helpers.hpp"

namespace gnssemu::config::test {
namespace {

const std::string kAllTypes = kBase +
                              "[[output]]\n"                          // 7
                              "name = \"fc\"\n"                       // 8
                              "type = \"serial\"\n"                   // 9
                              "device = \"/dev/ttyUSB0\"\n"           // 10
                              "baud = 38400\n"                        // 11
                              "protocols_in = [\"ubx\"]\n"            // 12
                              "protocols_out = [\"ubx\"]\n"           // 13
                              "ubx_messages = [\"NAV-SAT\", \"NAV-PVT\", \"MON-HW\"]\n"
                              "rates = { NAV-SAT = 5, MON-HW = 10 }\n"
                              "[[output]]\n"
                              "name = \"net\"\n"
                              "type = \"tcp\"\n"
                              "port = 2947\n"
                              "sentences = [\"GGA\", \"GSV\"]\n"
                              "rates = { GSV = 4 }\n"
                              "[[output]]\n"
                              "name = \"bcast\"\n"
                              "type = \"udp\"\n"
                              "address = \"127.0.0.1\"\n"
                              "port = 10110\n"
                              "[[output]]\n"
                              "name = \"log\"\n"
                              "type = \"file\"\n"
                              "path = \"out/x.ubx\"\n"
                              "protocols_out = [\"ubx\"]\n"
                              "ubx_messages = [\"NAV-PVT\"]\n";

TEST(ConfigPorts, EveryTypeParses) {
  const Config c = parse(kAllTypes);
  ASSERT_EQ(c.outputs.size(), 4u);
  const OutputPortConfig& s = c.outputs[0];
  EXPECT_EQ(s.type(), PortType::kSerial);
  EXPECT_EQ(std::get<SerialPortConfig>(s.transport).device, "/dev/ttyUSB0");
  EXPECT_EQ(s.baud, 38400u);
  EXPECT_EQ(s.protocols_in, protocol::ubx::proto::kUbx);
  EXPECT_EQ(s.protocols_out, protocol::ubx::proto::kUbx);
  // Stored in epoch order (NAV-PVT first), whatever the order in the file.
  ASSERT_EQ(s.ubx_messages.size(), 3u);
  EXPECT_EQ(s.ubx_messages[0], (MessageRate{0x01, 0x07, 1}));
  EXPECT_EQ(s.ubx_messages[1], (MessageRate{0x01, 0x35, 5}));
  EXPECT_EQ(s.ubx_messages[2], (MessageRate{0x0A, 0x09, 10}));

  const OutputPortConfig& t = c.outputs[1];
  EXPECT_EQ(t.type(), PortType::kTcp);
  EXPECT_EQ(std::get<TcpPortConfig>(t.transport).bind, "127.0.0.1");  // default bind: loopback only
  EXPECT_EQ(std::get<TcpPortConfig>(t.transport).port, 2947);
  EXPECT_EQ(t.baud, 0u);  // no line budget by default
  EXPECT_EQ(t.protocols_in, protocol::ubx::proto::kUbx | protocol::ubx::proto::kNmea);
  ASSERT_EQ(t.nmea_rates.size(), 1u);
  EXPECT_EQ(t.nmea_rates[0], (MessageRate{kNmeaClass, 0x03, 4}));
  const std::vector<MessageRate> all = message_rates(t);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0], (MessageRate{kNmeaClass, 0x00, 1}));  // GGA
  EXPECT_EQ(all[1], (MessageRate{kNmeaClass, 0x03, 4}));  // GSV every 4th epoch

  const OutputPortConfig& u = c.outputs[2];
  EXPECT_EQ(u.type(), PortType::kUdp);
  EXPECT_EQ(std::get<UdpPortConfig>(u.transport).address, "127.0.0.1");
  EXPECT_EQ(std::get<UdpPortConfig>(u.transport).port, 10110);
  EXPECT_EQ(u.protocols_in, 0);  // output only

  const OutputPortConfig& f = c.outputs[3];
  EXPECT_EQ(std::get<FilePortConfig>(f.transport).path, kData + "/out/x.ubx");
  EXPECT_EQ(f.protocols_in, 0);
  EXPECT_EQ(message_rates(f).size(), 1u + 6u);  // NAV-PVT + default sentences
}

TEST(ConfigPorts, DefaultsAreAFactoryM8) {
  const Config c = parse(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\n");
  const OutputPortConfig& p = c.outputs.at(0);
  EXPECT_EQ(p.type(), PortType::kPty);
  EXPECT_EQ(p.baud, 9600u);
  EXPECT_EQ(p.protocols_in, protocol::ubx::proto::kUbx | protocol::ubx::proto::kNmea);
  EXPECT_EQ(p.protocols_out, protocol::ubx::proto::kUbx | protocol::ubx::proto::kNmea);
  EXPECT_TRUE(p.ubx_messages.empty());
  EXPECT_TRUE(p.nmea_rates.empty());
}

// An unset baud is the chip's UART1 factory rate: 9600 on the NEO-M8N,
// 38400 on the NEO-M9N and ZED-F9P; a given one stays.
TEST(ConfigPorts, UnsetBaudIsTheGenerationsFactoryRate) {
  const std::string pty = "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\n";
  const std::string tcp = "[[output]]\nname = \"b\"\ntype = \"tcp\"\nport = 4001\n";
  EXPECT_EQ(parse(kBase + "[receiver]\ngeneration = \"m9\"\n" + pty).outputs.at(0).baud, 38400u);
  EXPECT_EQ(parse(kBase + "[receiver]\ngeneration = \"f9p\"\n" + pty).outputs.at(0).baud, 38400u);
  EXPECT_EQ(parse(kBase + "[receiver]\ngeneration = \"m8\"\n" + pty).outputs.at(0).baud, 9600u);
  EXPECT_EQ(parse(kBase + "[receiver]\ngeneration = \"m9\"\n" + pty + "baud = 9600\n").outputs.at(0).baud, 9600u);
  EXPECT_EQ(parse(kBase + "[receiver]\ngeneration = \"m9\"\n" + tcp).outputs.at(0).baud, 0u);  // no line
  const Config m9 = parse(kBase + "[receiver]\ngeneration = \"m9\"\n" + pty);
  EXPECT_EQ(parse(to_toml(m9, kData)).outputs.at(0).baud, 38400u);
}

// An unset nmea_version is the chip's factory version (the real logs: MAX-M8Q
// 4.0, NEO-M9N and ZED-F9P 4.10); a given one stays, and survives to_toml.
TEST(ConfigPorts, UnsetNmeaVersionIsTheGenerationsFactoryVersion) {
  using protocol::nmea::NmeaVersion;
  const std::string pty = "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\n";
  const auto version = [&](const std::string& gen, const std::string& extra) {
    return parse(kBase + "[receiver]\ngeneration = \"" + gen + "\"\n" + pty + extra).outputs.at(0).nmea.version;
  };
  EXPECT_EQ(version("m8", ""), NmeaVersion::k40);
  EXPECT_EQ(version("m9", ""), NmeaVersion::k410);
  EXPECT_EQ(version("f9p", ""), NmeaVersion::k410);
  EXPECT_EQ(version("m8", "nmea_version = \"4.11\"\n"), NmeaVersion::k411);
  EXPECT_EQ(version("m9", "nmea_version = \"2.3\"\n"), NmeaVersion::k23);
  const Config m9 = parse(kBase + "[receiver]\ngeneration = \"m9\"\n" + pty);
  EXPECT_EQ(parse(to_toml(m9, kData)).outputs.at(0).nmea.version, NmeaVersion::k410);
}

TEST(ConfigPorts, RoundTrip) {
  const Config c = parse(kAllTypes);
  const Config back = parse(to_toml(c, kData));
  ASSERT_EQ(back.outputs.size(), c.outputs.size());
  for (std::size_t i = 0; i < c.outputs.size(); ++i) {
    SCOPED_TRACE(i);
    const OutputPortConfig& a = c.outputs[i];
    const OutputPortConfig& b = back.outputs[i];
    EXPECT_EQ(a.type(), b.type());
    EXPECT_TRUE(a.transport == b.transport);  // path, device, address, port
    EXPECT_EQ(a.baud, b.baud);
    EXPECT_EQ(a.protocols_in, b.protocols_in);
    EXPECT_EQ(a.protocols_out, b.protocols_out);
    EXPECT_EQ(a.ubx_messages, b.ubx_messages);
    EXPECT_EQ(a.nmea_rates, b.nmea_rates);
  }
  // Written once more, the text is the same (a fixed point).
  EXPECT_EQ(to_toml(back, kData), to_toml(c, kData));
}

std::string port(const std::string& body) { return kBase + "[[output]]\nname = \"a\"\n" + body; }

TEST(ConfigPorts, MessagesMustExistOnTheGeneration) {
  // [[output]] line 7, name 8, type 9, path 10, ubx_messages from line 11; [receiver] after it.
  const auto with = [](const std::string& messages, const std::string& generation) {
    return port("type = \"file\"\npath = \"/tmp/a\"\nubx_messages = [\n" + messages + "]\n") +
           (generation.empty() ? "" : "[receiver]\ngeneration = \"" + generation + "\"\n");
  };
  EXPECT_EQ(error_of(with("\"NAV-PVT\",\n\"MON-RF\",\n", "")),
            "t.toml:13: output[0].ubx_messages: a u-blox m8 has no MON-RF ([receiver] generation = \"m8\"; "
            "docs/ubx.md \"Generations\")");
  EXPECT_EQ(error_of(with("\"SEC-SIG\",\n", "m8")),
            "t.toml:12: output[0].ubx_messages: a u-blox m8 has no SEC-SIG ([receiver] generation = \"m8\"; "
            "docs/ubx.md \"Generations\")");
  EXPECT_EQ(error_of(with("\"NAV-PVT\",\n\"NAV-SAT\",\n\"NAV-SVINFO\",\n", "m9")),
            "t.toml:14: output[0].ubx_messages: a u-blox m9 has no NAV-SVINFO ([receiver] generation = \"m9\"; "
            "docs/ubx.md \"Generations\")");
  const Config m9 = parse(with("\"NAV-PVT\",\n\"MON-HW\",\n\"MON-RF\",\n\"SEC-SIG\",\n", "m9"));
  ASSERT_EQ(m9.outputs.at(0).ubx_messages.size(), 4u);
  EXPECT_EQ(m9.outputs[0].ubx_messages[2], (MessageRate{0x0A, 0x38, 1}));
  EXPECT_EQ(m9.outputs[0].ubx_messages[3], (MessageRate{0x27, 0x09, 1}));
  EXPECT_EQ(parse(with("\"NAV-SVINFO\",\n", "m8")).outputs.at(0).ubx_messages.size(), 1u);
}

TEST(ConfigPorts, RawMessagesNeedRawDataFirmware) {
  const std::string out = port("type = \"file\"\npath = \"/tmp/a\"\nubx_messages = [\n\"NAV-PVT\",\n\"RXM-RAWX\",\n]\n");
  EXPECT_EQ(error_of(out),
            "t.toml:13: output[0].ubx_messages: a u-blox m8 has no RXM-RAWX without raw-data firmware ([receiver] "
            "raw_data = true; docs/raw-output.md)");
  const Config c = parse(out + "[receiver]\nraw_data = true\n");
  EXPECT_TRUE(c.raw_data);
  EXPECT_EQ(c.outputs.at(0).ubx_messages.at(1), (MessageRate{0x02, 0x15, 1}));
}

TEST(ConfigPorts, Errors) {
  // Line numbers: [[output]] is line 7, name line 8, body from line 9.
  EXPECT_EQ(error_of(port("type = \"serial\"\npath = \"/dev/ttyS0\"\n")),
            "t.toml:10: output[0].path: not used by a port of type \"serial\" (only \"pty\" or \"file\")");
  EXPECT_EQ(error_of(port("type = \"serial\"\ndevice = \"ttyS0\"\n")),
            "t.toml:10: output[0].device: serial device 'ttyS0' must be an absolute path (e.g. /dev/ttyUSB0)");
  EXPECT_EQ(error_of(port("type = \"serial\"\n")), "t.toml:7: missing required key 'output[0].device' in [output[0]]");
  EXPECT_EQ(error_of(port("type = \"udp\"\nport = 5\n")),
            "t.toml:7: missing required key 'output[0].address' in [output[0]]");
  EXPECT_EQ(error_of(port("type = \"udp\"\naddress = \"localhost\"\nport = 5\n")),
            "t.toml:10: output[0].address: 'localhost' is not an IPv4 or IPv6 address");
  EXPECT_EQ(error_of(port("type = \"udp\"\naddress = \"127.0.0.1\"\nport = 0\n")),
            "t.toml:11: output[0].port: 0 is out of range [1, 65535]");
  EXPECT_EQ(error_of(port("type = \"udp\"\naddress = \"127.0.0.1\"\nport = 9\nprotocols_in = [\"ubx\"]\n")),
            "t.toml:12: output[0].protocols_in: a port of type \"udp\" has no input; use []");
  EXPECT_EQ(error_of(port("type = \"tcp\"\ndevice = \"/dev/x\"\n")),
            "t.toml:10: output[0].device: not used by a port of type \"tcp\" (only \"serial\")");
  EXPECT_EQ(error_of(port("path = \"/tmp/a\"\nport = 4\n")),
            "t.toml:10: output[0].port: not used by a port of type \"pty\" (only \"tcp\" or \"udp\")");
  EXPECT_EQ(error_of(port("path = \"/tmp/a\"\nprotocols_out = [\"ubx\", \"rtcm\"]\n")),
            "t.toml:10: output[0].protocols_out: unknown protocol 'rtcm' (known: \"ubx\", \"nmea\")");
  EXPECT_EQ(error_of(port("path = \"/tmp/a\"\nprotocols_out = [\"ubx\", \"ubx\"]\n")),
            "t.toml:10: output[0].protocols_out: 'ubx' listed twice");
  EXPECT_EQ(error_of(port("path = \"/tmp/a\"\nubx_messages = [\"NAV-PVT\", \"NAV-XYZ\"]\n")),
            "t.toml:10: output[0].ubx_messages: unknown UBX message 'NAV-XYZ' (known: NAV-PVT NAV-POSLLH "
            "NAV-VELNED NAV-STATUS NAV-DOP NAV-SOL NAV-TIMEUTC NAV-SAT NAV-SVINFO MON-HW MON-RF SEC-SIG NAV-EOE "
            "NAV-SIG NAV-TIMEGLO NAV-TIMEGAL NAV-TIMEBDS MON-HW2 RXM-RAWX RXM-SFRBX NAV-HPPOSECEF NAV-HPPOSLLH "
            "NAV-RELPOSNED)");
  EXPECT_EQ(error_of(port("path = \"/tmp/a\"\nubx_messages = [\"NAV-PVT\", \"NAV-PVT\"]\n")),
            "t.toml:10: output[0].ubx_messages: 'NAV-PVT' listed twice");
  // A set whose protocol is off is kept: a host may turn the protocol on (CFG-PRT, $PUBX,41).
  EXPECT_EQ(parse(port("path = \"/tmp/a\"\nprotocols_out = [\"nmea\"]\nubx_messages = [\"NAV-PVT\"]\n"))
                .outputs.at(0).ubx_messages.size(), 1u);
  EXPECT_EQ(error_of(port("path = \"/tmp/a\"\nrates = { NAV-PVT = 2 }\n")),
            "t.toml:10: output[0].rates.NAV-PVT: 'NAV-PVT' is not in ubx_messages");
  EXPECT_EQ(error_of(port("path = \"/tmp/a\"\nrates = { GST = 2 }\n")),
            "t.toml:10: output[0].rates.GST: 'GST' is not in sentences");
  EXPECT_EQ(error_of(port("path = \"/tmp/a\"\nrates = { GSV = 0 }\n")),
            "t.toml:10: output[0].rates.GSV: 0 is out of range [1, 255] (epochs per message; leave a message "
            "out to turn it off)");
  EXPECT_EQ(error_of(port("path = \"/tmp/a\"\nrates = { GSV = 2.5 }\n")),
            "t.toml:10: output[0].rates.GSV: expected an integer, got a float");
  EXPECT_EQ(error_of(port("path = \"/tmp/a\"\nrates = { XYZ = 2 }\n")),
            "t.toml:10: output[0].rates.XYZ: unknown message 'XYZ'");
  EXPECT_EQ(error_of(port("path = \"/tmp/a\"\nrates = 2\n")),
            "t.toml:10: output[0].rates: expected a table of message = rate (e.g. { NAV-SAT = 5 }), got an integer");
  EXPECT_EQ(error_of(port("path = \"/tmp/a\"\nbaud = 0\n")),
            "t.toml:10: output[0].baud: 0 is out of range [1, 4294967295]");
  EXPECT_EQ(error_of(port("type = \"tcp\"\nbaud = 1000\n")),
            "t.toml:10: output[0].baud: 1000 is not a standard rate (4800 9600 19200 38400 57600 115200 230400 "
            "460800 921600) or 0 (no line budget)");
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\ntype = \"tcp\"\nport = 7000\n"
                             "[[output]]\nname = \"b\"\ntype = \"tcp\"\nport = 7000\n"),
            "t.toml:14: output[1].port: tcp port 7000 is already used by output 'a'");
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\ntype = \"serial\"\ndevice = \"/dev/ttyS0\"\n"
                             "[[output]]\nname = \"b\"\ntype = \"serial\"\ndevice = \"/dev/ttyS0\"\n"),
            "t.toml:14: output[1].device: '/dev/ttyS0' is already used by output 'a'");
}

TEST(ConfigPorts, TwoTcpPortsOnAnyPortAreFine) {
  const Config c = parse(kBase + "[[output]]\nname = \"a\"\ntype = \"tcp\"\n[[output]]\nname = \"b\"\ntype = \"tcp\"\n");
  EXPECT_EQ(std::get<TcpPortConfig>(c.outputs.at(0).transport).port, 0);
  EXPECT_EQ(std::get<TcpPortConfig>(c.outputs.at(1).transport).port, 0);
}

TEST(ConfigValidation, SentencesNotAnArray) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nsentences = \"GGA\"\n"),
            "t.toml:10: output[0].sentences: expected an array of strings, got a string");
}

TEST(ConfigValidation, BaudNotStandard) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nbaud = 9601\n"),
            "t.toml:10: output[0].baud: 9601 is not a standard rate "
            "(4800 9600 19200 38400 57600 115200 230400 460800 921600)");
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nbaud = 0\n"),
            "t.toml:10: output[0].baud: 0 is out of range [1, 4294967295]");
  EXPECT_EQ(parse(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nbaud = 115200\n").outputs.at(0).baud, 115200u);
}

TEST(ConfigValidation, UnknownSentence) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nsentences = [\"GGA\",\n  \"GGX\"]\n"),
            "t.toml:11: output[0].sentences: unknown sentence 'GGX' (known: GGA RMC GSA GSV VTG GLL GST ZDA GNS GBS)");
}

TEST(ConfigValidation, SentenceListedTwiceOrEmpty) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nsentences = [\"GGA\", \"GGA\"]\n"),
            "t.toml:10: output[0].sentences: 'GGA' listed twice");
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nsentences = []\n"),
            "t.toml:10: output[0].sentences: must name at least one sentence");
}

TEST(ConfigValidation, UnknownNmeaVersion) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"/tmp/a\"\nnmea_version = \"4.2\"\n"),
            "t.toml:10: output[0].nmea_version: '4.2' is not one of \"2.1\", \"2.3\", \"4.0\", \"4.10\", \"4.11\"");
}

TEST(ConfigValidation, UnknownPortType) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\ntype = \"usb\"\npath = \"/tmp/a\"\n"),
            "t.toml:9: output[0].type: 'usb' is not one of \"pty\", \"serial\", \"tcp\", \"udp\", \"file\"");
}

TEST(ConfigValidation, DuplicateOutputName) {
  const std::string text = kBase +
                           "[[output]]\nname = \"gps0\"\npath = \"/tmp/gnssemu/a\"\n"  // 7-9
                           "[[output]]\nname = \"gps0\"\npath = \"/tmp/gnssemu/b\"\n";  // 10-12
  EXPECT_EQ(error_of(text), "t.toml:11: output[1].name: 'gps0' is used twice");
}

TEST(ConfigValidation, DuplicateOutputPath) {
  const std::string text = kBase +
                           "[[output]]\nname = \"a\"\npath = \"/tmp/gnssemu/gps0\"\n"  // 7-9
                           "[[output]]\nname = \"b\"\npath = \"/tmp/gnssemu/gps0\"\n";  // 10-12
  EXPECT_EQ(error_of(text), "t.toml:12: output[1].path: '/tmp/gnssemu/gps0' is already used by output 'a'");
}

TEST(ConfigValidation, DuplicateFilePathAfterResolution) {
  const std::string text = kBase +
                           "[[output]]\nname = \"a\"\ntype = \"file\"\npath = \"out/x.nmea\"\n"         // 7-10
                           "[[output]]\nname = \"b\"\ntype = \"file\"\npath = \"out/../out/x.nmea\"\n";  // 11-14
  EXPECT_EQ(error_of(text),
            "t.toml:14: output[1].path: '" + kData + "/out/x.nmea' is already used by output 'a'");
}

TEST(ConfigValidation, RelativePtyPathRejected) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"a\"\npath = \"gps0\"\n"),
            "t.toml:9: output[0].path: pty path 'gps0' must be absolute");
}

TEST(ConfigValidation, OutputNameChecks) {
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"\"\npath = \"/tmp/a\"\n"),
            "t.toml:8: output[0].name: must not be empty");
  EXPECT_EQ(error_of(kBase + "[[output]]\nname = \"gps 0\"\npath = \"/tmp/a\"\n"),
            "t.toml:8: output[0].name: 'gps 0' contains a space or control character");
}

}  // namespace
}  // namespace gnssemu::config::test
