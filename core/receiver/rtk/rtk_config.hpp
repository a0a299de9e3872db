// SPDX-License-Identifier: Apache-2.0
#pragma once
// Settings of the receiver's differential stage (DGNSS, RTK float/fixed,
// moving baseline). Defaults: the ZED-F9P's documented ones where u-blox
// names them (CFG-NAVSPG-CONSTR_DGNSSTO, CFG-NAVSPG-INFIL_MINELEV), RTKLIB's
// defaults (manual 2.4.2, Table F.4-1) for the estimator's noise terms.
namespace gnssemu::receiver::rtk {

struct RtkConfig {
  /// Corrections older than this are not used at all (CFG-NAVSPG-CONSTR_DGNSSTO, default 60 s), s (> 0).
  double dgnss_timeout_s = 60.0;
  /// Carrier corrections older than this are not used (code still is), s (> 0; RTKLIB maxtdiff 30 s).
  double max_carrier_age_s = 30.0;
  double elevation_mask_rad = 10.0 * 3.14159265358979323846 / 180.0;  ///< CFG-NAVSPG-INFIL_MINELEV 10 deg
  /// Zenith code noise per receiver incl. multipath, m (RTKLIB eratio 100 x 0.003 m).
  double code_sigma_m = 0.3;
  /// Carrier noise per receiver, m: a + b / sin(el) (RTKLIB err[1], err[2]).
  double phase_sigma_a_m = 0.003;
  double phase_sigma_b_m = 0.003;
  /// Differential atmosphere per m of baseline (1-sigma, both code and carrier), m/m.
  double baseline_sigma_m_m = 1.0e-6;
  /// Growth of the correction error with its age, m/s (RTKLIB prn[5] 5e-12 s/s x c).
  double age_sigma_m_s = 1.5e-3;
  /// Rover position random walk besides the navigation velocity's uncertainty, m/sqrt(s).
  double pos_process_m_sqrt_s = 0.05;
  /// Ambiguity random walk, cycles/sqrt(s) (RTKLIB prn[0] 1e-4).
  double amb_process_cyc_sqrt_s = 1.0e-4;
  /// Integer ambiguities are searched and held (CFG-NAVHPG-DGNSSMODE 3, factory); false: float only (mode 2).
  bool fix_ambiguities = true;
  double ratio_threshold = 3.0;       ///< LAMBDA ratio test (RTKLIB default 3.0)
  int min_fix_ambiguities = 4;        ///< fewest double differences to fix
  /// Carrier lock before an ambiguity joins the integer search (half cycle resolved too), s.
  double min_lock_s = 6.0;
  /// A fix is re-validated every epoch; while float the search runs at most this often, s.
  double ar_interval_s = 1.0;
  /// While fixed, new ambiguities are searched for this often, s.
  double refix_interval_s = 10.0;
  /// Beyond this baseline the F9P warns "DGNSS baseline big" (IMF9 R08 §3.1.5.4), m.
  double warn_baseline_m = 50.0e3;
  /// Beyond this baseline no integer fix is tried (float only, counted), m. Ours:
  /// the atmosphere no longer cancels (RTKLIB's manual gives ~10-20 km for L1 fixes).
  double max_fix_baseline_m = 100.0e3;
  /// A moving-base rover holds its epochs this long for the base's epoch of
  /// the same time, then gives up on them (RELPOSNED refObsMiss), s. Ours:
  /// u-blox names no limit for the F9P; the M8P's moving base propagated past
  /// 700 ms and dropped out of float/fixed past 3 s (C94-M8P user guide
  /// UBX-15031066 R07 §4.3.5).
  double moving_base_max_age_s = 1.0;
};

}  // namespace gnssemu::receiver::rtk
