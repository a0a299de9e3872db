// SPDX-License-Identifier: Apache-2.0
#include "daemon/status/status_server.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <list>
#include <optional>
#include <string_view>

#include <boost/asio/ip/address.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

#include "core/common/error.hpp"
#include "daemon/status/web_assets.hpp"

namespace gnssemu::daemon {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = boost::beast::http;
using tcp = asio::ip::tcp;

namespace {

std::chrono::milliseconds millis(double s) { return std::chrono::milliseconds(static_cast<int64_t>(s * 1e3)); }

constexpr std::string_view kEventStreamHeader =
    "HTTP/1.1 200 OK\r\n"
    "Content-Type: text/event-stream\r\n"
    "Cache-Control: no-store\r\n"
    "X-Content-Type-Options: nosniff\r\n"
    "Connection: keep-alive\r\n\r\n"
    "retry: 1000\n\n";

/// history=N of a query string; def when absent or not a number.
std::size_t history_param(std::string_view query, std::size_t def) {
  std::size_t pos = 0;
  while (pos < query.size()) {
    std::size_t end = query.find('&', pos);
    if (end == std::string_view::npos) end = query.size();
    const std::string_view item = query.substr(pos, end - pos);
    if (item.starts_with("history=")) {
      std::size_t n = 0;
      const std::string_view v = item.substr(8);
      const auto r = std::from_chars(v.data(), v.data() + v.size(), n);
      if (r.ec == std::errc() && r.ptr == v.data() + v.size()) return n;
    }
    pos = end + 1;
  }
  return def;
}

/// The value of key=... in a query string (no decoding: ids are plain); "" when absent.
std::string_view query_param(std::string_view query, std::string_view key) {
  std::size_t pos = 0;
  while (pos < query.size()) {
    std::size_t end = query.find('&', pos);
    if (end == std::string_view::npos) end = query.size();
    const std::string_view item = query.substr(pos, end - pos);
    if (item.size() > key.size() && item.starts_with(key) && item[key.size()] == '=') {
      return item.substr(key.size() + 1);
    }
    pos = end + 1;
  }
  return {};
}

/// The first key of query /api/status does not take, as an error text; "" when none.
std::string unknown_status_param(std::string_view query) {
  std::size_t pos = 0;
  while (pos < query.size()) {
    std::size_t end = query.find('&', pos);
    if (end == std::string_view::npos) end = query.size();
    const std::string_view item = query.substr(pos, end - pos);
    pos = end + 1;
    const std::string_view key = item.substr(0, item.find('='));
    if (item.empty() || key == "history" || key == "vehicle" || key == "receiver") continue;
    return "unknown query parameter '" + std::string(key.substr(0, 64)) +
           "' (/api/status takes history, vehicle, receiver)";
  }
  return {};
}

}  // namespace

class Session;

struct StatusServer::Shared {
  explicit Shared(asio::io_context& io_ctx, const StatusProducer& p)
      : io(io_ctx), acceptor(io_ctx), retry(io_ctx), producer(&p) {}
  asio::io_context& io;
  tcp::acceptor acceptor;
  asio::steady_timer retry;  ///< back-off after an accept error
  const StatusProducer* producer;  ///< null after stop()
  StatusServer::Selector selector;  ///< a fleet's receivers by vehicle id and name
  StatusServer::Lister lister;      ///< the fleet's receivers, JSON
  StatusServer::Roster roster;      ///< the fleet's receivers for /api/overview
  std::vector<OverviewEntry> entries;  ///< roster's output, reused between requests
  std::list<std::weak_ptr<Session>> sessions;
  std::string event;  ///< the newest event, "data: {...}\n\n"
  StatusServerStats stats;
  bool stopped = false;
};

/// One HTTP connection: requests until it closes; /api/events turns it
/// into an event stream.
class Session : public std::enable_shared_from_this<Session> {
public:
  Session(tcp::socket socket, std::shared_ptr<StatusServer::Shared> shared)
      : stream_(std::move(socket)), shared_(std::move(shared)) {}

  void start() { read(); }

  /// Queue the newest event (event streams only). False: dropped.
  void push(std::string_view event) noexcept {
    if (!streaming_ || closed_) return;
    if (pending_.size() + event.size() > kMaxEventBacklogBytes) {
      ++shared_->stats.streams_dropped;
      close();
      return;
    }
    try {
      pending_.append(event);
    } catch (...) {
      close();
      return;
    }
    if (!writing_) write_pending();
  }

  void close() noexcept {
    if (closed_) return;
    closed_ = true;
    beast::error_code ec;
    stream_.socket().shutdown(tcp::socket::shutdown_both, ec);
    stream_.close();
  }

  bool streaming() const noexcept { return streaming_ && !closed_; }

private:
  void read() {
    parser_.emplace();
    parser_->header_limit(static_cast<std::uint32_t>(kMaxHeaderBytes));
    parser_->body_limit(0);
    stream_.expires_after(millis(kRequestTimeoutS));
    http::async_read(stream_, buffer_, *parser_,
                     [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
  }

  void on_read(beast::error_code ec) {
    if (closed_) return;
    if (ec == http::error::end_of_stream || ec == asio::error::eof || ec == asio::error::connection_reset ||
        ec == asio::error::operation_aborted) {
      close();
      return;
    }
    if (ec) {
      ++shared_->stats.bad_requests;
      // A timeout or a broken stream gets no answer; a bad request does.
      if (ec == beast::error::timeout || !parser_->is_header_done()) {
        const bool too_large = ec == http::error::header_limit || ec == http::error::buffer_overflow;
        if (ec != beast::error::timeout) respond_error(too_large ? http::status::request_header_fields_too_large
                                                                 : http::status::bad_request,
                                                       ec.message());
        else close();
        return;
      }
      respond_error(http::status::bad_request, ec.message());
      return;
    }
    handle(parser_->get());
  }

  void handle(const http::request<http::empty_body>& req) {
    const std::string_view target(req.target().data(), req.target().size());
    const std::size_t q = target.find('?');
    const std::string_view path = target.substr(0, q);
    const std::string_view query = q == std::string_view::npos ? std::string_view() : target.substr(q + 1);
    if (req.method() != http::verb::get) {
      ++shared_->stats.bad_requests;
      respond_error(http::status::method_not_allowed, "only GET is served");
      return;
    }
    if (path == "/api/events") {
      start_stream();
      return;
    }
    auto res = std::make_shared<http::response<http::string_body>>(http::status::ok, req.version());
    res->keep_alive(req.keep_alive());
    res->set(http::field::cache_control, "no-store");
    res->set("X-Content-Type-Options", "nosniff");
    if (path == "/api/status") {
      if (shared_->producer == nullptr) {
        respond_error(http::status::service_unavailable, "shutting down");
        return;
      }
      if (const std::string why = unknown_status_param(query); !why.empty()) {
        ++shared_->stats.bad_requests;
        respond_error(http::status::bad_request, why);
        return;
      }
      const StatusProducer* producer = shared_->producer;
      if (const std::string_view vehicle = query_param(query, "vehicle"); !vehicle.empty()) {
        producer = shared_->selector ? shared_->selector(vehicle, query_param(query, "receiver")) : nullptr;
        if (producer == nullptr) {
          respond_error(http::status::not_found, "no such vehicle or receiver");
          return;
        }
      }
      res->set(http::field::content_type, "application/json");
      std::string& body = res->body();
      body.reserve(64 * 1024);
      producer->write_json(body, history_param(query, StatusProducer::kHistory));
    } else if (path == "/api/overview" && shared_->roster) {
      if (shared_->producer == nullptr) {
        respond_error(http::status::service_unavailable, "shutting down");
        return;
      }
      OverviewQuery oq;
      if (const std::string why = parse_overview_query(query, oq); !why.empty()) {
        ++shared_->stats.bad_requests;
        respond_error(http::status::bad_request, why);
        return;
      }
      shared_->roster(shared_->entries);
      sort_overview(shared_->entries, oq);
      res->set(http::field::content_type, "application/json");
      res->body().reserve(512 + 600 * std::min(oq.limit, shared_->entries.size()));
      write_overview(res->body(), shared_->entries, oq);
    } else if (path == "/api/receivers" && shared_->lister) {
      res->set(http::field::content_type, "application/json");
      res->body() = shared_->lister();
    } else if (const web::Asset* a = web::find_asset(path)) {
      res->set(http::field::content_type, std::string(a->content_type));
      res->body().assign(a->text.data(), a->text.size());
    } else {
      respond_error(http::status::not_found, "no such page");
      return;
    }
    send(res);
  }

  void respond_error(http::status status, std::string_view why) {
    auto res = std::make_shared<http::response<http::string_body>>(status, 11);
    res->set(http::field::content_type, "text/plain; charset=utf-8");
    res->set(http::field::connection, "close");
    if (status == http::status::method_not_allowed) res->set(http::field::allow, "GET");
    res->body() = std::string(http::obsolete_reason(status)) + ": " + std::string(why) + "\n";
    res->keep_alive(false);
    send(res);
  }

  void send(const std::shared_ptr<http::response<http::string_body>>& res) {
    res->prepare_payload();
    ++shared_->stats.requests;
    stream_.expires_after(millis(kRequestTimeoutS));
    http::async_write(stream_, *res, [self = shared_from_this(), res](beast::error_code ec, std::size_t) {
      if (ec || !res->keep_alive() || self->closed_) {
        self->close();
        return;
      }
      self->read();
    });
  }

  void start_stream() {
    ++shared_->stats.requests;
    streaming_ = true;
    try {
      pending_.reserve(kMaxEventBacklogBytes);
      writing_buf_.reserve(kMaxEventBacklogBytes);
      pending_.assign(kEventStreamHeader);
      if (!shared_->event.empty()) pending_.append(shared_->event);
    } catch (...) {
      close();
      return;
    }
    write_pending();
    watch_peer();
  }

  /// An event stream's client sends nothing more: a read that ends tells
  /// that it went away, and keeps the session alive between events.
  void watch_peer() {
    stream_.socket().async_read_some(asio::buffer(sink_), [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (self->closed_) return;
      if (ec) {
        self->close();
        return;
      }
      self->watch_peer();  // whatever it sends is ignored
    });
  }

  void write_pending() noexcept {
    if (closed_ || pending_.empty()) return;
    writing_ = true;
    std::swap(pending_, writing_buf_);
    pending_.clear();
    stream_.expires_after(millis(kEventWriteTimeoutS));
    asio::async_write(stream_, asio::buffer(writing_buf_),
                      [self = shared_from_this()](beast::error_code ec, std::size_t) {
                        self->writing_ = false;
                        self->writing_buf_.clear();
                        if (ec) {
                          if (ec == beast::error::timeout) ++self->shared_->stats.streams_dropped;
                          self->close();
                          return;
                        }
                        self->stream_.expires_never();
                        self->write_pending();
                      });
  }

  beast::tcp_stream stream_;
  std::shared_ptr<StatusServer::Shared> shared_;
  beast::flat_buffer buffer_{kMaxHeaderBytes * 2};
  std::optional<http::request_parser<http::empty_body>> parser_;
  bool streaming_ = false;
  bool writing_ = false;
  bool closed_ = false;
  std::string pending_;      ///< events queued while a write is in flight
  std::string writing_buf_;  ///< the bytes being written
  std::array<char, 512> sink_{};  ///< what an event-stream client sends
};

StatusServer::StatusServer(asio::io_context& io, const StatusProducer& producer)
    : shared_(std::make_shared<Shared>(io, producer)) {}

void StatusServer::set_selector(Selector selector, Lister lister) {
  shared_->selector = std::move(selector);
  shared_->lister = std::move(lister);
}

void StatusServer::set_roster(Roster roster) { shared_->roster = std::move(roster); }

StatusServer::~StatusServer() { stop(); }

void StatusServer::start(const std::string& bind, uint16_t port) {
  beast::error_code ec;
  const asio::ip::address addr = asio::ip::make_address(bind, ec);
  if (ec) throw Error("status page: bad bind address '" + bind + "'");
  const tcp::endpoint ep(addr, port);
  tcp::acceptor& a = shared_->acceptor;
  a.open(ep.protocol(), ec);
  if (!ec) a.set_option(asio::socket_base::reuse_address(true), ec);
  if (!ec) a.bind(ep, ec);
  if (!ec) a.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) {
    throw Error("status page: cannot listen on " + bind + ":" + std::to_string(port) + ": " + ec.message() +
                " ([status] port, or port = 0 to turn the page off)");
  }
  accept();
}

tcp::endpoint StatusServer::local_endpoint() const {
  beast::error_code ec;
  return shared_->acceptor.local_endpoint(ec);
}

namespace {

void accept_loop(const std::shared_ptr<StatusServer::Shared>& shared) {
  shared->acceptor.async_accept(shared->io, [shared](beast::error_code ec, tcp::socket socket) {
    if (ec == asio::error::operation_aborted || shared->stopped) return;
    if (!ec) {
      shared->sessions.remove_if([](const std::weak_ptr<Session>& w) { return w.expired(); });
      if (shared->sessions.size() >= kMaxSessions) {
        ++shared->stats.sessions_refused;
        beast::error_code ignored;
        socket.close(ignored);
      } else {
        auto session = std::make_shared<Session>(std::move(socket), shared);
        shared->sessions.push_back(session);
        session->start();
      }
    }
    if (!ec) {
      accept_loop(shared);
      return;
    }
    // An accept error (e.g. out of descriptors) does not stop the listener; a
    // pause keeps it from spinning on the epoch loop's thread.
    shared->retry.expires_after(std::chrono::milliseconds(100));
    shared->retry.async_wait([shared](beast::error_code tec) {
      if (!tec && !shared->stopped) accept_loop(shared);
    });
  });
}

}  // namespace

void StatusServer::accept() { accept_loop(shared_); }

void StatusServer::set_producer(const StatusProducer& producer) noexcept {
  if (!shared_->stopped) shared_->producer = &producer;
}

void StatusServer::publish() noexcept {
  Shared& s = *shared_;
  if (s.stopped || s.producer == nullptr) return;
  bool any = false;
  for (const std::weak_ptr<Session>& w : s.sessions) {
    const std::shared_ptr<Session> p = w.lock();
    if (p && p->streaming()) any = true;
  }
  s.event.clear();
  if (!any) return;
  s.event.append("data: ");
  s.producer->write_json(s.event, 1);
  s.event.append("\n\n");
  for (const std::weak_ptr<Session>& w : s.sessions)
    if (const std::shared_ptr<Session> p = w.lock()) p->push(s.event);
}

void StatusServer::stop() noexcept {
  Shared& s = *shared_;
  if (s.stopped) return;
  s.stopped = true;
  s.producer = nullptr;
  beast::error_code ec;
  s.acceptor.close(ec);
  s.retry.cancel();
  for (const std::weak_ptr<Session>& w : s.sessions)
    if (const std::shared_ptr<Session> p = w.lock()) p->close();
  s.sessions.clear();
}

StatusServerStats StatusServer::stats() const noexcept {
  StatusServerStats st = shared_->stats;
  st.sessions = st.streams = 0;
  for (const std::weak_ptr<Session>& w : shared_->sessions) {
    if (const std::shared_ptr<Session> p = w.lock()) {
      ++st.sessions;
      if (p->streaming()) ++st.streams;
    }
  }
  return st;
}

}  // namespace gnssemu::daemon
