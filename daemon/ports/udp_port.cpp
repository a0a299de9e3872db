// SPDX-License-Identifier: Apache-2.0
// UDP output port: each epoch in datagrams of at most kMaxDatagramBytes,
// split at message boundaries (a datagram never holds half a message).
#include <boost/asio/ip/udp.hpp>

#include "core/common/error.hpp"
#include "daemon/ports/port_impl.hpp"

namespace gnssemu::daemon::detail {
namespace {

namespace asio = boost::asio;
using asio::ip::udp;

class UdpPort final : public OutputPort {
public:
  UdpPort(const config::OutputPortConfig& cfg, const config::UdpPortConfig& destination, asio::io_context& io)
      : OutputPort(cfg), destination_(destination), socket_(io) {
    boost::system::error_code ec;
    dest_ = udp::endpoint(asio::ip::make_address(destination.address, ec), destination.port);
    if (!ec) socket_.open(dest_.protocol(), ec);
    if (!ec) socket_.non_blocking(true, ec);
    if (ec) throw Error("output '" + cfg.name + "': cannot open udp socket: " + ec.message());
  }

  std::string describe() const override {
    return "udp to " + destination_.address + ":" + std::to_string(destination_.port);
  }

protected:
  void deliver(int /*source*/, std::string_view data, std::span<const std::size_t> ends, bool epoch) noexcept override {
    const std::size_t whole = data.size();
    if (ends.empty() && !data.empty()) ends = {&whole, 1};
    bool ok = true;
    std::size_t start = 0;
    for (std::size_t k = 0; k < ends.size();) {
      // Whole messages up to the datagram size (a longer message goes alone).
      std::size_t end = ends[k++];
      while (k < ends.size() && ends[k] - start <= kMaxDatagramBytes) end = ends[k++];
      boost::system::error_code ec;
      const std::size_t n = socket_.send_to(asio::buffer(data.data() + start, end - start), dest_, 0, ec);
      if (ec) {
        ok = false;  // e.g. ICMP port unreachable from an earlier datagram: nobody listens yet
      } else {
        stats_.bytes_written += n;
      }
      start = end;
    }
    if (epoch) {
      ok ? ++stats_.epochs_written : ++stats_.epochs_dropped;
    } else if (ok) {
      ++stats_.replies_written;
    }
  }

private:
  config::UdpPortConfig destination_;
  udp::socket socket_;
  udp::endpoint dest_;
};

}  // namespace

std::unique_ptr<OutputPort> make_port(const config::OutputPortConfig& cfg, const config::UdpPortConfig& destination,
                                      asio::io_context& io) {
  return std::make_unique<UdpPort>(cfg, destination, io);
}

}  // namespace gnssemu::daemon::detail

namespace gnssemu::daemon {

void validate_port(const config::OutputPortConfig& port, const config::UdpPortConfig& destination) {
  const std::string who = "output '" + port.name + "'";
  boost::system::error_code ec;
  boost::asio::ip::make_address(destination.address, ec);
  if (ec) throw Error(who + ": bad address '" + destination.address + "'");
  if (destination.port == 0) throw Error(who + ": udp destination port 0");
}

}  // namespace gnssemu::daemon
