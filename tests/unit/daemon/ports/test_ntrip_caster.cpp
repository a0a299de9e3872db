// SPDX-License-Identifier: Apache-2.0
// The NTRIP caster's answers (rtk-raw.md §3): v1 ICY / SOURCETABLE / 401,
// v2 HTTP/1.1 with chunks / gnss/sourcetable / 404 / 401.
#include <gtest/gtest.h>

#include "daemon/ports/ntrip_caster.hpp"

namespace gnssemu::daemon {
namespace {

config::NtripCasterConfig caster() {
  config::NtripCasterConfig c;
  c.enabled = true;
  c.mountpoint = "BASE";
  c.user = "user";
  c.password = "pass";
  return c;
}

constexpr std::string_view kStr = "STR;BASE;gnssemu;RTCM 3.3;1005(10),1077(1);2;GPS;gnssemu;FRA;48.88;2.30;0;0;gnssemu;none;B;N;0;";

std::string auth(std::string_view up) { return "Authorization: Basic " + base64(up) + "\r\n"; }

TEST(NtripCaster, Base64OfCredentials) {
  EXPECT_EQ(base64("user:pass"), "dXNlcjpwYXNz");
  EXPECT_EQ(base64("a"), "YQ==");
  EXPECT_EQ(base64("ab"), "YWI=");
}

TEST(NtripCaster, Version1) {
  const auto ok = NtripCaster::answer("GET /BASE HTTP/1.0\r\nUser-Agent: NTRIP RTKLIB\r\n" + auth("user:pass"), caster(), kStr);
  EXPECT_EQ(ok.text, "ICY 200 OK\r\n");
  EXPECT_TRUE(ok.data);
  EXPECT_FALSE(ok.chunked);
  const auto table = NtripCaster::answer("GET / HTTP/1.0\r\nUser-Agent: NTRIP x\r\n", caster(), kStr);
  EXPECT_EQ(table.text.rfind("SOURCETABLE 200 OK\r\n", 0), 0u);
  EXPECT_NE(table.text.find(std::string(kStr) + "\r\nENDSOURCETABLE\r\n"), std::string::npos);
  EXPECT_FALSE(table.data);
  const auto wrong_mount = NtripCaster::answer("GET /NOPE HTTP/1.0\r\n" + auth("user:pass"), caster(), kStr);
  EXPECT_EQ(wrong_mount.text.rfind("SOURCETABLE 200 OK", 0), 0u);
  const auto wrong_pass = NtripCaster::answer("GET /BASE HTTP/1.0\r\n" + auth("user:nope"), caster(), kStr);
  EXPECT_EQ(wrong_pass.text.rfind("HTTP/1.0 401 Unauthorized\r\n", 0), 0u);
  EXPECT_FALSE(wrong_pass.data);
}

TEST(NtripCaster, Version2) {
  const std::string v2 = "Host: 127.0.0.1\r\nNtrip-Version: Ntrip/2.0\r\nUser-Agent: NTRIP gpsd\r\n";
  const auto ok = NtripCaster::answer("GET /BASE HTTP/1.1\r\n" + v2 + auth("user:pass"), caster(), kStr);
  EXPECT_EQ(ok.text.rfind("HTTP/1.1 200 OK\r\n", 0), 0u);
  EXPECT_NE(ok.text.find("Transfer-Encoding: chunked"), std::string::npos);
  EXPECT_TRUE(ok.chunked);
  const auto table = NtripCaster::answer("GET / HTTP/1.1\r\n" + v2, caster(), kStr);
  EXPECT_NE(table.text.find("Content-Type: gnss/sourcetable"), std::string::npos);
  EXPECT_EQ(NtripCaster::answer("GET /NOPE HTTP/1.1\r\n" + v2, caster(), kStr).text.rfind("HTTP/1.1 404", 0), 0u);
  EXPECT_EQ(NtripCaster::answer("GET /BASE HTTP/1.1\r\n" + v2, caster(), kStr).text.rfind("HTTP/1.1 401", 0), 0u);
  EXPECT_EQ(NtripCaster::answer("POST /BASE HTTP/1.1\r\n" + v2, caster(), kStr).text.rfind("HTTP/1.1 400", 0), 0u);
}

TEST(NtripCaster, NoCredentialsConfiguredAcceptsAnyone) {
  config::NtripCasterConfig c = caster();
  c.user.clear();
  EXPECT_TRUE(NtripCaster::answer("GET /BASE HTTP/1.0\r\n", c, kStr).data);
}

}  // namespace
}  // namespace gnssemu::daemon
