// SPDX-License-Identifier: Apache-2.0
#pragma once
// ReceiverConfig: what the emulated receiver itself is set to: its mask,
// channels, tracking thresholds and its own solver with its broadcast
// corrections (DESIGN.md §1, steps 7-9). It knows nothing of the world's
// models. All values SI.
#include <array>
#include <optional>

#include "core/atmosphere/receiver_corrections.hpp"
#include "core/common/constants.hpp"
#include "core/common/gnss_signals.hpp"
#include "core/common/range.hpp"
#include "core/common/sat_id.hpp"
#include "core/common/violation.hpp"
#include "core/receiver/tracking/acquisition.hpp"
#include "core/receiver/solution/nav_filter.hpp"
#include "core/receiver/tracking/spoof_monitor.hpp"
#include "core/signal/tracking.hpp"

namespace gnssemu::receiver {

/// Variance model of a pseudorange in the solver's weights (1 / sigma^2);
/// formulas in weight_model.hpp and docs/models.md.
enum class WeightModel {
  /// a^2 + b^2 / sin^2(el) + c^2 10^(-C/N0 / 10): elevation as RTKLIB's
  /// form, C/N0 as Kuusniemi et al. 2004 (the default).
  kElevationCn0,
  /// RTKLIB rnx2rtkp single point (pntpos varerr + rescode): a^2 + b^2 /
  /// sin(el) + the broadcast URA's variance + code_bias_sigma_m^2.
  kRtklib,
};

/// What the receiver's own solver assumes (it does not know the world model).
struct SolverConfig {
  WeightModel weights = WeightModel::kElevationCn0;
  /// Pseudorange 1-sigma model sigma^2 = a^2 + b^2 / sin^2(el) (kRtklib:
  /// b^2 / sin(el)), m.
  double sigma_a_m = 1.2;
  double sigma_b_m = 0.3;
  /// C/N0 term: sigma^2 += c^2 10^(-C/N0 / 10), m sqrt(Hz) (Kuusniemi et al.
  /// 2004); 0 = elevation-only weights. kElevationCn0 only.
  double sigma_c_m_sqrt_hz = 150.0;
  /// kRtklib: 1-sigma of the receiver's unknown code bias (RTKLIB's
  /// ERR_CBIAS 0.3 m), m (>= 0).
  double code_bias_sigma_m = 0.3;
  /// What the receiver's own corrections may miss, added to sigma^2 when the
  /// correction is on (RTKLIB's ERR_BRDCI and ERR_SAAS): (f I_klobuchar)^2
  /// and (s / (sin el + 0.1))^2. f: fraction of the Klobuchar delay (>= 0);
  /// s: zenith troposphere model sigma, m (>= 0); 0 leaves the term out.
  double iono_model_fraction = 0.0;
  double tropo_model_sigma_m = 0.0;
  /// The receiver's own propagation corrections (DESIGN.md §1, step 8).
  atmosphere::IonoCorrection iono = atmosphere::IonoCorrection::kKlobuchar;
  atmosphere::TropoCorrection tropo = atmosphere::TropoCorrection::kSaastamoinenNiell;
  double sigma_range_rate_m_s = 0.05;  ///< Doppler range-rate 1-sigma, m/s
  double height_hold_sigma_m = 1.0;    ///< 1-sigma of the held height in 2D fixes, m
  /// False-alarm probability of the chi-square test on post-fit residuals
  /// (fails -> the worst satellite is excluded and the epoch re-solved while
  /// >= 5 remain, else no fix; docs/models.md); 0 disables the test.
  double residual_test_pfa = 1.0e-3;
  /// Satellites fault exclusion may remove in one epoch before the epoch is
  /// given up: 1 is RAIM's single-fault assumption (RTCA DO-229, RTKLIB
  /// raim_fde); more lets a canyon with several NLOS satellites keep a fix,
  /// and lets a storm that biases every satellite keep a wrong one. 0: none.
  int max_exclusions = 1;
  int max_iterations = 15;             ///< Gauss–Newton iterations at most
  /// Per-system factor on the elevation part of the pseudorange sigma (index
  /// GnssSystem), RTKLIB's EFACT_* (rtklib.h 2.4.3: GPS, Galileo, BeiDou, QZSS
  /// 1.0, GLONASS 1.5 for its wider FDMA code chips and inter-channel biases,
  /// SBAS 3.0), dimensionless (> 0).
  std::array<double, kNumSystems> system_sigma_factor{1.0, 1.5, 1.0, 1.0, 1.0, 3.0};
  /// QZSS gets its own inter-system bias state (true), or shares the GPS
  /// clock as RTKLIB's pntpos does (QZSST is steered to GPST).
  bool qzss_own_clock = true;
};

/// Valid values of SolverConfig's numbers (besides: check_weights). A
/// residual test false-alarm probability of 0.5 or more puts the chi-square
/// threshold below the median: a test that fails more often than not cannot detect.
struct SolverRanges {
  static constexpr Range sigma_a_m{0.0, 100.0, "m"};
  static constexpr Range sigma_b_m{0.0, 100.0, "m"};
  static constexpr Range sigma_c_m_sqrt_hz{0.0, 10000.0, "m sqrt(Hz)"};
  static constexpr Range code_bias_sigma_m{0.0, 100.0, "m"};
  static constexpr Range iono_model_fraction{0.0, 10.0, ""};
  static constexpr Range tropo_model_sigma_m{0.0, 100.0, "m"};
  static constexpr Range sigma_range_rate_m_s{0.0, 10.0, "m/s", true};
  static constexpr Range height_hold_sigma_m{0.0, 1000.0, "m", true};
  static constexpr Range residual_test_pfa{0.0, 0.5, "", false, true};
  static constexpr Range max_exclusions{0.0, kMaxSatsInView, ""};  ///< integer
  static constexpr Range max_iterations{1.0, 100.0, ""};  ///< integer
};

/// The weights need a or b: sigma_a_m and sigma_b_m not both 0.
std::optional<Violation> check_weights(const SolverConfig& s);

/// Throws gnssemu::Error for an invalid solver config (SolverRanges, check_weights).
void validate(const SolverConfig& s);

/// RTKLIB rnx2rtkp 2.4.3 single-point settings (pntpos.c, default
/// prcopt_t; docs/validation.md "Our single-point solution against
/// RTKLIB"): kRtklib weights with a = b = 0.3 m (err = 100 x 0.003 m),
/// code bias 0.3 m, broadcast-iono variance (0.5 I)^2 and Saastamoinen
/// variance (0.3 / (sin el + 0.1))^2; Klobuchar and Saastamoinen with the
/// 1/cos z mapping; chi-square test at 1e-3 without fault exclusion (RTKLIB's
/// RAIM FDE is off by default); at most 10 iterations (MAXITR); QZSS on the
/// GPS clock. The rest of base is kept.
SolverConfig rtklib_single_point(SolverConfig base = {}) noexcept;

/// Operational limits of the receiver (export-control limits of a u-blox M8,
/// MAX-M8 data sheet UBX-15031506: altitude 50 000 m, velocity 500 m/s):
/// beyond either there is no fix.
struct OperationalLimits {
  double max_altitude_m = 50000.0;  ///< height above mean sea level, m
  double max_speed_m_s = 500.0;     ///< 3D speed, m/s
};

/// Valid values of OperationalLimits' fields.
struct OperationalLimitRanges {
  static constexpr Range max_altitude_m{0.0, 1.0e7, "m", true};
  static constexpr Range max_speed_m_s{0.0, 1.0e5, "m/s", true};
};

struct ReceiverConfig {
  double elevation_mask_rad = 5.0 * kDegToRad;  ///< [0, pi/2)
  double max_pdop = 20.0;          ///< above this the fix is reported as none
  int max_channels = 32;           ///< satellites tracked at most (highest first; CFG-GNSS numTrkChHw of the M8 and M9)
  signal::TrackingThresholds tracking;  ///< acquire 30 / lose 25 dB-Hz
  SolverConfig solver;
  AcquisitionConfig acquisition;   ///< search, reacquisition, ephemeris download, start mode
  NavFilterConfig filter;          ///< carrier smoothing, Kalman filter, dynamic model, static hold
  OperationalLimits limits;
  SpoofDetectionConfig spoof_detection;  ///< NAV-STATUS spoofDetState criteria
  /// Signals tracked per satellite (1 or 2): 1 the L1-band signal; 2 also
  /// each system's second signal (gnss_signals.hpp band 1) in the raw
  /// measurements. The position solution uses the L1-band signal either way.
  int bands = 1;
  /// SBAS corrections (u-blox CFG-SBAS usage diffCorr, factory on): applied
  /// to the systems SBAS L1 corrects once a GEO of the service covering the
  /// receiver is decoded long enough (sbas_reception.hpp); the fix is then
  /// differential. false: SBAS GEOs are tracked (and ranged) only.
  bool sbas = true;
};

/// Valid values of ReceiverConfig's own numbers (the mask in degrees, as
/// configured; max_channels an integer of at least 4, the satellites of a
/// 3D fix, and at most one channel per satellite in view).
struct ReceiverRanges {
  static constexpr Range elevation_mask_deg{0.0, 90.0, "deg", false, true};
  static constexpr Range max_pdop{1.0, 1000.0, ""};
  static constexpr Range max_channels{4.0, kMaxSatsInView, ""};
  static constexpr Range bands{1.0, kNumBands, ""};  ///< integer
};

/// Throws gnssemu::Error for a value out of its range anywhere in c.
void validate(const ReceiverConfig& c);

}  // namespace gnssemu::receiver
