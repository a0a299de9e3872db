// SPDX-License-Identifier: Apache-2.0
#include "core/world/sky/shared_sky.hpp"

#include <cmath>

#include "core/common/constants.hpp"

namespace gnssemu::world {

namespace {

// A satellite is evaluated when it is above sin(el) = -0.02 (about -1.1°)
// for some antenna: light time moves a satellite by < 400 m (< 0.01° at
// GNSS ranges) and the ellipsoid normal used below is the geodetic up to
// ~1e-4 rad at aircraft heights, so nothing that rises above 0° this epoch
// is culled.
constexpr double kCullSinEl = -0.02;
// A culled satellite's evaluation serves the horizon test for this long,
// plus up to 63 s spread over the satellites so that refreshes do not all
// fall on one epoch (GPS: jerk dt^3 / 6 < 40 m at 124 s, < 2e-6 rad).
constexpr double kCullReuse_s = 60.0;
// 1 / (1 - e^2) of WGS 84: (x, y, z / (1 - e^2)) is the ellipsoid's normal
// at a point on it.
constexpr double kNormalZScale = 1.0 / ((1.0 - kWgs84F) * (1.0 - kWgs84F));

bool any_above(const Ecef& pos_m, std::span<const Ecef> antennas_m) noexcept {
  for (const Ecef& a : antennas_m) {
    const Vec3 n(a.x, a.y, a.z * kNormalZScale);
    const double r2 = n.dot(n);
    if (!(r2 > 0.0) || !std::isfinite(r2)) continue;
    const Vec3 d = pos_m - a;
    const double up = d.dot(n);
    if (up >= 0.0 || up * up < kCullSinEl * kCullSinEl * d.dot(d) * r2) return true;
  }
  return false;
}

}  // namespace

orbit::SatState taylor_state(const SkyState& s, double dt_s) noexcept {
  orbit::SatState o;
  o.pos_m = Ecef(s.pos_m + s.vel_m_s * dt_s + s.acc_m_s2 * (0.5 * dt_s * dt_s));
  o.vel_m_s = Ecef(s.vel_m_s + s.acc_m_s2 * dt_s);
  o.clk_bias_s = s.clk_bias_s + s.clk_drift_s_s * dt_s;
  o.clk_drift_s_s = s.clk_drift_s_s;
  return o;
}

SharedSky::SharedSky(const orbit::EphemerisStore& store, SystemSet systems, const SkyErrorsConfig& errors) noexcept
    : store_(store), systems_(systems), errors_(errors) {}

void SharedSky::rebuild() noexcept {
  n_sats_ = 0;
  for (int i = 0; i < kNumSats; ++i) {
    const SatId sat = SatId::from_index(i);
    if (systems_.has(sat.system) && store_.count(sat) > 0) sats_[static_cast<std::size_t>(n_sats_++)] = sat;
  }
  // Sets of a replaced store may sit at the addresses of the old ones.
  state_.fill(SkyState{});
  glonass_.fill(orbit::GlonassNode{});
  node_a_.fill(Node{});
  node_b_.fill(Node{});
  selected_from_.fill(time::GpsTime{});
  selected_until_.fill(time::GpsTime{});  // empty spans: select again
  fingerprint_ = store_.fingerprint();
  built_ = true;
  ++revision_;
}

SharedSky::Node SharedSky::evaluate(SatId sat, const orbit::Ephemeris& eph, const time::GpsTime& t) noexcept {
  const orbit::SatState st = orbit::sat_state(eph, t, glonass_[static_cast<std::size_t>(sat.index())]);
  Node n;
  n.eph = &eph;
  n.toe = eph.toe;
  n.t = t;
  n.pos_m = st.pos_m;
  n.vel_m_s = st.vel_m_s;
  n.acc_m_s2 = orbit::ecef_acceleration_m_s2(eph, st.pos_m, st.vel_m_s);
  n.clk_bias_s = st.clk_bias_s;
  n.clk_drift_s_s = st.clk_drift_s_s;
  ++evaluations_;
  return n;
}

void SharedSky::interpolate(SatId sat, const orbit::Ephemeris& eph, const time::GpsTime& t,
                            const time::GpsTime& ta) noexcept {
  const std::size_t k = static_cast<std::size_t>(sat.index());
  Node& a = node_a_[k];
  Node& b = node_b_[k];
  if (!a.of(eph, ta)) {
    a = b.of(eph, ta) ? b : evaluate(sat, eph, ta);
    b = evaluate(sat, eph, ta + kSkyNodeSpacing_s);
  }
  // Cubic Hermite on [a.t, b.t] in s = (t - a.t) / H; the acceleration
  // (the force model's, for the Taylor steps) linear between the nodes.
  constexpr double h = kSkyNodeSpacing_s;
  const double u = (t - ta) / h, u2 = u * u, u3 = u2 * u;
  const double h00 = 2.0 * u3 - 3.0 * u2 + 1.0, h10 = (u3 - 2.0 * u2 + u) * h, h01 = 3.0 * u2 - 2.0 * u3,
               h11 = (u3 - u2) * h;
  const double d00 = (6.0 * u2 - 6.0 * u) / h, d10 = 3.0 * u2 - 4.0 * u + 1.0, d11 = 3.0 * u2 - 2.0 * u;
  SkyState& s = state_[k];
  s.eph = &eph;
  s.t = t;
  s.pos_m = Ecef(a.pos_m * h00 + a.vel_m_s * h10 + b.pos_m * h01 + b.vel_m_s * h11);
  s.vel_m_s = Ecef((a.pos_m - b.pos_m) * d00 + a.vel_m_s * d10 + b.vel_m_s * d11);
  s.acc_m_s2 = Ecef(a.acc_m_s2 + (b.acc_m_s2 - a.acc_m_s2) * u);
  s.clk_bias_s = a.clk_bias_s * h00 + a.clk_drift_s_s * h10 + b.clk_bias_s * h01 + b.clk_drift_s_s * h11;
  s.clk_drift_s_s = (a.clk_bias_s - b.clk_bias_s) * d00 + a.clk_drift_s_s * d10 + b.clk_drift_s_s * d11;
  s.current = true;
}

void SharedSky::update(const time::GpsTime& t, std::span<const Ecef> antennas_m, SystemSet needed) noexcept {
  if (!built_ || store_.fingerprint() != fingerprint_) rebuild();
  t_ = t;
  errors_.begin(t, sats(), revision_);
  const time::GpsTime node = t - std::fmod(t.tow_s(), kSkyNodeSpacing_s);
  for (int i = 0; i < n_sats_; ++i) {
    const SatId sat = sats_[static_cast<std::size_t>(i)];
    const std::size_t k = static_cast<std::size_t>(sat.index());
    SkyState& s = state_[k];
    if (!needed.has(sat.system)) {
      s.current = false;
      continue;
    }
    if (!(t >= selected_from_[k] && t < selected_until_[k])) {
      selected_[k] = store_.select(sat, t, selected_until_[k]);
      selected_from_[k] = t;
    }
    const orbit::Ephemeris* eph = selected_[k];
    if (eph == nullptr) {
      s.eph = nullptr;
      s.current = false;
      continue;
    }
    // node_a_ holds the set state_ was last interpolated from (its toe tells
    // a set replaced at the same address).
    if (!antennas_m.empty() && s.eph == eph && node_a_[k].toe == eph->toe) {
      const double age_s = t - s.t;
      if (std::fabs(age_s) <= kCullReuse_s + static_cast<double>(i % 64) &&
          !any_above(taylor_state(s, age_s).pos_m, antennas_m)) {
        s.current = false;
        continue;
      }
    }
    interpolate(sat, *eph, t, node);
    errors_.step(sat);
  }
}

orbit::SatState SharedSky::state_at(const orbit::Ephemeris& eph, const time::GpsTime& t_eval) const noexcept {
  if (eph.sat.valid()) {
    const SkyState& s = state_[static_cast<std::size_t>(eph.sat.index())];
    const double dt_s = t_eval - s.t;
    if (s.current && s.eph == &eph && std::fabs(dt_s) <= kMaxTaylorStep_s) return taylor_state(s, dt_s);
  }
  return orbit::sat_state(eph, t_eval);
}

}  // namespace gnssemu::world
