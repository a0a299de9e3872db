// SPDX-License-Identifier: Apache-2.0
#pragma once
// Receiver profiles: the error model of the world and the emulated
// receiver's antenna and code loop for one kind of device, each with its
// evidence (docs/models.md, "Receiver profiles"; docs/validation.md, "An
// error model that holds on unseen stations").
// - kGeodetic reproduces the IGS-class station receivers of ../shared/data
//   (Trimble NetR9, Septentrio PolaRx2/5 with choke-ring antennas): the
//   pooled `gnssemu calibrate` fit of all five station-days, checked by
//   leaving each station out.
// - kUbloxM8 is the device the emulator claims to be, a u-blox M8 with a
//   patch antenna: the same signals in space (orbit/clock, ionosphere,
//   gradient: they are the sky's, not the receiver's), the C/N0 levels of
//   the u-blox NEO-M8N log and a code loop whose noise matches the
//   pseudorange sigma a NEO-M8T reports (RXM-RAWX prStdev).
#include <string_view>

#include "core/pipeline/pipeline.hpp"

namespace gnssemu::pipeline {

enum class ReceiverProfile {
  kUbloxM8,   ///< u-blox M8 with a patch antenna
  kGeodetic,  ///< geodetic receiver with a choke-ring antenna
};

/// "ublox_m8" or "geodetic"; throws gnssemu::Error naming both otherwise.
ReceiverProfile receiver_profile(std::string_view name);
/// The profile's name as receiver_profile reads it.
std::string_view profile_name(ReceiverProfile p) noexcept;

/// base with the profile's world error model, antenna and code loop, and
/// for kGeodetic the snapshot solution (filter none, as station receivers'
/// single-point positions are compared). The
/// mean azimuthal gradient was fitted at 36-79 deg N, where it points to
/// the equator; south of it the sign is mirrored (lat_rad < 0), an
/// assumption no data here can check. Everything else in base is kept.
PipelineConfig apply_profile(PipelineConfig base, ReceiverProfile p, double lat_rad);

}  // namespace gnssemu::pipeline
