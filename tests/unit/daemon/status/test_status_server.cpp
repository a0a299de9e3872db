// SPDX-License-Identifier: Apache-2.0
// StatusServer against hostile and slow clients on loopback: the server
// runs on its own io_context thread, as on the daemon's; clients are plain
// blocking sockets.
#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange
#include <vector>

#include <boost/asio.hpp>
#include <nlohmann/json.hpp>

#include "core/common/constants.hpp"
#include "core/geo/geodesy.hpp"
#include "daemon/status/status_server.hpp"
#include "tests/unit/daemon/io_thread_test.hpp"

namespace gnssemu::daemon {
namespace {

namespace asio = boost::asio;
using tcp = asio::ip::tcp;

class ServerFixture : public test::IoThreadTest {
protected:
  void SetUp() override {
    receiver::Fix f;
    f.t = time::GpsTime(2190, 1000.0);
    f.type = receiver::FixType::k3D;
    f.num_sats = 1;
    f.sats[0].sat = SatId::gps(7);
    f.sats[0].above_mask = f.sats[0].tracked = f.sats[0].used = true;
    f.sats[0].cn0_dbhz = 44.0;
    f.sats[0].el_rad = 0.5;
    fix_ = f;
    truth_.valid = false;
    producer_.on_epoch(EpochStatus{&fix_, &truth_, 0.0, 1.0, 1.0});
    server_ = std::make_unique<StatusServer>(io_, producer_);
    server_->start("127.0.0.1", 0);
    port_ = server_->local_endpoint().port();
    start_io();
  }
  void TearDown() override {
    on_io([this] { server_->stop(); });
    stop_io();
  }
  tcp::socket connect() {
    tcp::socket s(client_io_);
    s.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port_));
    return s;
  }
  /// Send raw bytes and read until the server closes or timeout_s passes.
  std::string exchange(const std::string& request, double timeout_s = 5.0) {
    tcp::socket s = connect();
    boost::system::error_code ec;
    asio::write(s, asio::buffer(request), ec);
    return read_until_close(s, timeout_s);
  }
  static std::string read_until_close(tcp::socket& s, double timeout_s) {
    std::string got;
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    s.non_blocking(true);
    char buf[65536];
    while (std::chrono::steady_clock::now() < end) {
      boost::system::error_code ec;
      const std::size_t n = s.read_some(asio::buffer(buf), ec);
      if (ec == asio::error::would_block) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        continue;
      }
      if (ec) break;
      got.append(buf, n);
    }
    return got;
  }
  static std::string body_of(const std::string& response) {
    const std::size_t p = response.find("\r\n\r\n");
    return p == std::string::npos ? std::string() : response.substr(p + 4);
  }

  asio::io_context client_io_;
  receiver::Fix fix_;
  world::Truth truth_;
  StatusProducer producer_{StatusSettings{}};
  std::unique_ptr<StatusServer> server_;
  uint16_t port_ = 0;
};

TEST_F(ServerFixture, ServesStatusJsonThePageAndChartJs) {
  const std::string r = exchange("GET /api/status?history=0 HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  ASSERT_EQ(r.rfind("HTTP/1.1 200", 0), 0u) << r;
  EXPECT_NE(r.find("application/json"), std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(body_of(r));
  EXPECT_EQ(j["satellites"][0]["prn"], 7);
  EXPECT_EQ(j["satellites"][0]["sat"], "G07");
  EXPECT_TRUE(j["history"]["t_s"].empty());
  const std::string page = exchange("GET / HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  EXPECT_NE(page.find("text/html"), std::string::npos);
  EXPECT_NE(page.find("status.js"), std::string::npos);
  const std::string chart = exchange("GET /chart.min.js HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  EXPECT_NE(chart.find("Chart.js v3"), std::string::npos);
}

TEST_F(ServerFixture, KeepAliveServesSeveralRequestsOnOneConnection) {
  const std::string r = exchange(
      "GET /api/status?history=1 HTTP/1.1\r\nHost: x\r\n\r\nGET /status.css HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  std::size_t n = 0;
  for (std::size_t p = r.find("HTTP/1.1 200"); p != std::string::npos; p = r.find("HTTP/1.1 200", p + 1)) ++n;
  EXPECT_EQ(n, 2u);
}

TEST_F(ServerFixture, BadRequestsGetAnErrorAndTheServerGoesOn) {
  EXPECT_EQ(exchange("GET /nope HTTP/1.1\r\nHost: x\r\n\r\n").rfind("HTTP/1.1 404", 0), 0u);
  EXPECT_EQ(exchange("POST /api/status HTTP/1.1\r\nHost: x\r\nContent-Length: 0\r\n\r\n").rfind("HTTP/1.1 405", 0), 0u);
  EXPECT_EQ(exchange("\x16\x03\x01\x02\x00junk\r\n\r\n").rfind("HTTP/1.1 400", 0), 0u);
  EXPECT_EQ(exchange("GET / HTTP/1.1\r\nX: " + std::string(100000, 'a') + "\r\n\r\n").rfind("HTTP/1.1 431", 0), 0u);
  EXPECT_EQ(exchange("GET /api/status HTTP/1.1\r\nContent-Length: 5\r\n\r\nhello").rfind("HTTP/1.1 400", 0), 0u);
  // Random bytes of every value, in several sizes.
  std::mt19937 rng(7);
  for (int size : {1, 17, 300, 5000}) {
    std::string junk(static_cast<std::size_t>(size), '\0');
    for (char& c : junk) c = static_cast<char>(rng() & 0xff);
    junk += "\r\n\r\n";
    (void)exchange(junk, 2.0);
  }
  const std::string ok = exchange("GET /api/status HTTP/1.1\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(ok.rfind("HTTP/1.1 200", 0), 0u);
  const StatusServerStats st = on_io([this] { return server_->stats(); });
  EXPECT_GE(st.bad_requests, 4u);
}

TEST_F(ServerFixture, OverviewListsTheRosterAndRefusesABadQuery) {
  const std::string get = "GET /api/overview HTTP/1.1\r\nConnection: close\r\n\r\n";
  EXPECT_EQ(exchange(get).rfind("HTTP/1.1 404", 0), 0u) << "no roster: no overview";
  on_io([this] {
    server_->set_roster([this](std::vector<OverviewEntry>& out) {
      out.clear();
      out.push_back({"v0", "gps1", &producer_});
      out.push_back({"v1", "gps1", &producer_});
      out.push_back({"v1", "gps2", &producer_});
    });
  });
  const std::string r = exchange(get);
  ASSERT_EQ(r.rfind("HTTP/1.1 200", 0), 0u) << r;
  EXPECT_NE(r.find("application/json"), std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(body_of(r));
  EXPECT_EQ(j["total"], 3);
  ASSERT_EQ(j["rows"].size(), 3u);
  EXPECT_EQ(j["rows"][2]["vehicle"], "v1");
  EXPECT_EQ(j["rows"][2]["receiver"], "gps2");
  EXPECT_EQ(j["rows"][2]["fix_type"], 3);
  const nlohmann::json two = nlohmann::json::parse(
      body_of(exchange("GET /api/overview?limit=2&offset=1 HTTP/1.1\r\nConnection: close\r\n\r\n")));
  ASSERT_EQ(two["rows"].size(), 2u);
  EXPECT_EQ(two["rows"][0]["vehicle"], "v1");
  const std::string bad = exchange("GET /api/overview?limit=0 HTTP/1.1\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(bad.rfind("HTTP/1.1 400", 0), 0u) << bad;
  EXPECT_NE(bad.find("limit must be a whole number in [1, 1000]"), std::string::npos) << bad;
  const std::string unknown = exchange("GET /api/overview?vehicle=v1 HTTP/1.1\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(unknown.rfind("HTTP/1.1 400", 0), 0u) << unknown;
  EXPECT_NE(unknown.find("unknown query parameter 'vehicle'"), std::string::npos) << unknown;
  // The whole roster sorted before paging (name, descending): v1/gps2 first.
  const nlohmann::json sorted = nlohmann::json::parse(
      body_of(exchange("GET /api/overview?sort=name&order=desc&limit=1 HTTP/1.1\r\nConnection: close\r\n\r\n")));
  ASSERT_EQ(sorted["rows"].size(), 1u);
  EXPECT_EQ(sorted["rows"][0]["vehicle"], "v1");
  EXPECT_EQ(sorted["rows"][0]["receiver"], "gps2");
}

TEST_F(ServerFixture, ConnectionsBeyondTheLimitAreRefusedOthersServed) {
  std::vector<tcp::socket> idle;
  for (std::size_t i = 0; i < kMaxSessions + 10; ++i) idle.push_back(connect());
  EXPECT_TRUE(eventually_on_io([this] { return server_->stats().sessions_refused >= 10u; }));
  const StatusServerStats st = on_io([this] { return server_->stats(); });
  EXPECT_EQ(st.sessions, kMaxSessions);
  EXPECT_GE(st.sessions_refused, 10u);
  idle.clear();  // they go away; the server serves again
  EXPECT_TRUE(eventually_on_io([this] { return server_->stats().sessions == 0u; }));
  EXPECT_EQ(exchange("GET /api/status HTTP/1.1\r\nConnection: close\r\n\r\n").rfind("HTTP/1.1 200", 0), 0u);
}

TEST_F(ServerFixture, EventStreamDeliversOneEventPerPublish) {
  tcp::socket s = connect();
  asio::write(s, asio::buffer(std::string("GET /api/events HTTP/1.1\r\nHost: x\r\n\r\n")));
  ASSERT_TRUE(eventually_on_io([this] { return server_->stats().streams == 1u; }));
  for (int k = 0; k < 3; ++k) on_io([this] { server_->publish(); });
  std::string got;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  s.non_blocking(true);
  std::size_t events = 0;
  while (events < 3 && std::chrono::steady_clock::now() < end) {
    char buf[65536];
    boost::system::error_code ec;
    const std::size_t n = s.read_some(asio::buffer(buf), ec);
    if (ec == asio::error::would_block) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      continue;
    }
    ASSERT_FALSE(ec) << ec.message();
    got.append(buf, n);
    events = 0;
    for (std::size_t p = got.find("data: "); p != std::string::npos; p = got.find("data: ", p + 1)) ++events;
  }
  EXPECT_EQ(got.rfind("HTTP/1.1 200", 0), 0u);
  EXPECT_NE(got.find("text/event-stream"), std::string::npos);
  ASSERT_EQ(events, 3u);
  const std::size_t a = got.find("data: ") + 6;
  const nlohmann::json j = nlohmann::json::parse(got.substr(a, got.find("\n\n", a) - a));
  EXPECT_EQ(j["history"]["t_s"].size(), 1u);
}

TEST_F(ServerFixture, AStreamThatIsNotReadIsDroppedAndPublishNeverWaits) {
  tcp::socket s(client_io_);
  s.open(tcp::v4());
  s.set_option(asio::socket_base::receive_buffer_size(4096));
  s.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port_));
  asio::write(s, asio::buffer(std::string("GET /api/events HTTP/1.1\r\nHost: x\r\n\r\n")));
  ASSERT_TRUE(eventually_on_io([this] { return server_->stats().streams == 1u; }));
  // Never read: kernel buffers fill, then the server's bounded backlog.
  for (int k = 0; k < 3000; ++k) {
    const bool dropped = on_io([this] {
      server_->publish();
      return server_->stats().streams_dropped > 0;
    });
    if (dropped) break;
  }
  const StatusServerStats st = on_io([this] { return server_->stats(); });
  EXPECT_EQ(st.streams_dropped, 1u);
  EXPECT_EQ(st.streams, 0u);
}

}  // namespace
}  // namespace gnssemu::daemon
