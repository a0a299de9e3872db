// SPDX-License-Identifier: Apache-2.0
// The world's carrier phase and Doppler as the receiver receives them:
// consistent with the range, the ionosphere advancing the phase, continuity
// broken by new locks, LOS/NLOS switches and jumps of the truth, carrier
// multipath of millimetres where the code's is metres.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/geo/geodesy.hpp"
#include "core/orbit/ephemeris_store.hpp"
#include "core/pipeline/pipeline.hpp"
#include "core/world/world.hpp"
#include "synthetic_sky.hpp"

namespace gnssemu::receiver {
namespace {

using pipeline::Pipeline;
using pipeline::PipelineConfig;
using test::kSite;
using test::kToe;
using test::truth_at;

const world::SatObservable* find(const world::Observables& o, int prn) {
  for (int i = 0; i < o.num_sats; ++i)
    if (o.sats[i].sat.prn() == prn && o.sats[i].received) return &o.sats[i];
  return nullptr;
}

TEST(WorldCarrier, PhaseFollowsTheRangeAndTheIonosphereAdvancesIt) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  PipelineConfig c = test::noiseless();
  c.world.carrier.oscillator_sigma_rad = 0.0;
  c.world.atmosphere.ionosphere.source = atmosphere::VtecSource::kFixed;
  Pipeline rx(store, c);
  world::World& w = rx.world();
  const Ecef pos = geo::ecef_from_lla(kSite);
  const world::Observables first = w.step(kToe, truth_at(pos, kToe), 5.0 * kDegToRad);
  const world::Observables later = w.step(kToe + 30.0, truth_at(pos, kToe + 30.0), 5.0 * kDegToRad);
  int checked = 0;
  for (int i = 0; i < first.num_sats; ++i) {
    const world::SatObservable& a = first.sats[i];
    const world::SatObservable* b = find(later, a.sat.prn());
    if (!a.received || b == nullptr) continue;
    ASSERT_TRUE(a.carrier_valid && b->carrier_valid);
    EXPECT_EQ(a.carrier_discontinuities, b->carrier_discontinuities) << a.sat.prn();
    // Code minus carrier is twice the ionosphere plus the ambiguity: over 30 s
    // it changes by twice the ionosphere's change, which is small but not 0.
    const double cmc_a = a.pseudorange_m - a.carrier_phase_cycles * kL1Wavelength_m;
    const double cmc_b = b->pseudorange_m - b->carrier_phase_cycles * kL1Wavelength_m;
    const double d_iono = rx.world().path_effects(a.sat).iono_m;
    EXPECT_LT(std::fabs(cmc_b - cmc_a), 1.0) << a.sat.prn();
    EXPECT_GT(d_iono, 0.5) << a.sat.prn();
    // The carrier's change is the range's (same clock, same orbit error, the
    // ionosphere's change of sign): the Doppler integrates to it.
    const double carrier_change = (b->carrier_phase_cycles - a.carrier_phase_cycles) * kL1Wavelength_m;
    const double mean_rate = -0.5 * (a.doppler_hz + b->doppler_hz) * kL1Wavelength_m;
    EXPECT_NEAR(carrier_change, mean_rate * 30.0, 2.0) << a.sat.prn();
    ++checked;
  }
  EXPECT_GE(checked, 6);
}

TEST(WorldCarrier, NewLockAfterLossAndLockBreakOnAJump) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  Pipeline rx(store, test::snapshot());
  world::World& w = rx.world();
  const Ecef pos = geo::ecef_from_lla(kSite);
  const world::Observables o0 = w.step(kToe, truth_at(pos, kToe), 0.1);
  const world::Observables o1 = w.step(kToe + 1.0, truth_at(pos, kToe + 1.0), 0.1);
  world::Truth lost = truth_at(pos, kToe + 2.0);
  lost.valid = false;
  w.step(kToe + 2.0, lost, 0.1);
  const world::Observables o3 = w.step(kToe + 3.0, truth_at(pos, kToe + 3.0), 0.1);
  // 5 km to the east in one second, velocity 0: ranges along the east jump by
  // more than half a chip, those across it hardly change.
  const Ecef moved = geo::ecef_from_lla({kSite.lat_rad, kSite.lon_rad + 5000.0 / 4.5e6, kSite.height_m});
  const world::Observables o4 = w.step(kToe + 4.0, truth_at(moved, kToe + 4.0), 0.1);
  int checked = 0, breaks = 0;
  for (int i = 0; i < o0.num_sats; ++i) {
    const int p = o0.sats[i].sat.prn();
    const world::SatObservable* a = find(o0, p);
    const world::SatObservable* b = find(o1, p);
    const world::SatObservable* c = find(o3, p);
    const world::SatObservable* d = find(o4, p);
    if (!a || !b || !c || !d) continue;
    EXPECT_FALSE(b->lock_break);
    EXPECT_EQ(b->carrier_discontinuities, a->carrier_discontinuities);  // continuous
    EXPECT_EQ(c->carrier_discontinuities, a->carrier_discontinuities + 1);  // after the antenna loss
    EXPECT_FALSE(c->lock_break);  // a new lock, not a jump within one
    const double jump_m = std::fabs(5000.0 * std::sin(d->az_rad) * std::cos(d->el_rad));
    if (jump_m > world::kHalfChip_m + 10.0) {
      EXPECT_TRUE(d->lock_break) << p << " jump " << jump_m;
    }
    if (jump_m < world::kHalfChip_m - 10.0) {
      EXPECT_FALSE(d->lock_break) << p << " jump " << jump_m;
    }
    EXPECT_EQ(d->carrier_discontinuities, c->carrier_discontinuities + (d->lock_break ? 1u : 0u));
    breaks += d->lock_break;
    ++checked;
  }
  EXPECT_GE(checked, 6);
  EXPECT_GE(2 * breaks, checked);
}

TEST(WorldCarrier, MultipathTurnsThePhaseByMillimetresWhereTheCodeHasMetres) {
  // Two worlds alike but for the multipath process (2 m / sin el): its draws
  // have their own purposes, so every other term, the ambiguities and the
  // slips are the same and the differences are the multipath alone.
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  world::WorldConfig clean = test::snapshot().world;
  clean.bands = 2;
  world::WorldConfig with = clean;
  with.errors.multipath = {2.0, 60.0};
  world::World a(store, with), b(store, clean);
  const Ecef pos = geo::ecef_from_lla(kSite);
  // One reflection of amplitude a turns the phase by at most asin(a) lambda / (2 pi).
  const auto bound_m = [](double lambda_m) {
    return std::asin(world::kCarrierReflectionAmplitude) * lambda_m / (2.0 * kPi);
  };
  std::array<double, 2> max_code_m{}, max_phase_m{}, max_ratio{};
  int checked = 0;
  for (int k = 0; k < 300; ++k) {
    const time::GpsTime t = kToe + 1.0 * k;
    const world::Observables& oa = a.step(t, truth_at(pos, t), 5.0 * kDegToRad);
    const world::Observables& ob = b.step(t, truth_at(pos, t), 5.0 * kDegToRad);
    ASSERT_EQ(oa.num_sats, ob.num_sats);
    for (int i = 0; i < oa.num_sats; ++i) {
      const world::SatObservable& x = oa.sats[i];
      const world::SatObservable& y = ob.sats[i];
      if (!x.received) continue;
      ASSERT_TRUE(x.carrier_valid && y.carrier_valid && x.band1.carrier_valid && y.band1.carrier_valid);
      ASSERT_EQ(x.carrier_discontinuities, y.carrier_discontinuities);
      ASSERT_EQ(x.band1.carrier_discontinuities, y.band1.carrier_discontinuities);
      const double code_m[2] = {x.pseudorange_m - y.pseudorange_m, x.band1.pseudorange_m - y.band1.pseudorange_m};
      const double lambda_m[2] = {x.wavelength_m, x.band1.wavelength_m};
      const double phase_m[2] = {(x.carrier_phase_cycles - y.carrier_phase_cycles) * lambda_m[0],
                                 (x.band1.carrier_phase_cycles - y.band1.carrier_phase_cycles) * lambda_m[1]};
      for (std::size_t band = 0; band < 2; ++band) {
        // The model's own formula of the phase turned by the code's reflection.
        EXPECT_NEAR(phase_m[band], world::carrier_multipath_m(code_m[band], lambda_m[band]), 1e-6)
            << x.sat.prn() << " band " << band << " code " << code_m[band];
        EXPECT_LE(std::fabs(phase_m[band]), bound_m(lambda_m[band]) + 1e-6);
        EXPECT_LT(std::fabs(phase_m[band]), lambda_m[band] / 4.0);
        max_code_m[band] = std::max(max_code_m[band], std::fabs(code_m[band]));
        max_phase_m[band] = std::max(max_phase_m[band], std::fabs(phase_m[band]));
        if (std::fabs(code_m[band]) > 0.5) {
          max_ratio[band] = std::max(max_ratio[band], std::fabs(phase_m[band] / code_m[band]));
        }
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 2000);
  for (std::size_t band = 0; band < 2; ++band) {
    // Metres of code multipath; its phase reaches the bound (6.1 mm on L1, 7.8
    // mm on L2), which is below the quarter wavelength (4.8 and 6.1 cm).
    EXPECT_GT(max_code_m[band], 3.0) << band;
    EXPECT_GT(max_phase_m[band], 0.9 * bound_m(band == 0 ? kL1Wavelength_m : kSpeedOfLight_m_s / 1227.60e6)) << band;
    EXPECT_LT(max_ratio[band], 0.02) << band;
  }
  EXPECT_NEAR(bound_m(kL1Wavelength_m), 0.0061, 0.00005);
}

TEST(WorldCarrier, DeterministicForASeed) {
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  Pipeline a(store, PipelineConfig{}), b(store, PipelineConfig{});
  const Ecef pos = geo::ecef_from_lla(kSite);
  for (int k = 0; k < 20; ++k) {
    const time::GpsTime t = kToe + 1.0 * k;
    const world::Observables& oa = a.world().step(t, truth_at(pos, t), 0.1);
    const world::Observables& ob = b.world().step(t, truth_at(pos, t), 0.1);
    ASSERT_EQ(oa.num_sats, ob.num_sats);
    for (int i = 0; i < oa.num_sats; ++i) {
      EXPECT_EQ(oa.sats[i].carrier_phase_cycles, ob.sats[i].carrier_phase_cycles);
      EXPECT_EQ(oa.sats[i].carrier_discontinuities, ob.sats[i].carrier_discontinuities);
      EXPECT_EQ(oa.sats[i].doppler_hz, ob.sats[i].doppler_hz);
    }
  }
}

TEST(WorldCarrier, DopplerNoiseGrowsAsCn0Falls) {
  // Same world, two noise floors: the FLL Doppler is noisier on weak signals,
  // the fixed model is not.
  const orbit::EphemerisStore store(test::nominal_constellation(kToe, 5));
  const auto doppler_rms = [&](double rise_db, world::DopplerModel model) {
    PipelineConfig c = test::snapshot();
    c.world.carrier.doppler_model = model;
    c.world.errors.doppler_sigma_m_s = 0.03;
    c.world.signal.link.environment_noise_rise_db = rise_db;
    PipelineConfig quiet = c;
    quiet.world.errors.doppler_sigma_m_s = 0.0;
    quiet.world.carrier.doppler_model = world::DopplerModel::kFixed;
    quiet.world.clock.drift_noise_s_s_sqrt_s = 0.0;
    c.world.clock.drift_noise_s_s_sqrt_s = 0.0;
    Pipeline noisy(store, c), clean(store, quiet);
    const Ecef pos = geo::ecef_from_lla(kSite);
    double sum = 0.0;
    int n = 0;
    for (int k = 0; k < 200; ++k) {
      const time::GpsTime t = kToe + 1.0 * k;
      const world::Observables& a = noisy.world().step(t, truth_at(pos, t), 0.1);
      const world::Observables& b = clean.world().step(t, truth_at(pos, t), 0.1);
      for (int i = 0; i < a.num_sats; ++i) {
        if (!a.sats[i].received || !b.sats[i].received) continue;
        const double d = (a.sats[i].doppler_hz - b.sats[i].doppler_hz) * kL1Wavelength_m;
        sum += d * d;
        ++n;
      }
    }
    return std::sqrt(sum / n);
  };
  const double quiet = doppler_rms(1.0, world::DopplerModel::kFll);
  const double noisy = doppler_rms(10.0, world::DopplerModel::kFll);
  EXPECT_GT(noisy, 2.0 * quiet);
  EXPECT_GT(quiet, 0.01);
  EXPECT_LT(quiet, 0.1);
  EXPECT_NEAR(doppler_rms(1.0, world::DopplerModel::kFixed), 0.03, 0.005);
  EXPECT_NEAR(doppler_rms(10.0, world::DopplerModel::kFixed), 0.03, 0.005);
}

}  // namespace
}  // namespace gnssemu::receiver
