// SPDX-License-Identifier: Apache-2.0
#pragma once
// A PortChannel test rig: a fake OutputPort that records what it is given,
// one emulated chip with a channel per output on a fake clock, and helpers
// that split the bytes a port carried into messages.
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "config/setup/device_setup.hpp"
#include "core/common/constants.hpp"
#include "core/protocol/ubx/wire/ubx_frame.hpp"
#include "core/protocol/ubx/wire/ubx_message_table.hpp"
#include "daemon/ports/port_channel.hpp"

namespace gnssemu::daemon::test {

namespace ubx = gnssemu::protocol::ubx;

inline std::string frame(ubx::MsgId id, std::vector<uint8_t> payload = {}) {
  std::string out;
  ubx::append_frame(out, id, payload);
  return out;
}

class FakePort final : public OutputPort {
public:
  explicit FakePort(const config::OutputPortConfig& c) : OutputPort(c) {}
  std::string describe() const override { return "fake"; }
  void set_baud_after_drain(uint32_t b) noexcept override { bauds.push_back(b); }
  uint32_t baud() const noexcept override { return bauds.empty() ? config_.baud : bauds.back(); }
  std::vector<std::string> epochs, replies;
  std::vector<uint32_t> bauds;

protected:
  void deliver(int, std::string_view data, std::span<const std::size_t>, bool epoch) noexcept override {
    (epoch ? epochs : replies).emplace_back(data);
  }
};

/// The messages of a byte stream in order: UBX frames with their ids, NMEA sentences.
struct Messages final : ubx::DecoderSink {
  std::vector<std::string> labels;
  std::vector<std::string> frames;  ///< whole UBX frames, "" for sentences
  void on_ubx(const ubx::FrameView& f) override {
    labels.emplace_back(ubx::message_label(f.id));
    frames.push_back(frame(f.id, {f.payload.begin(), f.payload.end()}));
  }
  void on_nmea(std::string_view s) override {
    labels.emplace_back(s.substr(3, 3));  // "$GPGGA" -> "GGA"
    frames.emplace_back();
  }
};

inline Messages split(std::string_view bytes) {
  Messages m;
  ubx::StreamDecoder d;
  d.feed(bytes, m);
  return m;
}

/// Label of the first message of bytes.
inline std::string message_label(std::string_view bytes) {
  const Messages m = split(bytes);
  return m.labels.empty() ? std::string() : m.labels.front();
}

inline receiver::Fix good_fix(double tow_s) {
  receiver::Fix f;
  f.t = time::GpsTime(2190, tow_s);
  f.time_valid = true;
  f.type = receiver::FixType::k3D;
  f.lla = {48.8738 * kDegToRad, 2.295 * kDegToRad, 100.0};
  f.num_used = 8;
  f.num_sats = 8;
  for (int i = 0; i < 8; ++i) {
    f.sats[static_cast<std::size_t>(i)] = {SatId::gps(i + 1), 0.5 * i, 0.3 + 0.1 * i, 40.0, true, true, true, true};
  }
  f.dop = {1.9, 1.6, 0.9, 1.3, 0.8};
  return f;
}

/// One device, one channel per port config, powered on at clock 100 s.
struct Rig {
  double now = 100.0;
  std::unique_ptr<ubx::Device> device;
  std::vector<FakePort*> ports;
  std::vector<std::unique_ptr<PortChannel>> channels;
  FakePort* port = nullptr;  ///< the first
  PortChannel* ch = nullptr;
  explicit Rig(const config::OutputPortConfig& c, double period_s = 1.0) : Rig(std::vector{c}, period_s) {}
  Rig(const std::vector<config::OutputPortConfig>& outputs, double period_s) {
    ubx::DeviceSetup setup;
    setup.nav_period_s = period_s;
    for (const auto& c : outputs) setup.outputs.push_back(config::output_setup(c));
    device = std::make_unique<ubx::Device>(setup);
    device->power_on(now);
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      auto p = std::make_unique<FakePort>(outputs[i]);
      ports.push_back(p.get());
      channels.push_back(std::make_unique<PortChannel>(std::move(p), *device, i, [this] { return now; }));
    }
    port = ports.front();
    ch = channels.front().get();
  }
  void input(const std::string& bytes, std::size_t output = 0) {
    channels[output]->on_port_input(0, {reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()});
  }
  /// One epoch: the device, then every channel.
  void on_epoch(const receiver::Fix& fix) {
    device->on_epoch(fix, now);
    for (const auto& c : channels) c->send_epoch();
  }
  std::vector<std::string> epoch(double tow_s) {
    port->epochs.clear();
    on_epoch(good_fix(tow_s));
    if (port->epochs.empty()) return {};
    return split(port->epochs.front()).labels;
  }
};

inline config::OutputPortConfig port_cfg(uint32_t baud = 0) {
  config::OutputPortConfig c;
  c.name = "t";
  c.transport = config::TcpPortConfig{"127.0.0.1", 0};
  c.baud = baud;
  return c;
}

}  // namespace gnssemu::daemon::test
