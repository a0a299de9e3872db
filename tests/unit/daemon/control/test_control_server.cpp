// SPDX-License-Identifier: Apache-2.0
// ControlServer on a real Unix socket: file mode, stale and foreign files,
// line framing, oversize lines, the session cap, removal at stop. The server
// runs on its own io_context thread, as on the daemon's; clients are plain
// blocking sockets.
#include <gtest/gtest.h>

#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <future>
#include <optional>
#include <string>
#include <thread>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp needs std::exchange
#include <vector>

#include <boost/asio.hpp>

#include "core/common/error.hpp"
#include "daemon/control/control_server.hpp"
#include "tests/unit/daemon/io_thread_test.hpp"

namespace gnssemu::daemon {
namespace {

namespace asio = boost::asio;
namespace fs = std::filesystem;

int connect_to(const std::string& path) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  path.copy(a.sun_path, sizeof a.sun_path - 1);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  timeval tv{5, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  return fd;
}

void send_all(int fd, const std::string& s) {
  std::size_t sent = 0;
  while (sent < s.size()) {
    const ssize_t n = ::send(fd, s.data() + sent, s.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return;
    sent += static_cast<std::size_t>(n);
  }
}

// One line (without the newline); "" on close or timeout.
std::string read_line(int fd) {
  std::string out;
  char c = 0;
  while (::recv(fd, &c, 1, 0) == 1) {
    if (c == '\n') return out;
    out += c;
  }
  return "";
}

class ControlServerTest : public test::IoThreadTest {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("gnssemu-ctl-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    path_ = (dir_ / "c.sock").string();
    start_io();
  }
  void TearDown() override {
    if (server_) on_io([this] { server_->stop(); return 0; });
    stop_io();
    server_.reset();
    fs::remove_all(dir_);
  }
  /// Start a server that echoes "reply:<request>"; "" or the error text.
  std::string start() {
    return on_io([this]() -> std::string {
      server_ = std::make_unique<ControlServer>(io_, [this](std::string_view req) {
        ++requests_;
        return "reply:" + std::string(req);
      });
      try {
        server_->start(path_);
      } catch (const Error& e) {
        return e.what();
      }
      return "";
    });
  }

  std::unique_ptr<ControlServer> server_;
  fs::path dir_;
  std::string path_;
  int requests_ = 0;
};

TEST_F(ControlServerTest, SocketIsOwnerOnlyAndAnswersEachLine) {
  ASSERT_EQ(start(), "");
  struct stat st {};
  ASSERT_EQ(::stat(path_.c_str(), &st), 0);
  EXPECT_TRUE(S_ISSOCK(st.st_mode));
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  const int fd = connect_to(path_);
  ASSERT_GE(fd, 0);
  send_all(fd, "one\r\ntwo\n\n");  // CRLF stripped, empty lines skipped
  EXPECT_EQ(read_line(fd), "reply:one");
  EXPECT_EQ(read_line(fd), "reply:two");
  send_all(fd, "thr");
  send_all(fd, "ee\n");  // a request split over writes
  EXPECT_EQ(read_line(fd), "reply:three");
  ::close(fd);
}

TEST_F(ControlServerTest, StopRemovesTheSocketFile) {
  ASSERT_EQ(start(), "");
  EXPECT_TRUE(fs::exists(fs::symlink_status(path_)));
  on_io([this] { server_->stop(); return 0; });
  EXPECT_FALSE(fs::exists(fs::symlink_status(path_)));
  EXPECT_LT(connect_to(path_), 0);
}

TEST_F(ControlServerTest, StaleSocketIsReplacedLiveOneAndPlainFileAreNot) {
  {  // a socket file nobody listens on (a daemon killed with SIGKILL)
    const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    path_.copy(a.sun_path, sizeof a.sun_path - 1);
    ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a), 0);
    ::close(fd);
  }
  ASSERT_EQ(start(), "");
  // A second server on the same path: the first is alive.
  const std::string second = on_io([this]() -> std::string {
    ControlServer other(io_, [](std::string_view) { return std::string(); });
    try {
      other.start(path_);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  });
  EXPECT_NE(second.find("another process is listening"), std::string::npos) << second;
  EXPECT_TRUE(fs::exists(fs::symlink_status(path_)));  // the live one's file stays

  const std::string file = (dir_ / "plain").string();
  std::ofstream(file) << "keep me";
  const std::string plain = on_io([&]() -> std::string {
    ControlServer other(io_, [](std::string_view) { return std::string(); });
    try {
      other.start(file);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  });
  EXPECT_NE(plain.find("not a socket"), std::string::npos) << plain;
  EXPECT_TRUE(fs::is_regular_file(file));

  const std::string nofolder = on_io([&]() -> std::string {
    ControlServer other(io_, [](std::string_view) { return std::string(); });
    try {
      other.start((dir_ / "missing" / "c.sock").string());
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  });
  EXPECT_NE(nofolder.find("does not exist"), std::string::npos) << nofolder;
}

TEST_F(ControlServerTest, OversizeLineGetsAnErrorAndTheConnectionCloses) {
  ASSERT_EQ(start(), "");
  const int fd = connect_to(path_);
  ASSERT_GE(fd, 0);
  std::thread writer([fd] { send_all(fd, std::string(kMaxControlLineBytes + 10, 'x')); });
  const std::string r = read_line(fd);
  writer.join();
  EXPECT_NE(r.find("longer than"), std::string::npos) << r.substr(0, 100);
  EXPECT_EQ(requests_, 0);
  ::close(fd);
  // The server still serves others.
  const int fd2 = connect_to(path_);
  send_all(fd2, "ok\n");
  EXPECT_EQ(read_line(fd2), "reply:ok");
  ::close(fd2);
}

TEST_F(ControlServerTest, ClientsBeyondTheCapAreToldWhy) {
  ASSERT_EQ(start(), "");
  std::vector<int> fds;
  for (std::size_t i = 0; i < kMaxControlSessions; ++i) {
    fds.push_back(connect_to(path_));
    send_all(fds.back(), "hi\n");
    ASSERT_EQ(read_line(fds.back()), "reply:hi");  // accepted and served
  }
  const int extra = connect_to(path_);
  ASSERT_GE(extra, 0);
  EXPECT_NE(read_line(extra).find("too many control connections"), std::string::npos);
  ::close(extra);
  ::close(fds.front());
  fds.erase(fds.begin());
  // A slot freed: a new client is served (the server notices the close first).
  bool served = false;
  for (int attempt = 0; attempt < 50 && !served; ++attempt) {
    const int fd = connect_to(path_);
    send_all(fd, "again\n");
    served = read_line(fd) == "reply:again";
    ::close(fd);
    if (!served) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_TRUE(served);
  for (const int fd : fds) ::close(fd);
}

}  // namespace
}  // namespace gnssemu::daemon
