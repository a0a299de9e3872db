// SPDX-License-Identifier: Apache-2.0
#include "daemon/ports/output_port.hpp"

#include <termios.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <variant>

#include "daemon/ports/port_impl.hpp"

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

void validate_port(const config::OutputPortConfig& port) {
  std::visit([&](const auto& transport) { validate_port(port, transport); }, port.transport);
}

std::unique_ptr<OutputPort> open_port(const config::OutputPortConfig& port, boost::asio::io_context& io) {
  validate_port(port);
  return std::visit([&](const auto& transport) { return detail::make_port(port, transport, io); }, port.transport);
}

}  // namespace gnssemu::daemon
