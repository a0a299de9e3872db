#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Faults and bad truth in a fleet (docs/configuration.md §Vehicles,
docs/faults.md): one gnssemud, [fleet] count = 3 (v0, v1, v2 at 2 Hz),
one UDP truth socket, a pty per receiver read by a thread that keeps every
GGA; the state of each receiver read from /api/overview and
/api/status?vehicle=. Cases:

  target  a --scenario outage with target = "v1": v1 loses its fix, v0 and
          v2 keep theirs; a target naming no vehicle or receiver is a
          file:line error at start.
  jammer  v0 50 m and v1 5 km from a positioned wideband jammer (eirp_dbw,
          lat/lon, gain 0 dBi), first at E dBW then at E + 40 dB: each
          receiver's C/N0 drop is the free-space one of its own distance, so
          the far one in the second phase loses what the near one lost in the
          first (100x the distance = 40 dB), the near one then loses its fix.
  swarm   tools/senders/swarm_truth.py drives [fleet] count = 5 in a line
          abreast 40 m apart: the daemon's truths are that far apart, the
          middle one on the sender's circle, each receiver with its own fix.
  jump    v1's truth jumps 1000 km north between two packets: v0 and v2 miss
          no epoch and their errors stay; v1 behaves as a receiver carried
          off at that speed (no fix past the speed limit, then a fix at the
          new place); the daemon logs it and exits 0.

Loopback only, free ports, temp dir; each case stops itself in 90 s.

usage: fleet_faults_integration.py --gnssemud PATH --gnssemu PATH --nav FILE target|jammer|jump|swarm
"""
import argparse
import json
import math
import os
import re
import socket
import subprocess
import sys
import threading
import time
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, enu_to_latlon, free_port, parse_gga, run_rig, daemon_toml  # noqa: E402

ORIGIN = (48.8738, 2.2950, 100.0)
RATE_HZ = 2.0
FIX_TOLERANCE_M = 15.0
C_M_S = 299792458.0
L1_HZ = 1575.42e6
HERE = os.path.dirname(os.path.abspath(__file__))


def horizontal_m(lat_a, lon_a, lat_b, lon_b):
    dn = math.radians(lat_a - lat_b) * 6371000.0
    de = math.radians(lon_a - lon_b) * 6371000.0 * math.cos(math.radians(ORIGIN[0]))
    return math.hypot(de, dn)


def fspl_db(d_m):
    """Free-space loss at L1, dB (Friis)."""
    return 20 * math.log10(4 * math.pi * d_m * L1_HZ / C_M_S)


class PtyReader:
    """Every GGA of a pty: (monotonic, hhmmss.ss field, quality)."""

    def __init__(self, path):
        self.path = path
        self.ggas = []
        self.stop = False
        threading.Thread(target=self.run, daemon=True).start()

    def run(self):
        fd = os.open(self.path, os.O_RDONLY | os.O_NOCTTY | os.O_NONBLOCK)
        buf = b""
        try:
            while not self.stop:
                try:
                    chunk = os.read(fd, 65536)
                except BlockingIOError:
                    time.sleep(0.005)
                    continue
                except OSError:
                    return
                buf += chunk
                *lines, buf = buf.split(b"\n")
                for raw in lines:
                    line = raw.decode(errors="replace").strip()
                    g = parse_gga(line) if "GGA" in line else None
                    if g is not None or line[3:6] == "GGA":
                        self.ggas.append((time.monotonic(), line.split(",")[1], g[0] if g else 0))
        finally:
            os.close(fd)


class Rig(RigBase):
    def __init__(self, args):
        super().__init__("gnssemu-fleetfaults-")
        self.args = args
        self.udp_port = free_port(socket.SOCK_DGRAM)
        self.http_port = free_port(socket.SOCK_STREAM)
        self.stop_sending = threading.Event()
        self.pos = {}  # vehicle -> (lat, lon); the sender reads it every packet
        self.count = 3
        self.lock = threading.Lock()

    def pty(self, v):
        return os.path.join(self.tmp, f"{v}-gps1")

    def config(self):
        cfg = os.path.join(self.tmp, "fleet.toml")
        with open(cfg, "w") as f:
            f.write(f"""{daemon_toml(ORIGIN, self.args.nav, "2022-01-01T01:00:00", RATE_HZ, self.udp_port)}[status]
bind = "127.0.0.1"
port = {self.http_port}
[fleet]
count = {self.count}
[[fleet.output]]
type = "pty"
name = "{{vehicle}}"
path = "{self.tmp}/{{vehicle}}-{{receiver}}"
""")
        return cfg

    def start(self, scenario=None, sender=None):
        """gnssemud (with scenario), pty readers, and the truth thread or sender (argv)."""
        argv = [self.args.gnssemud, "--config", self.config()]
        if scenario:
            argv += ["--scenario", scenario]
        self.daemon_log_path = os.path.join(self.tmp, "gnssemud.log")
        self.daemon_log = open(self.daemon_log_path, "w")
        self.daemon = self.spawn(argv, stdout=self.daemon_log, stderr=subprocess.STDOUT, text=True)
        deadline = time.monotonic() + 20
        ids = [f"v{i}" for i in range(self.count)]
        while not all(os.path.exists(self.pty(v)) for v in ids):
            if time.monotonic() > deadline or self.daemon.poll() is not None:
                raise AssertionError(f"the {self.count} ptys did not appear")
            time.sleep(0.1)
        self.readers = {v: PtyReader(self.pty(v)) for v in ids}
        if sender:
            self.spawn(sender, stdout=subprocess.DEVNULL, stderr=self.daemon_log)
        else:
            threading.Thread(target=self.send, daemon=True).start()

    def send(self):
        """10 Hz truth for every vehicle at self.pos."""
        s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        t = 0.0
        while not self.stop_sending.is_set():
            with self.lock:
                pos = dict(self.pos)
            for v, (lat, lon) in pos.items():
                msg = {"version": 1, "vehicle": v, "sim_time_s": t,
                       "lla": {"lat_deg": lat, "lon_deg": lon, "height_m": ORIGIN[2]}}
                s.sendto(json.dumps(msg).encode(), ("127.0.0.1", self.udp_port))
            t += 0.1
            time.sleep(0.1)
        s.close()

    def get(self, path):
        with urllib.request.urlopen(f"http://127.0.0.1:{self.http_port}{path}", timeout=5) as r:
            return json.loads(r.read())

    def overview(self):
        return {x["vehicle"]: x for x in self.get("/api/overview")["rows"]}

    def status(self, v):
        return self.get(f"/api/status?history=0&vehicle={v}&receiver=gps1")

    def wait(self, pred, limit_s, what):
        deadline = time.monotonic() + limit_s
        last = None
        while time.monotonic() < deadline:
            try:
                last = self.overview()
                if pred(last):
                    return last
            except OSError:
                pass
            time.sleep(0.25)
        raise AssertionError(f"{what} not within {limit_s:.0f} s (last overview {last})")

    def finish(self):
        self.stop_sending.set()
        for r in self.readers.values():
            r.stop = True
        rc = self.stop_all()
        self.daemon_log.flush()
        assert rc == 0, f"gnssemud exit {rc}"
        return open(self.daemon_log_path).read()


def all_fixed(o):
    return all(x["fix_type"] == 3 and x["h_err_m"] is not None and x["h_err_m"] < FIX_TOLERANCE_M
               for x in o.values())


def place(rig, enu):
    rig.pos = {v: enu_to_latlon(ORIGIN, e, n) for v, (e, n) in enu.items()}


def case_target(rig):
    place(rig, {"v0": (0.0, 0.0), "v1": (200.0, 0.0), "v2": (400.0, 0.0)})
    bad = [('target = "v7"', "target 'v7' names no vehicle or receiver"),
           ('target = "v1/gps2"', "target 'v1/gps2' names no vehicle or receiver")]
    for key, want in bad:
        scen = os.path.join(rig.tmp, "bad.toml")
        with open(scen, "w") as f:
            f.write(f'[[event]]\ntype = "outage"\nstart_s = 0\n\n[[event]]\ntype = "jammer"\njs_db = 10\n'
                    f'start_s = 1\n{key}\n')
        out = subprocess.run([rig.args.gnssemud, "--config", rig.config(), "--scenario", scen],
                             capture_output=True, text=True, timeout=20)
        assert out.returncode != 0 and f"{scen}:5: {want}" in out.stderr, (out.returncode, out.stderr)
    print("  an unknown vehicle or receiver as target: refused at start with file:line")

    scen = os.path.join(rig.tmp, "outage.toml")
    with open(scen, "w") as f:
        f.write('[[event]]\ntype = "outage"\nstart_s = 12\ntarget = "v1"\n')
    rig.start(scen)
    rig.wait(all_fixed, 60, "a 3D fix on v0, v1, v2")
    o = rig.wait(lambda o: o["v1"]["fix_type"] == 0, 30, "v1's fix lost")
    e0 = {v: x["epochs"] for v, x in o.items()}
    time.sleep(3.0)
    o = rig.overview()
    assert o["v1"]["fix_type"] == 0 and o["v1"]["num_tracked"] == 0 and o["v1"]["faults_active"] == 1, o["v1"]
    for v in ("v0", "v2"):
        x = o[v]
        assert x["fix_type"] == 3 and x["faults_scheduled"] == 0 and x["h_err_m"] < FIX_TOLERANCE_M, x
        assert x["epochs"] - e0[v] >= 5 and x["num_used"] >= 6, (x, e0[v])
    print(f"  outage target = \"v1\": v1 fix {o['v1']['fix_type']}, tracked {o['v1']['num_tracked']}; "
          f"v0 and v2 3D with {o['v0']['num_used']} / {o['v2']['num_used']} used, "
          f"{o['v0']['h_err_m']:.1f} / {o['v2']['h_err_m']:.1f} m")
    rig.finish()


def mean_cn0(st):
    """{sat: C/N0} of the tracked satellites."""
    return {s["sat"]: s["cn0_dbhz"] for s in st["satellites"] if s["tracked"] and s["cn0_dbhz"] is not None}


def case_jammer(rig):
    near_m, far_m = 50.0, 5000.0
    place(rig, {"v0": (0.0, near_m), "v1": (0.0, far_m), "v2": (0.0, -far_m)})
    jam = enu_to_latlon(ORIGIN, 0.0, 0.0)
    # N0 of the default front end: I0 = N0 at J/S 20.6 dB (docs/faults.md §1),
    # J/S over the nominal -158.5 dBW; wideband I0 = J / (2 Rc).
    n0_dbw_hz = -158.5 + 20.6 - 10 * math.log10(2 * 1.023e6)
    x_near = 9.0  # the near receiver's I0/N0 in the first phase: a 10 dB drop
    j_dbw = n0_dbw_hz + 10 * math.log10(x_near) + 10 * math.log10(2 * 1.023e6)
    eirp1 = j_dbw + fspl_db(near_m)
    eirp2 = eirp1 + 40.0
    scen = os.path.join(rig.tmp, "jammer.toml")
    with open(scen, "w") as f:
        for i, (start, eirp) in enumerate([(14, eirp1), (30, eirp2)]):
            f.write(f'[[event]]\ntype = "jammer"\nkind = "wideband"\nstart_s = {start}\nduration_s = 16\n'
                    f'eirp_dbw = {eirp:.3f}\nlat_deg = {jam[0]:.9f}\nlon_deg = {jam[1]:.9f}\n'
                    f'height_m = {ORIGIN[2]}\ngain_dbi = 0.0\n\n')
    rig.start(scen)
    rig.wait(all_fixed, 60, "a 3D fix on v0, v1, v2")
    # C/N0 samples per receiver and phase (0 quiet, 1 and 2 the jammer's),
    # the phase read from the receiver's own fault list, the first 2 s of a
    # phase left out (the ramp from one epoch's C/N0 to the next).
    samples = {v: {0: [], 1: [], 2: []} for v in ("v0", "v1")}
    fix_in_2 = {"v0": [], "v1": []}
    since = {}
    deadline = time.monotonic() + 70
    while time.monotonic() < deadline:
        for v in ("v0", "v1"):
            st = rig.status(v)
            act = [f for f in st["faults"] if f["active"]]
            ph = 0 if not act else (1 if act[0]["start_s"] < 20 else 2)
            if since.get((v, "phase")) != ph:
                since[(v, "phase")] = ph
                since[(v, "t")] = time.monotonic()
            if ph == 0 and any(f["start_s"] > 20 and not f["active"] and st["epoch"]["run_s"] > f["end_s"]
                               for f in st["faults"]):
                deadline = 0
            if time.monotonic() - since[(v, "t")] > 2.0:
                samples[v][ph].append(mean_cn0(st))
                if ph == 2:
                    fix_in_2[v].append(st["fix"]["type"])
        if all(len(samples[v][2]) >= 8 for v in samples):
            break
        time.sleep(0.5)

    def drop(v, ph):
        """Mean C/N0 drop from quiet over the satellites tracked in both."""
        base = {}
        for s in samples[v][0]:
            for k, c in s.items():
                base.setdefault(k, []).append(c)
        now = {}
        for s in samples[v][ph]:
            for k, c in s.items():
                now.setdefault(k, []).append(c)
        both = [k for k in base if k in now]
        if not both:
            return None, 0
        return sum(sum(base[k]) / len(base[k]) - sum(now[k]) / len(now[k]) for k in both) / len(both), len(both)

    for v in samples:
        for ph in (0, 1, 2):
            assert len(samples[v][ph]) >= 4, f"{v}: {len(samples[v][ph])} samples in phase {ph}"
    d_near1, n_near1 = drop("v0", 1)
    d_far1, _ = drop("v1", 1)
    d_far2, n_far2 = drop("v1", 2)
    d_near2, n_near2 = drop("v0", 2)

    def want(d_m, eirp):
        x = 10 ** ((eirp - fspl_db(d_m) - n0_dbw_hz - 10 * math.log10(2 * 1.023e6)) / 10)
        return 10 * math.log10(1 + x)

    print(f"  jammer {eirp1:.1f} dBW: near (50 m) C/N0 -{d_near1:.2f} dB over {n_near1} sats "
          f"(model {want(near_m, eirp1):.2f}), far (5 km) -{d_far1:.2f} dB (model {want(far_m, eirp1):.3f})")
    print(f"  jammer {eirp2:.1f} dBW: far C/N0 -{d_far2:.2f} dB over {n_far2} sats "
          f"(model {want(far_m, eirp2):.2f}); near fix types {sorted(set(fix_in_2['v0']))}, "
          f"{n_near2} sats still tracked")
    assert abs(d_near1 - want(near_m, eirp1)) < 0.5, "near receiver's drop is not the free-space one"
    assert abs(d_far1) < 0.5, f"far receiver lost {d_far1:.2f} dB to a jammer 5 km away"
    assert abs(d_far2 - want(far_m, eirp2)) < 0.5, "far receiver's drop is not the free-space one"
    # 100x the distance, 40 dB more EIRP: the same J, the same drop.
    assert abs(d_far2 - d_near1) < 0.5, f"far at +40 dB lost {d_far2:.2f} dB, near lost {d_near1:.2f}"
    # Dead reckoning (1) for its 3 s, then none.
    assert set(fix_in_2["v0"]) <= {0, 1} and 0 in fix_in_2["v0"] and n_near2 == 0, \
        f"near receiver kept {fix_in_2['v0']}, {n_near2} sats"
    assert set(fix_in_2["v1"]) == {3}, f"far receiver lost its fix: {fix_in_2['v1']}"
    rig.finish()


def gga_gaps(ggas):
    """Epochs missing between consecutive GGA times (hhmmss.ss), at RATE_HZ."""
    def sec(f):
        return int(f[0:2]) * 3600 + int(f[2:4]) * 60 + float(f[4:])
    missed = 0
    for (_, a, _), (_, b, _) in zip(ggas, ggas[1:]):
        if a and b:
            missed += round((sec(b) - sec(a)) * RATE_HZ) - 1
    return missed


def case_jump(rig):
    place(rig, {"v0": (0.0, 0.0), "v1": (200.0, 0.0), "v2": (400.0, 0.0)})
    rig.start()
    rig.wait(all_fixed, 60, "a 3D fix on v0, v1, v2")
    time.sleep(3.0)
    before = rig.overview()
    n_before = {v: len(r.ggas) for v, r in rig.readers.items()}
    far = enu_to_latlon(ORIGIN, 200.0, 0.0)
    far = (far[0] + math.degrees(1.0e6 / 6371000.0), far[1])  # 1000 km north
    with rig.lock:
        rig.pos["v1"] = far
    t_jump = time.monotonic()
    lost = rig.wait(lambda o: o["v1"]["fix_type"] != 3 or o["v1"]["h_err_m"] is None
                    or o["v1"]["h_err_m"] > 1000.0, 20, "v1 reacting to the jump")["v1"]
    back = rig.wait(lambda o: o["v1"]["fix_type"] == 3 and o["v1"]["h_err_m"] is not None
                    and o["v1"]["h_err_m"] < FIX_TOLERANCE_M, 40, "v1's fix at the new place")
    t_back = time.monotonic() - t_jump
    st = rig.status("v1")
    assert horizontal_m(st["fix"]["lat_deg"], st["fix"]["lon_deg"], *far) < FIX_TOLERANCE_M, st["fix"]
    time.sleep(max(0.0, 8.0 - (time.monotonic() - t_jump)))
    after = rig.overview()
    for v in ("v0", "v2"):
        g = rig.readers[v].ggas[n_before[v]:]
        assert len(g) >= 10 and gga_gaps(g) == 0, f"{v}: {gga_gaps(g)} epochs missed over {len(g)} GGA"
        assert all(q == 1 for _, _, q in g), f"{v}: GGA quality {set(q for _, _, q in g)} after v1's jump"
        assert after[v]["epochs_dropped"] == before[v]["epochs_dropped"] == 0, after[v]
        assert after[v]["fix_type"] == 3 and after[v]["h_err_m"] < FIX_TOLERANCE_M, after[v]
        assert abs(after[v]["h_err_m"] - before[v]["h_err_m"]) < 5.0, (before[v], after[v])
        print(f"  {v}: {len(g)} GGA, none missed, all quality 1; error {before[v]['h_err_m']:.1f} -> "
              f"{after[v]['h_err_m']:.1f} m")
    # Handled as a real receiver carried off: no truth packet dropped, the
    # fix lost (no satellite where the receiver looked) and found again there.
    assert st["truth"]["dropped"] == 0, st["truth"]
    assert lost["fix_type"] != 3 or lost["h_err_m"] > 1000.0, lost
    print(f"  v1 jumped 1000 km: fix {lost['fix_type']} (error {lost['h_err_m']}), "
          f"3D fix at the new place {t_back:.1f} s after the jump; truth drops {st['truth']['drops']}")
    log = rig.finish()
    jumps = [ln for ln in log.splitlines() if "jumped" in ln]
    km = re.search(r"truth: vehicle 'v1' jumped ([\d.]+) km in ([\d.]+) s", jumps[0] if jumps else "")
    # The chord of a 1000 km arc north (the ECEF step), at most 0.1 s apart.
    assert len(jumps) == 1 and km and 990.0 < float(km[1]) < 1000.5 and float(km[2]) <= 0.1001 and \
        "1 jump(s) in total" in jumps[0], jumps
    assert "truth: vehicle 'v1': " in log and "; 1 jump(s)" in log, "the exit summary lacks v1's jump"
    for v in ("v0", "v2"):
        assert f"truth: vehicle '{v}': " in log and not any(f"vehicle '{v}' jumped" in ln for ln in jumps), v
    print(f"  log: {jumps[0].split('warning ')[-1]}")


def ecef(lat_deg, lon_deg, h_m):
    """WGS 84 geodetic -> ECEF, m."""
    a, f = 6378137.0, 1 / 298.257223563
    e2 = f * (2 - f)
    la, lo = math.radians(lat_deg), math.radians(lon_deg)
    n = a / math.sqrt(1 - e2 * math.sin(la) ** 2)
    return ((n + h_m) * math.cos(la) * math.cos(lo), (n + h_m) * math.cos(la) * math.sin(lo),
            (n * (1 - e2) + h_m) * math.sin(la))


def case_swarm(rig):
    """tools/senders/swarm_truth.py --count 5 --formation line --spacing 40:
    the daemon's five vehicles 40 m apart abreast, the middle one on the
    100 m circle about the origin 30 m up, each with a fix on its own."""
    rig.count = 5
    spacing_m, radius_m, up_m = 40.0, 100.0, 30.0
    sender = [sys.executable, os.path.join(HERE, "..", "..", "..", "tools", "senders", "swarm_truth.py"),
              "--port", str(rig.udp_port), "--count", "5", "--formation", "line", "--spacing", str(spacing_m),
              "--radius", str(radius_m), "--up", str(up_m), "--speed", "10", "--rate", "10", "--duration", "60"]
    rig.start(sender=sender)
    o = rig.wait(lambda o: len(o) == 5 and all_fixed(o), 60, "a 3D fix on v0 .. v4")
    ids = [f"v{i}" for i in range(5)]
    assert sorted(o) == ids and all(x["truth_source"] == "simulator" and x["truth_fresh"] for x in o.values()), o
    for _ in range(20):  # the five truths of one epoch
        st = {v: rig.status(v) for v in ids}
        if len({x["epoch"]["count"] for x in st.values()}) == 1:
            break
    else:
        raise AssertionError("no epoch read on all five receivers")
    pos = {v: ecef(x["truth"]["lat_deg"], x["truth"]["lon_deg"], x["truth"]["height_m"]) for v, x in st.items()}
    worst = 0.0
    for i in range(5):
        for j in range(i + 1, 5):
            d = math.dist(pos[ids[i]], pos[ids[j]])
            worst = max(worst, abs(d - spacing_m * (j - i)))
    assert worst < 0.5, f"spacing off by {worst:.3f} m"
    mid = st["v2"]["truth"]
    o0 = ecef(*ORIGIN)
    up = (math.cos(math.radians(ORIGIN[0])) * math.cos(math.radians(ORIGIN[1])),
          math.cos(math.radians(ORIGIN[0])) * math.sin(math.radians(ORIGIN[1])), math.sin(math.radians(ORIGIN[0])))
    rel = [p - q for p, q in zip(ecef(mid["lat_deg"], mid["lon_deg"], mid["height_m"]), o0)]
    rise = sum(r * u for r, u in zip(rel, up))
    horiz = math.sqrt(max(0.0, sum(r * r for r in rel) - rise * rise))
    assert abs(horiz - radius_m) < 0.5 and abs(rise - up_m) < 0.5, (horiz, rise)
    print(f"  swarm_truth line of 5: every pair {spacing_m:g} m x index apart (worst {worst * 100:.1f} cm), "
          f"v2 {horiz:.2f} m from the origin, {rise:.2f} m up; fixes "
          + ", ".join(f"{o[v]['h_err_m']:.1f}" for v in ids) + " m from truth")
    rig.finish()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--nav", required=True)
    ap.add_argument("case", choices=["target", "jammer", "jump", "swarm"])
    args = ap.parse_args()
    body = {"target": case_target, "jammer": case_jammer, "jump": case_jump, "swarm": case_swarm}[args.case]
    return run_rig(Rig(args), body, 90)


if __name__ == "__main__":
    sys.exit(main())
