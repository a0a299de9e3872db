#include "core/receiver/receiver_config.hpp"

#include <cmath>
#include <string>

#include "core/common/error.hpp"

namespace gnssemu::receiver {

namespace {

void check(bool ok, const std::string& what) {
  if (!ok) throw Error("receiver config: " + what);
}

}  // namespace

void validate(const ReceiverConfig& c) {
  check(c.elevation_mask_rad >= 0.0 && c.elevation_mask_rad < kPi / 2.0,
        "elevation_mask_rad must be in [0, pi/2)");
  check(std::isfinite(c.max_pdop) && c.max_pdop > 0.0, "max_pdop must be > 0");
  check(c.max_channels >= 1 && c.max_channels <= kMaxGpsPrn, "max_channels must be in [1, 32]");
  const SolverConfig& s = c.solver;
  check(std::isfinite(s.sigma_a_m) && std::isfinite(s.sigma_b_m) && s.sigma_a_m >= 0.0 && s.sigma_b_m >= 0.0 &&
            s.sigma_a_m + s.sigma_b_m > 0.0,
        "solver.sigma_a_m / sigma_b_m must be >= 0 and not both 0");
  check(std::isfinite(s.sigma_range_rate_m_s) && s.sigma_range_rate_m_s > 0.0,
        "solver.sigma_range_rate_m_s must be > 0");
  check(std::isfinite(s.height_hold_sigma_m) && s.height_hold_sigma_m > 0.0,
        "solver.height_hold_sigma_m must be > 0");
  check(s.residual_test_pfa >= 0.0 && s.residual_test_pfa < 0.5, "solver.residual_test_pfa must be in [0, 0.5)");
  check(s.max_exclusions >= 0 && s.max_exclusions <= kMaxGpsPrn, "solver.max_exclusions must be in [0, 32]");
  check(s.max_iterations >= 1 && s.max_iterations <= 100, "solver.max_iterations must be in [1, 100]");
  check(std::isfinite(s.sigma_c_m_sqrt_hz) && s.sigma_c_m_sqrt_hz >= 0.0, "solver.sigma_c_m_sqrt_hz must be >= 0");
  signal::validate(c.tracking);
}

}  // namespace gnssemu::receiver
