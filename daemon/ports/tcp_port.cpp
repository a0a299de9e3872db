// SPDX-License-Identifier: Apache-2.0
// TCP server port: every client gets the stream; input from any client goes
// to the port's responder and replies go back to that client only.
#include <algorithm>
#include <array>
#include <chrono>
#include <list>
#include <memory>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/write.hpp>
#include <spdlog/spdlog.h>

#include "core/common/error.hpp"
#include "daemon/ports/input_budget.hpp"
#include "daemon/ports/port_impl.hpp"

namespace gnssemu::daemon::detail {
namespace {

namespace asio = boost::asio;
using asio::ip::tcp;

constexpr std::size_t kMaxClients = 16;
// A client whose socket has taken no byte for this long while data waits
// is not reading (an idle connection, a hung program): it is disconnected so
// it neither holds a slot nor memory. Readers at any line rate drain a
// write well within it.
constexpr double kStallS = 10.0;
// A new client beyond kMaxClients takes the slot of a client stalled this long.
constexpr double kEvictStallS = 1.0;
// Kernel send buffer per client: bounds what a non-reading client holds
// beyond its kMaxQueuedBytes queue, so a stall shows within seconds.
constexpr int kSendBufferBytes = 32 * 1024;

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

class TcpPort final : public OutputPort {
public:
  TcpPort(const config::OutputPortConfig& cfg, const config::TcpPortConfig& server, asio::io_context& io)
      : OutputPort(cfg), bind_(server.bind), io_(io), acceptor_(io) {
    boost::system::error_code ec;
    const tcp::endpoint ep(asio::ip::make_address(server.bind, ec), server.port);
    if (!ec) acceptor_.open(ep.protocol(), ec);
    if (!ec) acceptor_.set_option(tcp::acceptor::reuse_address(true), ec);
    if (!ec) acceptor_.bind(ep, ec);
    if (!ec) acceptor_.listen(asio::socket_base::max_listen_connections, ec);
    if (ec) {
      throw Error("output '" + cfg.name + "': cannot listen on tcp " + server.bind + ":" + std::to_string(server.port) +
                  ": " + ec.message());
    }
    local_port_ = acceptor_.local_endpoint(ec).port();
  }

  ~TcpPort() override {
    boost::system::error_code ec;
    acceptor_.close(ec);
    for (auto& c : clients_) c->socket.close(ec);
  }

  void start(PortListener* listener) override {
    listener_ = listener;
    accept();
  }

  int readers() const noexcept override { return static_cast<int>(clients_.size()); }

  std::string describe() const override {
    return "tcp " + bind_ + ":" + std::to_string(local_port_) + " (server)";
  }

protected:
  void deliver(int source, std::string_view data, std::span<const std::size_t> /*ends*/, bool epoch) noexcept override {
    bool any = false;
    const double now = now_s();
    for (auto it = clients_.begin(); it != clients_.end();) {
      const ClientPtr s = *it++;  // a copy: drop() erases the element
      if (s->writing && now - s->progress_s > kStallS) {
        spdlog::warn("output {}: client {} took no data for {:.0f} s: disconnected ({} epochs dropped for it)",
                     config_.name, s->id, kStallS, s->dropped);
        drop(s);
      }
    }
    for (auto& c : clients_) {
      if (source != kAllSources && c->id != source) continue;
      if (c->queue.size() + data.size() > kMaxQueuedBytes) {
        ++c->dropped;  // a client that does not read loses epochs, not the others
        continue;
      }
      c->queue.append(data);
      any = true;
      flush(c);
    }
    if (epoch) {
      any || clients_.empty() ? ++stats_.epochs_written : ++stats_.epochs_dropped;
    } else if (any) {
      ++stats_.replies_written;
    }
  }

private:
  struct Client {
    explicit Client(asio::io_context& io) : socket(io), pacer(io) {}
    tcp::socket socket;
    InputPacer pacer;
    int id = 0;
    std::string queue;
    bool writing = false;
    double progress_s = 0.0;  ///< when the pending write started or last took bytes, steady s
    uint64_t dropped = 0;
    std::array<uint8_t, 1024> rx{};
  };
  using ClientPtr = std::shared_ptr<Client>;

  std::string bind_;  ///< listen address

  void accept() {
    auto c = std::make_shared<Client>(io_);
    acceptor_.async_accept(c->socket, [this, c](const boost::system::error_code& ec) {
      if (ec == asio::error::operation_aborted || !acceptor_.is_open()) return;
      if (!ec) {
        if (clients_.size() >= kMaxClients) evict_stalled();
        if (clients_.size() >= kMaxClients) {
          spdlog::warn("output {}: refusing a client beyond {} (all of them reading)", config_.name, kMaxClients);
          boost::system::error_code cec;
          c->socket.close(cec);
        } else {
          c->progress_s = now_s();
          c->id = next_id_++;
          c->queue.reserve(kMaxQueuedBytes);
          boost::system::error_code oec;
          c->socket.set_option(tcp::no_delay(true), oec);
          c->socket.set_option(asio::socket_base::send_buffer_size(kSendBufferBytes), oec);
          const auto peer = c->socket.remote_endpoint(oec);
          spdlog::info("output {}: client {} connected from {}:{}", config_.name, c->id, peer.address().to_string(),
                       peer.port());
          clients_.push_back(c);
          read(c);
        }
      }
      accept();
    });
  }

  void read(const ClientPtr& c) {
    c->socket.async_read_some(asio::buffer(c->rx), [this, c](const boost::system::error_code& ec, std::size_t n) {
      if (ec == asio::error::operation_aborted) return;
      if (ec) {
        drop(c);
        return;
      }
      stats_.bytes_from_reader += n;
      if (listener_ != nullptr) listener_->on_port_input(c->id, {c->rx.data(), n});
      // A closed socket: the client (or the port) is gone.
      c->pacer.next(n, [this, c] {
        if (c->socket.is_open()) read(c);
      });
    });
  }

  void flush(const ClientPtr& c) {
    if (c->writing || c->queue.empty()) return;
    c->writing = true;
    c->progress_s = now_s();  // a pending write older than kStallS: not reading
    c->socket.async_write_some(asio::buffer(c->queue), [this, c](const boost::system::error_code& ec, std::size_t n) {
      c->writing = false;
      if (ec) {
        if (ec != asio::error::operation_aborted) drop(c);
        return;
      }
      stats_.bytes_written += n;
      c->progress_s = now_s();
      c->queue.erase(0, n);
      flush(c);
    });
  }

  /// Disconnect the client stalled longest, if any is stalled kEvictStallS.
  void evict_stalled() {
    const double now = now_s();
    ClientPtr worst;
    for (const ClientPtr& c : clients_) {
      if (c->writing && now - c->progress_s > kEvictStallS && (!worst || c->progress_s < worst->progress_s)) worst = c;
    }
    if (!worst) return;
    spdlog::warn("output {}: client {} took no data for {:.0f} s: disconnected for a new client", config_.name,
                 worst->id, now - worst->progress_s);
    drop(worst);
  }

  void drop(const ClientPtr& c) {
    const auto it = std::find(clients_.begin(), clients_.end(), c);
    if (it == clients_.end()) return;
    spdlog::info("output {}: client {} gone ({} epochs dropped for it)", config_.name, c->id, c->dropped);
    boost::system::error_code ec;
    c->socket.close(ec);
    c->pacer.cancel();
    clients_.erase(it);
    if (listener_ != nullptr) listener_->on_source_closed(c->id);
  }

  asio::io_context& io_;
  tcp::acceptor acceptor_;
  uint16_t local_port_ = 0;
  std::list<ClientPtr> clients_;
  int next_id_ = 1;
  PortListener* listener_ = nullptr;
};

}  // namespace

std::unique_ptr<OutputPort> make_port(const config::OutputPortConfig& cfg, const config::TcpPortConfig& server,
                                      asio::io_context& io) {
  return std::make_unique<TcpPort>(cfg, server, io);
}

}  // namespace gnssemu::daemon::detail

namespace gnssemu::daemon {

void validate_port(const config::OutputPortConfig& port, const config::TcpPortConfig& server) {
  boost::system::error_code ec;
  boost::asio::ip::make_address(server.bind, ec);
  if (ec) throw Error("output '" + port.name + "': bad address '" + server.bind + "'");
}

}  // namespace gnssemu::daemon
