// SPDX-License-Identifier: Apache-2.0
// Device: RTCM 3 input on a port (ubx_rtcm_input.hpp).
#include "core/protocol/ubx/device/ubx_device.hpp"
#include "core/protocol/ubx/config/ubx_hpg.hpp"

namespace gnssemu::protocol::ubx {

InputResult Device::handle_rtcm(Link at, std::span<const std::uint8_t> payload, bool crc_ok, std::string& out) {
  InputResult r;
  if (!valid(at) || (current_.port(column(at)).in_proto_mask & proto::kRtcm3) == 0) {
    rtcm_.count_ignored();
    ++stats_.ignored;
    return r;
  }
  const bool lost = rtcm_.outage();
  const std::uint32_t revision = rtcm_.corrections().revision;
  const rtcm::DecodeResult res = rtcm_.take(payload, crc_ok);
  r.corrections_changed = rtcm_.corrections().revision != revision;
  // A lost frame never reached the chip: nothing to report.
  if (lost || !current_.port(column(at)).outputs_ubx()) return r;
  if (message_rate(at, msg::kRxmRtcm) != 0) {
    r.bytes += rxm_rtcm(res, !crc_ok, out);
    r.label = "RXM-RTCM";
  }
  // The F9P reports every correction message in RXM-COR as well (protocol 27.30+).
  if (message_rate(at, msg::kRxmCor) != 0) {
    r.bytes += rxm_cor_rtcm(static_cast<std::uint16_t>(res.message), static_cast<std::uint16_t>(res.subtype), crc_ok,
                            res.used, out);
    if (r.label.empty()) r.label = "RXM-COR";
  }
  return r;
}

}  // namespace gnssemu::protocol::ubx
