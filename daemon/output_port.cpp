#include "daemon/output_port.hpp"

#include <sys/stat.h>
#include <termios.h>

#include <array>
#include <cerrno>
#include <cstring>

#include <boost/asio/ip/address.hpp>

#include "core/common/error.hpp"
#include "daemon/port_impl.hpp"

namespace gnssemu::daemon {

namespace detail {

unsigned baud_constant(uint32_t baud) noexcept {
  // termios speeds of protocol::ubx::kUartBauds, in the same order.
  static constexpr std::array<unsigned, protocol::ubx::kUartBauds.size()> kSpeeds{
      B4800, B9600, B19200, B38400, B57600, B115200, B230400, B460800, B921600};
  for (std::size_t i = 0; i < kSpeeds.size(); ++i) {
    if (protocol::ubx::kUartBauds[i] == baud) return kSpeeds[i];
  }
  return B9600;
}

std::string errno_text() { return std::strerror(errno); }

}  // namespace detail

void validate_port(const config::OutputPortConfig& cfg) {
  const std::string who = "output '" + cfg.name + "'";
  switch (cfg.type) {
    case config::PortType::kPty: {
      if (cfg.path.empty()) throw Error(who + ": empty path");
      struct stat st{};
      if (::lstat(cfg.path.c_str(), &st) == 0 && !S_ISLNK(st.st_mode)) {
        throw Error(cfg.path, 0, who + ": path exists and is not a symlink; refusing to replace it");
      }
      break;
    }
    case config::PortType::kFile:
      if (cfg.path.empty()) throw Error(who + ": empty path");
      break;
    case config::PortType::kSerial: {
      if (cfg.path.empty() || cfg.path.front() != '/') throw Error(who + ": serial device must be an absolute path");
      struct stat st{};
      // Absent is fine (unplugged adapter: the port retries); a plain file is a mistake.
      if (::stat(cfg.path.c_str(), &st) == 0 && (S_ISREG(st.st_mode) || S_ISDIR(st.st_mode))) {
        throw Error(cfg.path, 0, who + ": is a regular file or folder, not a serial device");
      }
      if (cfg.baud == 0) throw Error(who + ": a serial port needs a baud rate");
      break;
    }
    case config::PortType::kTcp:
    case config::PortType::kUdp: {
      boost::system::error_code ec;
      boost::asio::ip::make_address(cfg.address, ec);
      if (ec) throw Error(who + ": bad address '" + cfg.address + "'");
      if (cfg.type == config::PortType::kUdp && cfg.port == 0) throw Error(who + ": udp destination port 0");
      break;
    }
  }
}

std::unique_ptr<OutputPort> open_port(const config::OutputPortConfig& cfg, boost::asio::io_context& io) {
  validate_port(cfg);
  switch (cfg.type) {
    case config::PortType::kPty: return detail::make_pty_port(cfg, io);
    case config::PortType::kFile: return detail::make_file_port(cfg);
    case config::PortType::kSerial: return detail::make_serial_port(cfg, io);
    case config::PortType::kTcp: return detail::make_tcp_port(cfg, io);
    case config::PortType::kUdp: return detail::make_udp_port(cfg, io);
  }
  throw Error("output '" + cfg.name + "': unknown port type");
}

}  // namespace gnssemu::daemon
