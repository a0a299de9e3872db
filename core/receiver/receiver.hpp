#pragma once
// Receiver: one GNSS receiver. step() turns vehicle truth at an epoch into
// the Fix a real receiver would report. Pure and deterministic for a seed;
// no exceptions and no allocation on step() after construction.
#include "core/common/vec3.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/receiver/fix.hpp"
#include "core/receiver/receiver_config.hpp"

namespace gnssemu::receiver {

/// Vehicle truth at the antenna, at time t.
struct Truth {
  time::GpsTime t;
  Ecef pos_m;       ///< antenna position, ECEF m
  Ecef vel_m_s;     ///< antenna velocity, ECEF m/s
  bool valid = false;  ///< false: no truth (antenna lost) -> no fix
};

class Receiver {
public:
  /// store must outlive the receiver. Throws gnssemu::Error on an invalid config.
  Receiver(const orbit::EphemerisStore& store, const ReceiverConfig& config);

  /// Run one epoch at receive time t (GPS). truth.valid == false gives a
  /// no-fix epoch (time still advances, satellites drop out).
  const Fix& step(const time::GpsTime& t, const Truth& truth) noexcept;

  const Fix& last_fix() const noexcept { return fix_; }
  const ReceiverConfig& config() const noexcept { return config_; }

private:
  struct Impl;
  // Implementation detail owned by the receiver module.
  const orbit::EphemerisStore& store_;
  ReceiverConfig config_;
  Fix fix_;
};

}  // namespace gnssemu::receiver
