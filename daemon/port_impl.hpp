#pragma once
// Factories of the port types (one file each); internal to output_port.cpp.
#include <memory>

#include "daemon/output_port.hpp"

namespace gnssemu::daemon::detail {

std::unique_ptr<OutputPort> make_pty_port(const config::OutputPortConfig& cfg, boost::asio::io_context& io);
std::unique_ptr<OutputPort> make_file_port(const config::OutputPortConfig& cfg);
std::unique_ptr<OutputPort> make_serial_port(const config::OutputPortConfig& cfg, boost::asio::io_context& io);
std::unique_ptr<OutputPort> make_tcp_port(const config::OutputPortConfig& cfg, boost::asio::io_context& io);
std::unique_ptr<OutputPort> make_udp_port(const config::OutputPortConfig& cfg, boost::asio::io_context& io);

/// termios speed constant for a standard rate (B9600 for anything else).
unsigned baud_constant(uint32_t baud_bps) noexcept;
std::string errno_text();

}  // namespace gnssemu::daemon::detail
