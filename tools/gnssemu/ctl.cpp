// SPDX-License-Identifier: Apache-2.0
#include "tools/gnssemu/ctl.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "config/control_config.hpp"
#include "tools/gnssemu/cli.hpp"

namespace gnssemu::cli {

namespace {

using Clock = std::chrono::steady_clock;

struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

// Milliseconds left until deadline (at least 0).
int left_ms(Clock::time_point deadline) {
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return ms > 0 ? static_cast<int>(ms) : 0;
}

// Send request (one line) and read one reply line; "" and why on failure.
std::string exchange(const std::string& path, const std::string& request, double timeout_s, std::string& why) {
  if (path.size() > config::kMaxSocketPathBytes) {
    why = path + ": longer than a Unix socket path can be";
    return {};
  }
  Fd s{::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0)};
  if (s.fd < 0) {
    why = std::string("socket: ") + std::strerror(errno);
    return {};
  }
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::memcpy(addr.sun_path, path.data(), path.size());
  if (::connect(s.fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    why = path + ": " + std::strerror(errno) + " (is gnssemud running with [control] socket = \"" + path + "\"?)";
    return {};
  }
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s));
  std::size_t sent = 0;
  while (sent < request.size()) {
    pollfd p{s.fd, POLLOUT, 0};
    if (::poll(&p, 1, left_ms(deadline)) <= 0) {
      why = path + ": the daemon did not take the request within " + std::to_string(timeout_s) + " s";
      return {};
    }
    const ssize_t n = ::send(s.fd, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EINTR || errno == EAGAIN) continue;
      why = path + ": " + std::strerror(errno);
      return {};
    }
    sent += static_cast<std::size_t>(n);
  }
  std::string reply;
  char buf[65536];
  for (;;) {
    const std::size_t nl = reply.find('\n');
    if (nl != std::string::npos) return reply.substr(0, nl);
    pollfd p{s.fd, POLLIN, 0};
    if (::poll(&p, 1, left_ms(deadline)) <= 0) {
      why = path + ": no reply within " + std::to_string(timeout_s) + " s";
      return {};
    }
    const ssize_t n = ::recv(s.fd, buf, sizeof buf, 0);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n <= 0) {
      why = path + ": the daemon closed the connection without a reply";
      return {};
    }
    reply.append(buf, static_cast<std::size_t>(n));
  }
}

}  // namespace

int run_ctl(const CtlArgs& a, std::ostream& out, std::ostream& err) {
  nlohmann::json req{{"cmd", a.command}};
  if (!a.receiver.empty() && a.vehicle.empty()) {
    err << "gnssemu ctl: --receiver needs --vehicle\n";
    return kExitBadInput;
  }
  if (!a.vehicle.empty()) req["target"] = a.receiver.empty() ? a.vehicle : a.vehicle + "/" + a.receiver;
  if (a.command == "inject") {
    std::ifstream f(a.file, std::ios::binary);
    if (!f) {
      err << "gnssemu ctl: " << a.file << ": cannot read\n";
      return kExitBadInput;
    }
    std::ostringstream text;
    text << f.rdbuf();
    req["scenario"] = text.str();
    req["source"] = a.file;  // the daemon's errors name file:line
  }
  std::string why;
  const std::string reply = exchange(a.socket, req.dump() + "\n", a.timeout_s, why);
  if (reply.empty()) {
    err << "gnssemu ctl: " << why << '\n';
    return kExitBadInput;
  }
  const nlohmann::json r = nlohmann::json::parse(reply, nullptr, false);
  if (r.is_discarded() || !r.is_object() || !r.contains("ok")) {
    err << "gnssemu ctl: not a control reply: " << reply.substr(0, 200) << '\n';
    return kExitBadInput;
  }
  out << reply << '\n';
  if (r["ok"] != true) {
    err << "gnssemu ctl: " << (r.contains("error") && r["error"].is_string() ? r["error"].get<std::string>() : reply) << '\n';
    return kExitBadInput;
  }
  return kExitOk;
}

}  // namespace gnssemu::cli
