// SPDX-License-Identifier: Apache-2.0
#pragma once
// Interference at the antenna: the jammer's power, its effect on each
// satellite's C/N0 and on the front end's noise floor.
//
// Effective C/N0 (Kaplan & Hegarty, Understanding GPS/GNSS, 2nd ed.,
// §6.10.1, eq. 6.61; Betz, "Effect of partial-band interference on receiver
// estimation of C/N0", ION NTM 2001, for the spectral separation view):
//   (C/N0)eff^-1 = (C/N0)^-1 + (J/S) / (Q Rc)
// Rc = 1.023 Mchip/s; Q = 1 narrowband / CW (worst case on a C/A line),
// 1.5 matched-spectrum (BPSK(1)), 2 wideband Gaussian noise. Written as
// noise densities: the jammer adds I0 = J / (Q Rc) to N0.
#include "core/common/constants.hpp"
#include "core/faults/fault_event.hpp"

namespace gnssemu::faults {

/// Minimum received L1 C/A power of IS-GPS-200 (-128.5 dBm = -158.5 dBW):
/// the S of a js_db given at the antenna.
inline constexpr double kNominalSignal_dbw = -158.5;
/// Front-end bandwidth whose total power the AGC levels (a 2 MHz C/A front
/// end), Hz.
inline constexpr double kFrontEndBandwidth_hz = 2.0e6;

/// Q of the interference relation for a jammer kind (dimensionless).
double spectral_factor(JammerKind kind) noexcept;

/// Jammer power at the antenna output, dBW, from EIRP (dBW), distance (m,
/// > 0, free-space loss at freq_hz, Hz > 0) and receive gain toward it (dBi).
double jammer_power_dbw(double eirp_dbw, double distance_m, double gain_dbi, double freq_hz = kL1Freq_hz) noexcept;

/// A jammer's spectrum: centre and full width, Hz (width 0: a line).
struct JammerBand {
  double centre_hz = kL1Freq_hz;
  double width_hz = 0.0;
};
/// A satellite signal's main lobe: its carrier and half width, Hz (> 0).
struct SignalBand {
  double centre_hz = kL1Freq_hz;
  double half_width_hz = kCaChipRate_hz;
};

/// Width of the default band of a jammer kind, Hz: wideband noise as wide as
/// the C/A main lobe (2 x 1.023 MHz, which makes Q = 2 of the relation
/// above), narrowband and CW a line.
double default_jammer_width_hz(JammerKind kind) noexcept;

/// Fraction of a jammer's power inside a signal's main lobe, [0, 1]: the
/// overlap of the two bands over the jammer's width (a flat spectrum); a
/// line counts whole inside the lobe (edges included), nothing outside.
double band_overlap_fraction(const JammerBand& j, const SignalBand& s) noexcept;

/// Interference density I0 one jammer of power j_w (W, >= 0) puts into the
/// correlator of a signal, W/Hz. Narrowband and CW: the power inside the
/// lobe over Q w (w the half width: for a BPSK signal its chip rate, so a
/// C/A signal gets the J / (Q Rc) above). Wideband: its density J / B
/// averaged over the lobe, (J / B) overlap / (2 w) (for B = 2 Rc over a C/A
/// lobe: J / (2 Rc), the Q = 2 above). A jammer clear of the lobe: 0.
double interference_density_w_hz(double j_w, JammerKind kind, const JammerBand& j, const SignalBand& s) noexcept;

/// Interference noise density I0 = J / (Q Rc), W/Hz, for J in W (>= 0).
double interference_density_w_hz_of_w(double j_w, JammerKind kind) noexcept;
/// The same for J in dBW.
double interference_density_w_hz(double j_dbw, JammerKind kind) noexcept;

/// C/N0 after interference: c/n0 (dB-Hz) with the thermal floor n0 (dBW/Hz)
/// raised by i0 (W/Hz). The relation above, exactly.
double effective_cn0_dbhz(double cn0_dbhz, double n0_dbw_hz, double i0_w_hz) noexcept;

/// Rise of the total in-band power the AGC sees, dB, for in-band
/// interference power j_w (W) over the floor n0 (dBW/Hz) across the front end.
double agc_rise_db(double j_w, double n0_dbw_hz) noexcept;

}  // namespace gnssemu::faults
