// SPDX-License-Identifier: Apache-2.0
#pragma once
// Counter-based random numbers: every draw is a pure function of
// (seed, stream, epoch index, purpose), so one satellite's noise never
// depends on which other satellites are visible, and no generator state is
// carried between epochs. Mixing: splitmix64 finaliser (Steele, Lea, Flood,
// "Fast splittable pseudorandom number generators", OOPSLA 2014).
#include <cmath>
#include <cstdint>

#include "core/common/constants.hpp"
#include "core/common/sat_id.hpp"

namespace gnssemu::world {

/// What a draw is for; part of the key so streams never collide.
enum class Purpose : uint64_t {
  kGaussMarkovInit = 1,
  kGaussMarkovStep = 2,
  kThermal = 3,
  kDoppler = 4,
  kClockDrift = 5,
  kIonoInit = 6,   ///< vertical TEC perturbation per line of sight
  kIonoStep = 7,
  kTropoInit = 8,  ///< zenith wet delay perturbation (stream kClockStream)
  kTropoStep = 9,
  kMultipathInit = 10,  ///< unit multipath process per satellite
  kMultipathStep = 11,
  kGradientInit = 12,   ///< azimuthal gradient, streams kGradientStream + 0 (N) / 1 (E)
  kGradientStep = 13,
  kIonoScaleInit = 14,  ///< common relative ionospheric error, stream kIonoScaleStream
  kIonoScaleStep = 15,
  kCarrierNoise = 16,      ///< carrier phase jitter per satellite
  kCycleSlip = 17,         ///< slip draw per satellite (uniform) and its size
  kCarrierAmbiguity = 18,  ///< integer ambiguity of a new carrier lock
  kAcquisition = 19,       ///< the receiver's search times (streams kAcquisitionStream + sat_stream)
  kSkyInit = 20,           ///< shared sky processes (sky_errors.hpp): stationary start at a coarse node
  kSkyCoarse = 21,         ///< coarse node step
  kSkyFine = 22,           ///< fine node of the bridge between two coarse nodes
  kSbasOrbitClockInit = 23,  ///< residual of an SBAS's orbit/clock correction per satellite
  kSbasOrbitClockStep = 24,
  kSbasIonoInit = 25,        ///< residual of an SBAS's ionospheric correction per satellite
  kSbasIonoStep = 26,
  kRelockAmbiguity = 27,     ///< the receiver's ambiguity of a re-acquired carrier (streams kAcquisitionStream + band_stream)
  kLockHalfCycle = 28,       ///< the sign a Costas loop locks on at a new carrier lock (half a cycle or none)
  kRelockHalfCycle = 29,     ///< the same for the receiver's re-acquired carrier (streams kAcquisitionStream + band_stream)
};

/// Random stream of a satellite: (system << 8) | RINEX number. GPS is system
/// 0, so a GPS satellite's stream is its PRN (1..32) and GPS runs keep their
/// draws; every other system's streams lie at 256 and above (numbers < 256),
/// clear of the receiver's own streams below.
constexpr uint64_t sat_stream(SatId sat) noexcept {
  return (static_cast<uint64_t>(sat.system) << 8) | static_cast<uint64_t>(sat.number);
}

/// Random stream of sat's signal on band (0: sat_stream, which the L1-band
/// signal has always drawn from; band 1 in bit 20 and up, clear of every
/// other stream).
constexpr uint64_t band_stream(SatId sat, int band) noexcept {
  return sat_stream(sat) | (static_cast<uint64_t>(band) << 20);
}

/// Stream id of the receiver clock (0: no satellite has number 0).
inline constexpr uint64_t kClockStream = 0;
/// First stream of the two azimuthal-gradient processes: 33 and 34, above
/// every GPS number and below the first stream of another system.
inline constexpr uint64_t kGradientStream = 33;
/// Stream of the common relative ionospheric error (after the gradients).
inline constexpr uint64_t kIonoScaleStream = 35;
static_assert(kIonoScaleStream < sat_stream(SatId(GnssSystem::kGlonass, 0)));

/// Streams of the receiver's acquisition draws: this + sat_stream(sat) (a
/// purpose of their own, so they cannot meet the world's draws).
inline constexpr uint64_t kAcquisitionStream = 100;

class CounterRng {
public:
  explicit constexpr CounterRng(uint64_t seed) noexcept : seed_(seed) {}

  static constexpr uint64_t mix(uint64_t z) noexcept {
    z += 0x9E3779B97F4A7C15ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }

  /// 64 random bits for a key; each component is folded in through a full mix.
  constexpr uint64_t bits(uint64_t stream, uint64_t epoch, Purpose purpose, uint64_t k) const noexcept {
    uint64_t h = mix(seed_);
    h = mix(h ^ stream);
    h = mix(h ^ epoch);
    h = mix(h ^ static_cast<uint64_t>(purpose));
    return mix(h ^ k);
  }

  /// Uniform in (0, 1]; never 0 so log() is finite.
  double uniform(uint64_t stream, uint64_t epoch, Purpose purpose, uint64_t k) const noexcept {
    return (static_cast<double>(bits(stream, epoch, purpose, k) >> 11) + 1.0) * 0x1.0p-53;
  }

  /// Standard normal (Box–Muller, one of the pair).
  double normal(uint64_t stream, uint64_t epoch, Purpose purpose) const noexcept {
    const double u1 = uniform(stream, epoch, purpose, 0);
    const double u2 = uniform(stream, epoch, purpose, 1);
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
  }

private:
  uint64_t seed_;
};

}  // namespace gnssemu::world
