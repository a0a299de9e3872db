// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <string>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/common/error.hpp"
#include "daemon/ports/output_port.hpp"

using namespace gnssemu;
using namespace gnssemu::daemon;
namespace fs = std::filesystem;

namespace {

boost::asio::io_context io;

struct TempDir {
  fs::path path;
  TempDir() {
    char tmpl[] = "/tmp/gnssemu-test-XXXXXX";
    path = ::mkdtemp(tmpl);
  }
  ~TempDir() { fs::remove_all(path); }
};

config::OutputPortConfig pty_config(const fs::path& p) {
  config::OutputPortConfig c;
  c.name = "gps0";
  c.transport = config::PtyPortConfig{p.string()};
  return c;
}

// Everything a reader on fd gets until the line stays quiet for quiet_ms: the
// kernel hands pty data to the reader's queue asynchronously (a flip-buffer
// work item), so one non-blocking pass right after a write can come up short.
std::string read_pty_until_quiet(int fd, int quiet_ms = 200) {
  std::string got;
  char buf[4096];
  pollfd p{fd, POLLIN, 0};
  while (::poll(&p, 1, quiet_ms) > 0 && (p.revents & POLLIN) != 0) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) break;
    got.append(buf, static_cast<std::size_t>(n));
  }
  return got;
}

// Run io until done() holds or limit_ms passes (the port's reactions to a
// line event are asynchronous; a loaded machine can take far longer than usual).
template <class Done>
bool run_io_until(Done done, int limit_ms = 3000) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(limit_ms);
  while (!done() && std::chrono::steady_clock::now() < end) {
    io.restart();
    io.run_for(std::chrono::milliseconds(10));
  }
  return done();
}

}  // namespace

TEST(OutputPort, RefusesToReplaceRegularFile) {
  TempDir dir;
  const fs::path p = dir.path / "gps0";
  std::ofstream(p) << "precious";
  EXPECT_THROW(validate_port(pty_config(p)), Error);
  EXPECT_THROW(open_port(pty_config(p), io), Error);
  std::ifstream in(p);
  std::string s;
  in >> s;
  EXPECT_EQ(s, "precious");
  config::OutputPortConfig empty = pty_config(p);
  std::get<config::PtyPortConfig>(empty.transport).path.clear();
  EXPECT_THROW(validate_port(empty), Error);
}

TEST(OutputPort, PtySymlinkReplacesStaleLinkAndIsRemoved) {
  TempDir dir;
  const fs::path p = dir.path / "sub" / "gps0";
  fs::create_directories(p.parent_path());
  fs::create_symlink("/dev/pts/does-not-exist", p);
  {
    auto port = open_port(pty_config(p), io);
    ASSERT_TRUE(fs::is_symlink(p));
    const std::string target = fs::read_symlink(p).string();
    EXPECT_EQ(target.rfind("/dev/pts/", 0), 0u);
    EXPECT_NE(target, "/dev/pts/does-not-exist");
    EXPECT_NE(port->describe().find(target), std::string::npos);

    // A reader on the symlink sees exactly what was written.
    const int fd = ::open(p.c_str(), O_RDONLY | O_NOCTTY | O_NONBLOCK);
    ASSERT_GE(fd, 0);
    const std::string epoch = "$GPGGA,test*00\r\n";
    port->write_epoch(epoch);
    EXPECT_EQ(read_pty_until_quiet(fd), epoch);
    ::close(fd);
    EXPECT_EQ(port->stats().epochs_written, 1u);
  }
  EXPECT_FALSE(fs::exists(fs::symlink_status(p)));
}

TEST(OutputPort, UndrainedPtyDropsWholeEpochsAndNeverBlocks) {
  TempDir dir;
  auto port = open_port(pty_config(dir.path / "gps0"), io);
  const std::string epoch(500, 'x');
  // 500 kB with nobody reading: far beyond the kernel's pty buffers (about
  // 64 kB + 4 kB), so without dropping this loop would block or fail.
  // (Exact drop counts need epochs spaced in time: the kernel moves pty data
  // to the reader's queue asynchronously, so a tight loop undercounts.)
  for (int i = 0; i < 1000; ++i) port->write_epoch(epoch);
  const PortStats& s = port->stats();
  EXPECT_GT(s.epochs_dropped, 0u);
  EXPECT_EQ(s.bytes_written, s.epochs_written * epoch.size());
  // A late reader finds whole epochs only, and not the whole history.
  const int fd = ::open((dir.path / "gps0").c_str(), O_RDONLY | O_NOCTTY | O_NONBLOCK);
  ASSERT_GE(fd, 0);
  // (The queue may also be empty: when the last write tore, the port flushed.)
  const std::string got = read_pty_until_quiet(fd);
  EXPECT_LE(got.size(), 68u * 1024u);
  EXPECT_EQ(got.size() % epoch.size(), 0u);
  // Drained, the reader gets the next epoch whole.
  port->write_epoch(epoch);
  EXPECT_EQ(read_pty_until_quiet(fd), epoch);
  ::close(fd);
}

TEST(OutputPort, FilePortWrites) {
  TempDir dir;
  config::OutputPortConfig c;
  c.name = "log";
  c.transport = config::FilePortConfig{(dir.path / "out.nmea").string()};
  {
    auto port = open_port(c, io);
    port->write_epoch("A\r\n");
    port->write_epoch("B\r\n");
    EXPECT_EQ(port->stats().epochs_written, 2u);
  }
  std::ifstream in(std::get<config::FilePortConfig>(c.transport).path);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(), "A\r\nB\r\n");
}

TEST(OutputPort, SerialLostDuringABaudSwitchReopensAtTheNewRateWithoutStaleOutput) {
  // The host asked for 38400; the switch waits for the line to drain, and
  // output produced meanwhile is held for the new rate. The device vanishes
  // before the drain: the reopened device must run at 38400 and must not
  // replay the held output of the old connection first.
  TempDir d;
  const fs::path link = d.path / "ttyGPS";
  int m1 = -1, s1 = -1;
  ASSERT_EQ(::openpty(&m1, &s1, nullptr, nullptr, nullptr), 0);
  fs::create_symlink(::ttyname(s1), link);
  config::OutputPortConfig c;
  c.name = "uart";
  c.transport = config::SerialPortConfig{link.string()};
  c.baud = 9600;
  auto port = open_port(c, io);
  port->start(nullptr);
  ::close(s1);  // the port holds its own fd
  // Fill the pty (nobody reads the master) so the drain cannot finish.
  port->write_epoch(std::string(60000, 'A'));
  port->set_baud_after_drain(38400);
  port->write_epoch("HELD");
  io.restart();
  io.run_for(std::chrono::milliseconds(50));
  EXPECT_EQ(port->baud(), 9600u);  // still draining
  // Unplug: the master goes, the slave reads EIO, the port closes.
  ::close(m1);
  EXPECT_TRUE(run_io_until([&] { return port->baud() == 38400u; }));
  // Plug in again: a new pty behind the same path; the port reopens (back-off 0.5 s).
  int m2 = -1, s2 = -1;
  ASSERT_EQ(::openpty(&m2, &s2, nullptr, nullptr, nullptr), 0);
  fs::remove(link);
  fs::create_symlink(::ttyname(s2), link);
  EXPECT_TRUE(run_io_until([&] { return port->stats().reopens >= 1u; }));
  ::close(s2);
  EXPECT_EQ(port->stats().reopens, 1u);
  port->write_epoch("NEW");
  ::fcntl(m2, F_SETFL, ::fcntl(m2, F_GETFL) | O_NONBLOCK);
  std::string got;
  run_io_until([&] {
    char buf[64];
    for (ssize_t n; (n = ::read(m2, buf, sizeof buf)) > 0;) got.append(buf, static_cast<std::size_t>(n));
    return got.size() >= 3;
  });
  EXPECT_EQ(got, "NEW");
  port.reset();
  ::close(m2);
}

TEST(ValidatePort, EveryType) {
  config::OutputPortConfig c;
  c.name = "t";
  c.transport = config::TcpPortConfig{"127.0.0.1", 0};
  c.baud = 0;
  EXPECT_NO_THROW(validate_port(c));
  std::get<config::TcpPortConfig>(c.transport).bind = "not-an-ip";
  EXPECT_THROW(validate_port(c), Error);
  c.transport = config::UdpPortConfig{"127.0.0.1", 0};
  EXPECT_THROW(validate_port(c), Error);
  c.transport = config::SerialPortConfig{"/dev/ttyUSB-absent-gnssemu"};  // absent: fine, the port retries
  c.baud = 9600;
  EXPECT_NO_THROW(validate_port(c));
  const config::SerialPortConfig plain_file{GNSSEMU_SOURCE_DIR "/CMakeLists.txt"};  // a regular file is a mistake
  EXPECT_THROW(validate_port(c, plain_file), Error);
  EXPECT_THROW(validate_port(c, config::SerialPortConfig{"ttyS0"}), Error);
  c.baud = 0;  // a serial line needs a rate
  EXPECT_THROW(validate_port(c), Error);
}

