// SPDX-License-Identifier: Apache-2.0
#pragma once
// A configuration that sets every key of the key tables to a value other
// than its default, and one with the keys it cannot hold.
#include <string>

namespace gnssemu::config::test {

/// Every key, each off its default; parses against tests/data.
inline const std::string kEveryKey = R"(
[origin]
lat_deg = -33.8568
lon_deg = 151.2153
height_m = 39.5

[nav]
file = "nav/ab422100.18n"
files = ["nav/brdc0010.22n"]
folder = "nav"
mode = "relabel"

[time]
mode = "lockstep"
start = "2018-07-29T06:30:15.5"
use_wall_clock_date = false
output_delay_s = 0.25

[receiver]
profile = "geodetic"
rate_hz = 4
elevation_mask_deg = 12.5
seed = 424242
nominal_cn0_dbhz = 41.5
max_pdop = 8.0
max_channels = 12
generation = "m9"
raw_data = true
sbas = false
constellations = ["G", "E", "C"]  # not the m9 factory set, so it is written
state_file = "state/ubx-state.txt"
filter = "none"

[receiver.errors]
thermal_model = "fixed"
thermal_sigma_m = 0.45
doppler_sigma_m_s = 0.07

[receiver.errors.orbit_clock]
sigma_m = 0.8
tau_s = 900

[receiver.errors.multipath]
sigma_m = 0.061145637
tau_s = 1920

[receiver.errors.gradient]
north_m = -0.383278
east_m = -0.134185
north_diurnal_m = 0.471
north_peak_h = 3.8
east_diurnal_m = 0.416
east_peak_h = 6.3
sigma_m = 0.351071
tau_s = 15291.3

[receiver.errors.iono_scale]
sigma = 0.25
tau_s = 7200

[receiver.clock]
bias_s = -2.5e-4
drift_s_s = -1.5e-7
drift_noise_s_s_sqrt_s = 3e-11
jump_threshold_s = 5e-4

[receiver.solver]
weights = "rtklib"
code_bias_sigma_m = 0.45
sigma_a_m = 0.9
sigma_b_m = 0.45
sigma_c_m_sqrt_hz = 95.5
iono_model_fraction = 0.5
tropo_model_sigma_m = 0.3
sigma_range_rate_m_s = 0.08
height_hold_sigma_m = 2.5
residual_test_pfa = 0.01
max_exclusions = 3
max_iterations = 8

[receiver.corrections]
ionosphere = "none"
troposphere = "zhd_niell"

[receiver.nav]
dyn_model = "automotive"
static_hold_thresh_m_s = 0.5
static_hold_max_dist_m = 20
smoothing_window_s = 100
coast_limit_s = 5
coast_report = "dead_reckoning"
position_noise_m2_s = 0.05
clock_h0_s = 9.4e-20
clock_h_minus2_per_s = 3.8e-21
innovation_gate_sigma = 4
reinit_margin_m = 50

[receiver.acquisition]
start = "cold"
modelled = false
cold_search_s = 2.5
aided_search_s = 0.8
reacq_search_s = 0.2
reacq_window_s = 120
strong_cn0_dbhz = 42
search_spread = 0.2
cold_acquire_dbhz = 26
reacq_margin_db = 2
aided_doppler_window_hz = 800
bit_sync_s = 0.5
almanac_download_s = 800
ephemeris_validity_s = 7200

[receiver.limits]
max_altitude_m = 18000
max_speed_m_s = 515

[receiver.spoof_detection]
enabled = false
cn0_jump_db = 6
cn0_jump_sats = 4
clock_jump_m = 300
uniform_std_db = 0.5
uniform_min_sats = 6
system_disagreement_m = 80
hold_s = 10

[atmosphere]
cache_refresh_s = 30
cache_mode = "hold"
gases = false
water_vapour_density_g_m3 = 12.5
water_vapour_scale_height_m = 1800

[atmosphere.ionosphere]
enabled = false
vtec_source = "fixed"
vtec_tecu = 42.5
klobuchar_scale = 1.7
mapping = "thin_shell"
obliquity_pivot_deg = 96
shell_height_m = 450000

[atmosphere.ionosphere.perturbation]
sigma_tecu = 2.5
tau_s = 900

[atmosphere.troposphere]
enabled = false
zhd_model = "saastamoinen"
zhd_a_m = 2.25
zhd_b_per_m = 1.3e-4
zwd_model = "saastamoinen"
zwd_m = 0.21
zwd_scale_height_m = 1500
rel_humidity = 0.55

[atmosphere.troposphere.zwd_perturbation]
sigma_m = 0.035
tau_s = 7200

[atmosphere.shells.troposphere]
enabled = false
bottom_m = -10
top_m = 11000
temperature_k = 290.5
gas_absorption = false

[atmosphere.shells.stratosphere]
enabled = false
bottom_m = 11000
top_m = 48000
temperature_k = 230.5
gas_absorption = false

[atmosphere.shells.mesosphere]
enabled = false
bottom_m = 48000
top_m = 90000
temperature_k = 220
gas_absorption = false

[atmosphere.shells.thermosphere]
enabled = false
bottom_m = 90000
top_m = 700000
temperature_k = 900
gas_absorption = false

[atmosphere.shells.ionosphere]
enabled = false
bottom_m = 70000
top_m = 900000
temperature_k = 700
gas_absorption = true

[[atmosphere.clouds]]
base_m = 200
thickness_m = 350.5
liquid_water_g_m3 = 0.42
temperature_k = 280

[atmosphere.rain]
rate_mm_h = 100
rain_height_m = 4200
k = 6.0e-5
alpha = 0.95

[signal]
enabled = false
noise_rise_db = 4.5
eirp_dbw = 27.5
noise_figure_db = 1.5
noise_temperature_k = 300
implementation_loss_db = 1.25
acquire_dbhz = 33
lose_dbhz = 28.5

[signal.antenna]
zenith_gain_dbi = 5.5
horizon_gain_dbi = -8.5
below_horizon_slope_db_per_deg = 0.5

[signal.dll]
loop_bandwidth_hz = 1.0
integration_s = 0.005
spacing_chips = 0.1
discriminator = "dot_product"

[signal.carrier]
enabled = false
doppler_model = "fixed"
pll_bandwidth_hz = 15
fll_bandwidth_hz = 5
integration_s = 0.01
oscillator_sigma_rad = 0.05
lock_break_m = 300

[truth]
bind = "0.0.0.0"
port = 6001
timeout_s = 1.5
max_extrapolation_s = 0.25
allow = ["127.0.0.1/32", "10.0.0.0/8", "::1/128"]
vehicle = "ego"

[demo]
enabled = false
radius_m = 120.0
speed_m_s = 13.9
height_m = 2.5

[[output]]
name = "ecu"
type = "pty"
path = "/tmp/gnssemu/ecu"
baud = 115200
protocols_in = ["nmea", "rtcm3"]
protocols_out = ["nmea"]
ubx_messages = ["NAV-SAT", "NAV-PVT"]
nmea_version = "2.3"
sentences = ["GGA", "RMC", "GST", "ZDA"]
course_min_speed_m_s = 0.0
rates = { NAV-SAT = 5, GGA = 2 }

[[output]]
name = "log"
type = "file"
path = "out/run.nmea"
baud = 38400

[[output]]
name = "fc"
type = "serial"
device = "/dev/ttyUSB0"

[[output]]
name = "net"
type = "tcp"
bind = "::1"
port = 2947

[[output]]
name = "bcast"
type = "udp"
address = "127.0.0.2"
port = 10110

[base]
lat_deg = -33.9
lon_deg = 151.1
height_m = 45.5
station_id = 2003
antenna_height_m = 1.25
open_sky = true
messages = "1006(10),1077(1),1087(1),1230(5),1019(60),1020"
seed = 99

[base.ntrip]
port = 2102
mountpoint = "SYD0"
user = "rover"
password = "secret"

[[base.output]]
name = "rtcm_net"
type = "tcp"
bind = "::1"
port = 2948

[[base.output]]
name = "rtcm_radio"
type = "serial"
device = "/dev/ttyUSB1"
baud = 57600

[[base.output]]
name = "rtcm_pty"
type = "pty"
path = "/tmp/gnssemu/rtcm"

[[base.output]]
name = "rtcm_udp"
type = "udp"
address = "127.0.0.3"
port = 10111

[scene]
mesh = "scenes/street_canyon.toml"
offset_m = [10.0, -5.5, 0.25]
yaw_deg = 90.0
scale = 2.0
up_axis = "y"
rays = 512
azimuth_rays = 64
max_bounces = 8
match_factor = 2.5
reuse_distance_m = 0.5
reuse_angle_deg = 0.25
min_arrival_elevation_deg = 2.0
max_loss_db = 18.0
reflection_loss_db = 3.5

[scene.material_loss_db]
glass = 1.5

[status]
bind = "::1"
port = 8088
free_port = true

[control]
socket = "/run/gnssemu/control.sock"

[log]
level = "debug"
)";

/// The keys kEveryKey cannot hold: the presets (read as other keys) and
/// nav.almanac (mode almanac only), use_wall_clock_date (not together with a
/// start time), [[vehicle]] and [fleet] (not together with [[output]]),
/// receiver.bands off its default (an F9P on L1 only: an M9, which
/// raw_data = true needs, tracks one band).
inline const std::string kOtherKeys = R"(
[origin]
lat_deg = 1
lon_deg = 2
height_m = 0

[receiver]
generation = "f9p"
bands = 1

[nav]
file = "nav/brdc0010.22n"
almanac = "almanac/yuma_week862_toa319488.alm"
mode = "almanac"

[time]
use_wall_clock_date = true

[[atmosphere.clouds]]
preset = "cumulus"

[signal]
environment = "urban"

[[vehicle]]
id = "ego"
allow = ["127.0.0.1", "10.1.0.0/16"]

[[vehicle.receiver]]
name = "gps1"
lever_arm_m = [0.5, -0.25, -0.1]
seed = 7
generation = "m9"

[vehicle.receiver.errors]
thermal_model = "fixed"

[[vehicle.receiver.output]]
name = "ecu"
type = "pty"
path = "/tmp/gnssemu/ego/gps1"

[[vehicle.receiver]]
name = "gps2"

[[vehicle.receiver.output]]
name = "ecu"
type = "tcp"
port = 2948

[fleet]
count = 3

[[fleet.output]]
name = "gps-{vehicle}"
type = "pty"
path = "/tmp/gnssemu/{vehicle}/{receiver}"
baud = 115200
protocols_in = ["nmea"]
protocols_out = ["nmea"]
ubx_messages = ["NAV-SAT", "NAV-PVT"]
nmea_version = "2.3"
sentences = ["GGA", "RMC", "GST", "ZDA"]
course_min_speed_m_s = 0.0
rates = { NAV-SAT = 5, GGA = 2 }

[[fleet.output]]
name = "log-{index}"
type = "file"
path = "out/{vehicle}.nmea"
baud = 38400

[[fleet.output]]
name = "fc"
type = "serial"
device = "/dev/ttyUSB{index}"

[[fleet.output]]
name = "net"
type = "tcp"
bind = "::1"
port_base = 3000

[[fleet.output]]
name = "bcast"
type = "udp"
address = "127.0.0.2"
port_base = 10110
)";

}  // namespace gnssemu::config::test
