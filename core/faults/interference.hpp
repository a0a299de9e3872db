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
/// > 0, free-space loss at L1) and receive gain toward it (dBi).
double jammer_power_dbw(double eirp_dbw, double distance_m, double gain_dbi) noexcept;

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
