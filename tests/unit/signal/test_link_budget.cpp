// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "core/common/constants.hpp"
#include "core/common/error.hpp"
#include "core/signal/link_budget.hpp"
#include "core/signal/system_signal.hpp"

using namespace gnssemu;
using namespace gnssemu::signal;

namespace {
constexpr double kDeg = kDegToRad;
}

TEST(LinkBudget, FreeSpaceLossAndNoise) {
  // Reference §4: 20 180 km -> 182.49 dB, 25 231 km -> 184.43 dB, 21 662 km -> 183.11 dB.
  EXPECT_NEAR(free_space_path_loss_db(20180e3), 182.494, 0.001);
  EXPECT_NEAR(free_space_path_loss_db(25231e3), 184.434, 0.001);
  EXPECT_NEAR(free_space_path_loss_db(21662e3), 183.11, 0.01);
  EXPECT_NEAR(thermal_noise_density_dbw_hz(290.0), -203.975, 0.001);
  EXPECT_TRUE(std::isfinite(free_space_path_loss_db(0.0)));
  EXPECT_TRUE(std::isfinite(free_space_path_loss_db(NAN)));
}

TEST(LinkBudget, AntennaPattern) {
  const AntennaPattern p;
  EXPECT_NEAR(antenna_gain_dbi(p, 90 * kDeg), 3.0, 1e-12);
  EXPECT_NEAR(antenna_gain_dbi(p, 0.0), -5.0, 1e-12);
  EXPECT_NEAR(antenna_gain_dbi(p, 30 * kDeg), -1.0, 1e-12);  // 3 - 8 * 0.5
  EXPECT_NEAR(antenna_gain_dbi(p, -10 * kDeg), -15.0, 1e-9);
  EXPECT_TRUE(std::isfinite(antenna_gain_dbi(p, NAN)));
}

TEST(LinkBudget, OpenSkyCn0) {
  const LinkBudgetModel m(LinkBudgetConfig{});
  // Zenith, 20 180 km, gases 0.046 dB: 26.8 - 182.494 - 0.046 + 3 - (-203.975 + 2 + 1) = 48.23 dB-Hz.
  const LinkBudget z = m.evaluate(20180e3, 90 * kDeg, 0.046);
  EXPECT_NEAR(z.cn0_dbhz, 48.235, 0.002);
  EXPECT_GE(z.cn0_dbhz, 45.0);
  EXPECT_LE(z.cn0_dbhz, 50.0);
  // 5 deg, 25 231 km, gases 0.5 dB.
  const double c5 = m.cn0_dbhz(25231e3, 5 * kDeg, 0.5);
  EXPECT_NEAR(c5, 38.54, 0.01);
  EXPECT_GE(c5, 38.0);
  EXPECT_LE(c5, 45.0);
  // Isotropic received power at 5 deg meets the IS-GPS-200 minimum (-158.5 dBW, 0 dBic equivalent).
  EXPECT_GE(26.8 - free_space_path_loss_db(25231e3), -158.5);
  // Losses subtract 1:1; an infinite loss is a blocked path, finite C/N0.
  EXPECT_NEAR(m.cn0_dbhz(20180e3, 90 * kDeg, 10.046), z.cn0_dbhz - 10.0, 1e-9);
  EXPECT_TRUE(std::isfinite(m.cn0_dbhz(20180e3, 90 * kDeg, INFINITY)));
  EXPECT_LT(m.cn0_dbhz(20180e3, 90 * kDeg, INFINITY), 0.0);
  EXPECT_NEAR(m.cn0_dbhz(20180e3, 90 * kDeg, NAN), m.cn0_dbhz(20180e3, 90 * kDeg, 0.0), 0.0);
}

TEST(LinkBudget, EnvironmentNoise) {
  EXPECT_EQ(environment_noise_rise_db("countryside"), 1.0);
  EXPECT_EQ(environment_noise_rise_db("industrial"), 20.0);
  EXPECT_EQ(environment_noise_rise_db("jamming"), 40.0);
  EXPECT_THROW(environment_noise_rise_db("harbour"), Error);
  LinkBudgetConfig c;
  c.environment_noise_rise_db = environment_noise_rise_db("industrial");
  const LinkBudgetModel ind(c);
  const LinkBudgetModel open(LinkBudgetConfig{});
  EXPECT_NEAR(ind.cn0_dbhz(20180e3, 90 * kDeg, 0.0), open.cn0_dbhz(20180e3, 90 * kDeg, 0.0) - 19.0, 1e-9);
}

TEST(LinkBudget, BadConfigThrows) {
  LinkBudgetConfig c;
  c.noise_temperature_k = 0.0;
  EXPECT_THROW(LinkBudgetModel{c}, Error);
  c = {};
  c.noise_figure_db = -1.0;
  EXPECT_THROW(LinkBudgetModel{c}, Error);
  c = {};
  c.environment_noise_rise_db = 80.0;
  EXPECT_THROW(LinkBudgetModel{c}, Error);
  c = {};
  c.antenna.horizon_gain_dbi = 10.0;
  EXPECT_THROW(LinkBudgetModel{c}, Error);
  c = {};
  c.eirp_dbw = NAN;
  EXPECT_THROW(LinkBudgetModel{c}, Error);
}

TEST(LinkBudget, CarrierAndSystemOfTheSatellite) {
  const LinkBudgetModel m(LinkBudgetConfig{});
  const double r = 2.2e7, el = 0.7;
  // GPS at L1: the three-argument budget exactly.
  EXPECT_EQ(m.cn0_dbhz(r, el, 0.5, GnssSystem::kGps, kL1Freq_hz), m.cn0_dbhz(r, el, 0.5));
  // Free-space loss at the satellite's carrier: 20 log10(f / f_L1) more or less.
  const LinkBudget g1 = m.evaluate(r, el, 0.0, GnssSystem::kGps, 1602.0e6);
  const LinkBudget b1 = m.evaluate(r, el, 0.0, GnssSystem::kGps, 1561.098e6);
  const LinkBudget l1 = m.evaluate(r, el, 0.0);
  EXPECT_NEAR(g1.fspl_db - l1.fspl_db, 20.0 * std::log10(1602.0 / 1575.42), 1e-9);
  EXPECT_NEAR(b1.fspl_db - l1.fspl_db, 20.0 * std::log10(1561.098 / 1575.42), 1e-9);
  // The system's table row adds its power and slope offsets.
  for (int s = 0; s < kNumSystems; ++s) {
    const auto sys = static_cast<GnssSystem>(s);
    const SystemSignal& ss = system_signal(sys);
    EXPECT_NEAR(m.cn0_dbhz(r, el, 0.0, sys, kL1Freq_hz) - l1.cn0_dbhz,
                ss.power_offset_db + ss.slope_offset_db * (1.0 - std::sin(el)), 1e-9);
  }
}
