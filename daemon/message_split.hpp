#pragma once
// Message boundaries in an output byte stream of UBX frames and NMEA
// sentences (what encoders produce). Pure.
#include <cstddef>
#include <string_view>

namespace gnssemu::daemon {

/// Length of the message at the start of data: a UBX frame (header length
/// + 8) or an NMEA sentence up to and including LF. Anything else runs to
/// the next UBX sync or '$'. Never more than data.size(); 0 only for empty data.
std::size_t message_length(std::string_view data) noexcept;

/// Name of the message at the start of data for logs: "NAV-PVT", "GGA",
/// "UBX-0A-04"; views into a static table or into data.
std::string_view message_label(std::string_view data) noexcept;

}  // namespace gnssemu::daemon
