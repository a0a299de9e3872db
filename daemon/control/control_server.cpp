// SPDX-License-Identifier: Apache-2.0
#include "daemon/control/control_server.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <vector>

#include <boost/asio/local/stream_protocol.hpp>
#include <boost/asio/read_until.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/streambuf.hpp>
#include <boost/asio/write.hpp>

#include "core/common/error.hpp"

namespace gnssemu::daemon {

namespace asio = boost::asio;
using Local = asio::local::stream_protocol;

namespace {

class Session;

}  // namespace

struct ControlServer::Shared {
  Shared(asio::io_context& ctx, Handler h) : io(ctx), acceptor(ctx), retry(ctx), handler(std::move(h)) {}
  asio::io_context& io;
  Local::acceptor acceptor;
  asio::steady_timer retry;  ///< after a failed accept (EMFILE): no busy loop
  Handler handler;
  std::vector<std::weak_ptr<Session>> sessions;
  bool stopped = false;

  std::size_t live() {
    std::erase_if(sessions, [](const std::weak_ptr<Session>& w) { return w.expired(); });
    return sessions.size();
  }
};

namespace {

std::string busy_reply() { return R"({"ok":false,"error":"too many control connections"})"; }

// One client: read a line, answer it, read the next.
class Session : public std::enable_shared_from_this<Session> {
public:
  Session(Local::socket socket, std::shared_ptr<ControlServer::Shared> shared)
      : socket_(std::move(socket)), timer_(shared->io), shared_(std::move(shared)), in_(kMaxControlLineBytes + 1) {}

  void start() { read(); }
  void close() noexcept {
    boost::system::error_code ec;
    timer_.cancel();
    socket_.close(ec);
  }
  /// Say why and hang up (connection limit, oversize request).
  void reply_and_close(std::string reply) {
    out_ = std::move(reply) + "\n";
    auto self = shared_from_this();
    asio::async_write(socket_, asio::buffer(out_), [self](const boost::system::error_code&, std::size_t) {
      self->close();
    });
  }

private:
  void arm_idle() {
    timer_.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(kControlIdleS)));
    std::weak_ptr<Session> weak = shared_from_this();
    timer_.async_wait([weak](const boost::system::error_code& ec) {
      if (ec) return;
      if (auto s = weak.lock()) s->close();
    });
  }

  void read() {
    arm_idle();
    auto self = shared_from_this();
    asio::async_read_until(socket_, in_, '\n', [self](const boost::system::error_code& ec, std::size_t n) {
      self->on_read(ec, n);
    });
  }

  void on_read(const boost::system::error_code& ec, std::size_t n) {
    if (shared_->stopped) return;
    if (ec == asio::error::not_found) {  // the buffer filled without a newline
      reply_and_close(R"({"ok":false,"error":"request longer than )" + std::to_string(kMaxControlLineBytes) +
                      R"( bytes"})");
      return;
    }
    if (ec) {
      close();
      return;
    }
    std::string line(asio::buffers_begin(in_.data()), asio::buffers_begin(in_.data()) + static_cast<std::ptrdiff_t>(n));
    in_.consume(n);
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
    if (line.empty()) {
      read();
      return;
    }
    out_ = shared_->handler(line) + "\n";
    auto self = shared_from_this();
    asio::async_write(socket_, asio::buffer(out_), [self](const boost::system::error_code& wec, std::size_t) {
      if (wec) {
        self->close();
        return;
      }
      self->read();
    });
  }

  Local::socket socket_;
  asio::steady_timer timer_;
  std::shared_ptr<ControlServer::Shared> shared_;
  asio::streambuf in_;
  std::string out_;
};

// Connect to the socket at path: success (somebody listens), connection
// refused (a stale file) or another error.
boost::system::error_code probe(asio::io_context& io, const std::string& path) {
  Local::socket s(io);
  boost::system::error_code ec;
  s.connect(Local::endpoint(path), ec);
  return ec;
}

void accept_next(const std::shared_ptr<ControlServer::Shared>& shared) {
  std::weak_ptr<ControlServer::Shared> weak = shared;
  shared->acceptor.async_accept([weak](const boost::system::error_code& ec, Local::socket socket) {
    auto sh = weak.lock();
    if (!sh || sh->stopped || ec == asio::error::operation_aborted) return;
    if (ec) {  // e.g. EMFILE: the listener stays, tried again shortly
      sh->retry.expires_after(std::chrono::milliseconds(100));
      sh->retry.async_wait([weak](const boost::system::error_code& tec) {
        auto again = weak.lock();
        if (!tec && again && !again->stopped) accept_next(again);
      });
      return;
    }
    auto session = std::make_shared<Session>(std::move(socket), sh);
    if (sh->live() >= kMaxControlSessions) {
      session->reply_and_close(busy_reply());
    } else {
      sh->sessions.push_back(session);
      session->start();
    }
    accept_next(sh);
  });
}

}  // namespace

ControlServer::ControlServer(asio::io_context& io, Handler handler)
    : shared_(std::make_shared<Shared>(io, std::move(handler))) {}

ControlServer::~ControlServer() { stop(); }

void ControlServer::start(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code fec;
  const fs::file_status st = fs::symlink_status(path, fec);
  if (fs::exists(st)) {
    if (!fs::is_socket(st)) throw Error("control socket " + path + ": exists and is not a socket; not replacing it");
    const boost::system::error_code pec = probe(shared_->io, path);
    if (!pec) throw Error("control socket " + path + ": another process is listening on it");
    if (pec != asio::error::connection_refused) throw Error("control socket " + path + ": " + pec.message());
    fs::remove(path, fec);  // stale: left by a daemon that did not exit cleanly
  }
  const fs::path folder = fs::path(path).parent_path();
  if (!fs::is_directory(folder, fec)) throw Error("control socket " + path + ": folder " + folder.string() + " does not exist");
  boost::system::error_code ec;
  Local::acceptor& a = shared_->acceptor;
  a.open(Local(), ec);
  if (!ec) a.bind(Local::endpoint(path), ec);
  if (ec) throw Error("control socket " + path + ": " + ec.message());
  path_ = path;
  // 0600 before listen(): nobody can connect until then (unix(7): connecting
  // needs write permission on the socket file).
  if (::chmod(path.c_str(), S_IRUSR | S_IWUSR) != 0) {
    const int err = errno;
    stop();
    throw Error("control socket " + path + ": chmod 0600: " + std::strerror(err));
  }
  a.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) {
    stop();
    throw Error("control socket " + path + ": " + ec.message());
  }
  accept();
}

void ControlServer::accept() { accept_next(shared_); }

void ControlServer::stop() noexcept {
  if (shared_->stopped) return;
  shared_->stopped = true;
  boost::system::error_code ec;
  shared_->acceptor.close(ec);
  shared_->retry.cancel();
  for (auto& w : shared_->sessions)
    if (auto s = w.lock()) s->close();
  shared_->sessions.clear();
  if (!path_.empty()) {
    std::error_code fec;
    std::filesystem::remove(path_, fec);
  }
}

}  // namespace gnssemu::daemon
