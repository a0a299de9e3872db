// SPDX-License-Identifier: Apache-2.0
#include "core/receiver/receiver_config.hpp"

#include <string>

#include "core/common/error.hpp"

namespace gnssemu::receiver {

namespace {

constexpr const char* kWhat = "receiver config";

}  // namespace

std::optional<Violation> check_weights(const SolverConfig& s) {
  if (s.sigma_a_m + s.sigma_b_m > 0.0) return std::nullopt;
  return Violation{"sigma_a_m", "sigma_b_m",
                   "sigma_a_m and sigma_b_m are both 0 (the solver's weights would be infinite)"};
}

void validate(const SolverConfig& s) {
  using R = SolverRanges;
  check_ranges(kWhat, {{s.sigma_a_m, R::sigma_a_m, "solver.sigma_a_m"}, {s.sigma_b_m, R::sigma_b_m, "solver.sigma_b_m"},
                       {s.sigma_c_m_sqrt_hz, R::sigma_c_m_sqrt_hz, "solver.sigma_c_m_sqrt_hz"},
                       {s.code_bias_sigma_m, R::code_bias_sigma_m, "solver.code_bias_sigma_m"},
                       {s.iono_model_fraction, R::iono_model_fraction, "solver.iono_model_fraction"},
                       {s.tropo_model_sigma_m, R::tropo_model_sigma_m, "solver.tropo_model_sigma_m"},
                       {s.sigma_range_rate_m_s, R::sigma_range_rate_m_s, "solver.sigma_range_rate_m_s"},
                       {s.height_hold_sigma_m, R::height_hold_sigma_m, "solver.height_hold_sigma_m"},
                       {s.residual_test_pfa, R::residual_test_pfa, "solver.residual_test_pfa"},
                       {static_cast<double>(s.max_exclusions), R::max_exclusions, "solver.max_exclusions"},
                       {static_cast<double>(s.max_iterations), R::max_iterations, "solver.max_iterations"}});
  if (const std::optional<Violation> v = check_weights(s)) throw Error(kWhat, 0, "solver: " + v->reason);
  for (std::size_t i = 0; i < s.system_sigma_factor.size(); ++i) {
    const double f = s.system_sigma_factor[i];
    if (!(f > 0.0 && f <= 100.0)) {
      throw Error(kWhat, 0, "solver: system_sigma_factor of " + std::string(system_name(static_cast<GnssSystem>(i))) +
                                " is not in (0, 100]");
    }
  }
}

SolverConfig rtklib_single_point(SolverConfig base) noexcept {
  base.weights = WeightModel::kRtklib;
  base.sigma_a_m = 0.3;  // err[0] x err[1] = 100 x 0.003 m
  base.sigma_b_m = 0.3;  // err[0] x err[2]
  base.sigma_c_m_sqrt_hz = 0.0;
  base.code_bias_sigma_m = 0.3;    // ERR_CBIAS
  base.iono_model_fraction = 0.5;  // ERR_BRDCI
  base.tropo_model_sigma_m = 0.3;  // ERR_SAAS
  base.iono = atmosphere::IonoCorrection::kKlobuchar;
  base.tropo = atmosphere::TropoCorrection::kSaastamoinenCosZ;
  base.residual_test_pfa = 1.0e-3;  // chisqr[] table at alpha 0.001
  base.max_exclusions = 0;
  base.max_iterations = 10;         // MAXITR
  base.qzss_own_clock = false;      // rescode: QZSS on x[3], the GPS clock
  // varerr (pntpos.c 2.4.3 b34) applies EFACT_GLO and EFACT_SBS; every other
  // system EFACT_GPS.
  base.system_sigma_factor = {1.0, 1.5, 1.0, 1.0, 1.0, 3.0};
  return base;
}

void validate(const ReceiverConfig& c) {
  using R = ReceiverRanges;
  check_ranges(kWhat, {{c.elevation_mask_rad * kRadToDeg, R::elevation_mask_deg, "elevation_mask_deg"},
                       {c.max_pdop, R::max_pdop, "max_pdop"},
                       {static_cast<double>(c.max_channels), R::max_channels, "max_channels"},
                       {static_cast<double>(c.bands), R::bands, "bands"}});
  signal::validate(c.tracking);
  validate(c.solver);
  validate(c.acquisition);
  validate(c.filter);
  check_ranges(kWhat, {{c.limits.max_altitude_m, OperationalLimitRanges::max_altitude_m, "limits.max_altitude_m"},
                       {c.limits.max_speed_m_s, OperationalLimitRanges::max_speed_m_s, "limits.max_speed_m_s"}});
  validate(c.spoof_detection);
}

}  // namespace gnssemu::receiver
