// SPDX-License-Identifier: Apache-2.0
#pragma once
// Setup of each port type, defined with its port class in the type's file
// (pty_port.cpp holds pty and file); internal to output_port.cpp.
#include <memory>

#include "daemon/ports/output_port.hpp"

namespace gnssemu::daemon::detail {

std::unique_ptr<OutputPort> make_port(const config::OutputPortConfig& cfg, const config::PtyPortConfig& pty,
                                      boost::asio::io_context& io);
std::unique_ptr<OutputPort> make_port(const config::OutputPortConfig& cfg, const config::FilePortConfig& file,
                                      boost::asio::io_context& io);
std::unique_ptr<OutputPort> make_port(const config::OutputPortConfig& cfg, const config::SerialPortConfig& serial,
                                      boost::asio::io_context& io);
std::unique_ptr<OutputPort> make_port(const config::OutputPortConfig& cfg, const config::TcpPortConfig& server,
                                      boost::asio::io_context& io);
std::unique_ptr<OutputPort> make_port(const config::OutputPortConfig& cfg, const config::UdpPortConfig& destination,
                                      boost::asio::io_context& io);

/// termios speed constant for a standard rate (B9600 for anything else).
unsigned baud_constant(uint32_t baud_bps) noexcept;
std::string errno_text();

}  // namespace gnssemu::daemon::detail
