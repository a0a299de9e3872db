// SPDX-License-Identifier: Apache-2.0
#pragma once
// The reference station of a [base]: a static receiver (make_pipeline with
// the base's settings and seed) at the base's position, its RawEpoch encoded
// as the configured RTCM 3 messages on their intervals. What gnssemud sends
// to the base's ports and NTRIP clients, and `gnssemu base` writes to a file.
#include <memory>
#include <string>

#include "config/config.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/protocol/rtcm/rtcm_msm.hpp"
#include "core/protocol/rtcm/rtcm_station.hpp"
#include "core/world/sky/shared_sky.hpp"

namespace gnssemu::config {

/// What the base sent so far.
struct BaseStats {
  std::uint64_t epochs = 0;
  std::uint64_t messages = 0;
  std::uint64_t bytes = 0;
  std::uint64_t dropped_cells = 0;  ///< MSM signals that did not fit their fields
};

class BaseStation {
public:
  /// c: the whole configuration (c.base set); store and scene must outlive
  /// the station. Setup only (allocates); throws gnssemu::Error on an
  /// invalid setting.
  BaseStation(const Config& c, const orbit::EphemerisStore& store, const pipeline::Broadcast& broadcast,
              const scene::Scene* scene);
  ~BaseStation();

  /// The base's epochs are the multiples of 1/rate_hz s of GPS week.
  double rate_hz() const noexcept { return base_.settings.rate_hz; }
  /// t lies on the base's epoch grid.
  bool is_epoch(const time::GpsTime& t) const noexcept;

  /// Steps the base's receiver at t and appends the messages due at t (MSMs,
  /// station, biases, ephemerides of the satellites it tracks). Never throws;
  /// no allocation once out has capacity.
  void step(const time::GpsTime& t, std::string& out) noexcept;
  /// The same on a sky shared with other receivers at sky.t().
  void step(const world::SharedSky& sky, std::string& out) noexcept;

  const receiver::RawEpoch& raw() const noexcept;
  const BaseConfig& config() const noexcept { return base_; }
  Ecef position_ecef_m() const noexcept { return pos_m_; }
  const BaseStats& stats() const noexcept { return stats_; }
  /// "1005(10),1077(1),..." for the sourcetable's format-details.
  std::string format_details() const;

private:
  void encode(const time::GpsTime& t, std::string& out) noexcept;
  static bool due(const time::GpsTime& t, double interval_s) noexcept;

  BaseConfig base_;
  const orbit::EphemerisStore& store_;
  Ecef pos_m_;
  std::unique_ptr<pipeline::Pipeline> rx_;
  protocol::rtcm::MsmEncoder msm_;
  SystemSet msm_systems_;
  double msm_interval_s_ = 0.0;  ///< 0: no MSMs
  protocol::rtcm::StationInfo station_;
  BaseStats stats_;
};

/// Parses a message list in str2str's -msg syntax, "1005(10),1077,1230(5)":
/// message numbers of kBaseMessageNumbers, each with an optional interval in
/// seconds (default 1). Throws gnssemu::Error("where: reason") on an unknown
/// number, a bad interval, a number twice, MSM4 and MSM7 mixed, or MSMs at
/// different intervals (one observation rate, as the F9P: rtk-raw.md §2.6).
std::vector<BaseMessage> parse_base_messages(std::string_view text, const std::string& where, int line);

/// The [base]'s checks that need the whole file: a base farther than
/// kBaseWarnDistance_m from the rover's origin gives a warning text (empty
/// when none).
std::string base_distance_warning(const Config& c);

}  // namespace gnssemu::config
