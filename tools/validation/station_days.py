# SPDX-License-Identifier: Apache-2.0
"""The real station-days of ../shared/data (provenance: its README.md) that
the error-model validation and the RTKLIB comparison run on: observation
file, the same day's broadcast nav file, and the antenna reference point
(header APPROX POSITION XYZ plus ANTENNA: DELTA H/E/N, as the data README's
RTKLIB check takes it)."""
import gzip
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEFAULT_DATA = os.path.normpath(os.path.join(ROOT, "..", "shared", "data"))
# The RTKLIB comparison of one file (and its gzip helper) is the integration test's.
sys.path.insert(0, os.path.join(ROOT, "tests", "integration", "offline"))
import spp_vs_rtklib  # noqa: E402,F401

# name, station (held-out unit of leave-one-station-out), obs, nav
DAYS = [
    ("NYA1-2024-124", "NYA1", "obs/NYA100NOR_S_20241240000_01D_30S_GO_L1.rnx.gz", "nav/NYA100NOR_S_20241240000_01D_GN.rnx"),
    ("NYA1-2024-127", "NYA1", "obs/NYA100NOR_S_20241270000_01D_30S_GO_L1.rnx.gz", "nav/NYA100NOR_S_20241270000_01D_GN.rnx"),
    ("ESBC-2020-177", "ESBC", "obs/ESBC00DNK_R_20201770000_01D_30S_GO_L1.rnx.gz", "nav/ESBC00DNK_R_20201770000_01D_MN.rnx.gz"),
    ("S6-2023-248", "S6", "obs/OB712480_12H_GO_L1.23O", "nav/brdc2480.23n"),
    ("ROAP-2009-181", "ROAP", "obs/roap1810.09o.gz", "nav/brdc1810.09n"),
]

# Days with every system's observations and the same day's multi-system nav
# (the multi-system gain; errmodel_validation.py --gain): name, station, obs, nav.
MULTI_SYSTEM_DAYS = [
    ("BELE-2024-010", "BELE", "obs/BELE00BRA_R_20240100000_01D_30S_MO.crx.gz", "nav/BRDC00IGS_R_20240100000_01D_MN.rnx.gz"),
    ("TLSE-2024-001-15min", "TLSE", "obs/TLSE00FRA_R_20240011200_15M_01S_MO.crx.gz", "nav/BRDC00IGS_R_20240010000_01D_MN.rnx.gz"),
]


class Day:
    def __init__(self, data, name, station, obs, nav):
        self.name, self.station = name, station
        self.obs, self.nav = os.path.join(data, obs), os.path.join(data, nav)
        self.arp = antenna_reference_point(self.obs)


def days(data=DEFAULT_DATA):
    return [Day(data, *d) for d in DAYS]


def multi_system_days(data=DEFAULT_DATA):
    return [Day(data, *d) for d in MULTI_SYSTEM_DAYS]


def _header(obs):
    opener = gzip.open if obs.endswith(".gz") else open
    out = {}
    with opener(obs, "rt") as f:
        for line in f:
            label = line[60:].strip()
            out.setdefault(label, line[:60])
            if label == "END OF HEADER":
                break
    return out


def antenna_reference_point(obs):
    """Header APPROX POSITION XYZ plus the ANTENNA: DELTA H/E/N eccentricity, ECEF m."""
    h = _header(obs)
    x, y, z = (float(v) for v in h["APPROX POSITION XYZ"].split()[:3])
    dh, de, dn = (float(v) for v in h.get("ANTENNA: DELTA H/E/N", "0 0 0").split()[:3])
    lon = math.atan2(y, x)
    lat = math.atan2(z, math.hypot(x, y) * (1 - 6.69437999014e-3))  # geodetic to < 1e-5 rad: fine for a 1 m offset
    sl, cl, so, co = math.sin(lat), math.cos(lat), math.sin(lon), math.cos(lon)
    return (x - so * de - sl * co * dn + cl * co * dh,
            y + co * de - sl * so * dn + cl * so * dh,
            z + cl * dn + sl * dh)
