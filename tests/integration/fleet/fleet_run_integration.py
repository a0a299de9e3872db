#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Two vehicles, three receivers in one gnssemud (docs/configuration.md
§Vehicles): vehicle "a" carries gps1 and gps2 (50 m to its right), vehicle
"b" carries gps1 1 km north of "a". One UDP socket takes truth for both
(and for 300 ids nobody configured); a private gpsd on each of the three
ptys must report a 3D fix where that antenna is; the truth each receiver
used (gnssemu ctl --vehicle/--receiver status) is its own vehicle's, with the
lever arm as the offset between a's two antennas; ctl inject/clear act on
the receivers named; /api/status?vehicle= picks one; the exit summary counts
each vehicle. Loopback only, free ports, temp dir; stops itself in 150 s.

usage: fleet_run_integration.py --gnssemud PATH --gnssemu PATH --nav FILE
"""
import json
import math
import os
import socket
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, free_port, gpsd_daemon_main, enu_to_latlon as itlib_enu_to_latlon, daemon_toml  # noqa: E402

ORIGIN = (48.8738, 2.2950, 100.0)
A_ENU = (120.0, -80.0)    # vehicle a, m east/north of the origin
B_ENU = (120.0, 920.0)    # vehicle b: 1 km north of a
LEVER_RIGHT_M = 50.0      # a/gps2: 50 m right of a (a stands still: heading north, right is east)
FIX_TOLERANCE_M = 15.0
TRUTH_TOLERANCE_M = 0.05
UNKNOWN_IDS = 300


def enu_to_latlon(e, n):
    return itlib_enu_to_latlon(ORIGIN, e, n)


def horizontal_m(lat_a, lon_a, lat_b, lon_b):
    dn = math.radians(lat_a - lat_b) * 6371000.0
    de = math.radians(lon_a - lon_b) * 6371000.0 * math.cos(math.radians(ORIGIN[0]))
    return math.hypot(de, dn)


# Where each receiver's antenna is: (vehicle, receiver) -> (lat, lon).
EXPECTED = {
    ("a", "gps1"): enu_to_latlon(*A_ENU),
    ("a", "gps2"): enu_to_latlon(A_ENU[0] + LEVER_RIGHT_M, A_ENU[1]),
    ("b", "gps1"): enu_to_latlon(*B_ENU),
}


class Rig(RigBase):
    def __init__(self, args):
        super().__init__("gnssemu-fleet-")
        self.args = args
        self.udp_port = free_port(socket.SOCK_DGRAM)
        self.http_port = free_port(socket.SOCK_STREAM)
        self.sock = os.path.join(self.tmp, "ctl.sock")
        self.stop_sending = threading.Event()

    def pty(self, v, r):
        return os.path.join(self.tmp, f"{v}-{r}")

    def start(self):
        cfg = os.path.join(self.tmp, "fleet.toml")
        with open(cfg, "w") as f:
            f.write(f"""{daemon_toml(ORIGIN, self.args.nav, "2022-01-01T01:00:00", 2.0, self.udp_port)}[status]
bind = "127.0.0.1"
port = {self.http_port}
[control]
socket = "{self.sock}"
[[vehicle]]
id = "a"
[[vehicle.receiver]]
name = "gps1"
[[vehicle.receiver.output]]
name = "a-gps1"
type = "pty"
path = "{self.pty('a', 'gps1')}"
[[vehicle.receiver]]
name = "gps2"
lever_arm_m = [0.0, {LEVER_RIGHT_M}, 0.0]
seed = 7
[[vehicle.receiver.output]]
name = "a-gps2"
type = "pty"
path = "{self.pty('a', 'gps2')}"
[[vehicle]]
id = "b"
allow = ["127.0.0.1"]
[[vehicle.receiver]]
name = "gps1"
[[vehicle.receiver.output]]
name = "b-gps1"
type = "pty"
path = "{self.pty('b', 'gps1')}"
""")
        self.daemon_log_path = os.path.join(self.tmp, "gnssemud.log")
        self.daemon_log = open(self.daemon_log_path, "w")
        self.daemon = self.spawn([self.args.gnssemud, "--config", cfg], stdout=subprocess.PIPE,
                                 stderr=self.daemon_log, text=True)
        deadline = time.monotonic() + 20
        while not all(os.path.exists(self.pty(v, r)) for v, r in EXPECTED):
            if time.monotonic() > deadline or self.daemon.poll() is not None:
                raise AssertionError("the three ptys did not appear")
            time.sleep(0.1)
        threading.Thread(target=self.send, daemon=True).start()

    def send(self):
        """10 Hz truth for a and b, and one packet each from UNKNOWN_IDS ids."""
        s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        pos = {"a": EXPECTED[("a", "gps1")], "b": EXPECTED[("b", "gps1")]}
        t = 0.0
        k = 0
        while not self.stop_sending.is_set():
            for v, (lat, lon) in pos.items():
                msg = {"version": 1, "vehicle": v, "sim_time_s": t,
                       "lla": {"lat_deg": lat, "lon_deg": lon, "height_m": ORIGIN[2]}}
                s.sendto(json.dumps(msg).encode(), ("127.0.0.1", self.udp_port))
            if k < UNKNOWN_IDS:
                for _ in range(10):
                    msg = {"version": 1, "vehicle": f"ghost{k}", "sim_time_s": t,
                           "lla": {"lat_deg": ORIGIN[0], "lon_deg": ORIGIN[1], "height_m": 0.0}}
                    s.sendto(json.dumps(msg).encode(), ("127.0.0.1", self.udp_port))
                    k += 1
            t += 0.1
            time.sleep(0.1)
        s.close()

    def ctl(self, *argv):
        out = subprocess.run([self.args.gnssemu, "ctl", "--socket", self.sock, *argv], capture_output=True,
                             text=True, timeout=15)
        if out.returncode != 0:
            raise AssertionError(f"ctl {' '.join(argv)}: rc {out.returncode}: {out.stderr}")
        return json.loads(out.stdout)


def wait_fix(rig, v, r, limit_s):
    """A TPV of mode 3 within FIX_TOLERANCE_M of (v, r)'s antenna on its gpsd."""
    lat, lon = EXPECTED[(v, r)]
    deadline = time.monotonic() + limit_s
    last = None
    while time.monotonic() < deadline:
        line = rig.pipes[(v, r)].readline()
        if not line:
            break
        try:
            m = json.loads(line)
        except ValueError:
            continue
        if m.get("class") != "TPV" or m.get("mode", 0) < 3:
            continue
        last = horizontal_m(m["lat"], m["lon"], lat, lon)
        if last < FIX_TOLERANCE_M:
            return last
    raise AssertionError(f"{v}/{r}: no 3D fix within {FIX_TOLERANCE_M} m of its antenna (last {last})")


def http_get(rig, path):
    """(status, body) of GET path on the status page."""
    try:
        with urllib.request.urlopen(f"http://127.0.0.1:{rig.http_port}{path}", timeout=5) as r:
            return r.status, r.read().decode()
    except urllib.error.HTTPError as e:
        return e.code, e.read().decode()


def check_overview(rig):
    """/api/overview: a row per receiver in config order, b's scheduled outage,
    rows equal to /api/status of the same epoch, limit/offset, bad queries 400."""
    code, text = http_get(rig, "/api/overview")
    assert code == 200, (code, text)
    o = json.loads(text)
    ids = [(x["vehicle"], x["receiver"]) for x in o["rows"]]
    assert o["total"] == 3 and ids == list(EXPECTED), o
    for x in o["rows"]:
        scheduled = 1 if x["vehicle"] == "b" else 0
        assert x["faults_scheduled"] == scheduled and x["faults_active"] == 0, x
        assert x["fix_type"] == 3 and x["truth_source"] == "simulator" and x["truth_fresh"], x
        assert x["h_err_m"] is not None and x["h_err_m"] < FIX_TOLERANCE_M, x
        assert x["ports"] == 1 and x["bytes_written"] > 0, x
    for (v, r) in EXPECTED:
        for _ in range(20):
            row = next(x for x in json.loads(http_get(rig, "/api/overview")[1])["rows"]
                       if (x["vehicle"], x["receiver"]) == (v, r))
            st = json.loads(http_get(rig, f"/api/status?history=0&vehicle={v}&receiver={r}")[1])
            if st["epoch"]["count"] == row["epochs"]:
                break
        else:
            raise AssertionError(f"{v}/{r}: /api/overview and /api/status never showed the same epoch")
        for key in ("num_used", "num_tracked", "num_visible", "h_acc_m"):
            assert row[key] == st["fix"][key], (v, r, key, row[key], st["fix"][key])
        assert row["fix_type"] == st["fix"]["type"] and row["h_err_m"] == st["error"]["h_m"], (row, st["error"])
    page = json.loads(http_get(rig, "/api/overview?limit=2&offset=1")[1])
    assert page["total"] == 3 and [(x["vehicle"], x["receiver"]) for x in page["rows"]] == list(EXPECTED)[1:], page
    # The whole fleet sorted before paging: name descending, first row b/gps1.
    page = json.loads(http_get(rig, "/api/overview?sort=name&order=desc&limit=1")[1])
    assert [(x["vehicle"], x["receiver"]) for x in page["rows"]] == list(reversed(list(EXPECTED)))[:1], page
    for query, want in [("limit=0", "limit must be a whole number in [1, 1000]"),
                        ("limit=1001", "limit must be a whole number in [1, 1000]"),
                        ("limit=ten", "not 'ten'"), ("offset=-1", "offset must be a whole number"),
                        ("limit=1&limit=2", "limit given twice"),
                        ("sort=speed", "sort must be one of name, fix, sats, herr"),
                        ("order=up", "order must be asc or desc, not 'up'"),
                        ("vehicle=a",
                         "unknown query parameter 'vehicle' (/api/overview takes limit, offset, sort, order)")]:
        code, text = http_get(rig, f"/api/overview?{query}")
        assert code == 400 and want in text, (query, code, text)
    code, text = http_get(rig, "/api/status?vehicle=a&histroy=5")
    assert code == 400 and "unknown query parameter 'histroy' (/api/status takes history, vehicle, receiver)" in text, \
        (code, text)
    print("  /api/overview: a row per receiver = /api/status, b's outage scheduled, limit/offset, sorted, bad queries 400")


def body(rig):
    rig.start()
    rig.pipes = {}
    for i, (v, r) in enumerate(EXPECTED):
        rig.pipes[(v, r)] = rig.spawn_gpsd(rig.pty(v, r), tag=str(i)).stdout
    for (v, r) in EXPECTED:
        err = wait_fix(rig, v, r, 60)
        print(f"  {v}/{r}: gpsd 3D fix {err:.1f} m from its antenna")

    # Each receiver's truth is its own vehicle's, at its antenna.
    every = rig.ctl("status")["status"]["receivers"]
    names = sorted((x["vehicle"], x["receiver"]) for x in every)
    assert names == sorted(EXPECTED), f"ctl status lists {names}"
    truth = {}
    for (v, r) in EXPECTED:
        st = rig.ctl("--vehicle", v, "--receiver", r, "status")["status"]
        truth[(v, r)] = (st["truth"]["lat_deg"], st["truth"]["lon_deg"])
        d = horizontal_m(*truth[(v, r)], *EXPECTED[(v, r)])
        assert d < TRUTH_TOLERANCE_M, f"{v}/{r}: truth {d:.3f} m from its antenna"
    lever = horizontal_m(*truth[("a", "gps2")], *truth[("a", "gps1")])
    # The same spherical measure of the 50 m east offset sent (its scale error cancels).
    want = horizontal_m(*EXPECTED[("a", "gps2")], *EXPECTED[("a", "gps1")])
    assert abs(lever - want) < TRUTH_TOLERANCE_M, f"a's antennas {lever:.3f} m apart, want {want:.3f}"
    print(f"  truth per receiver as sent; a/gps2 is {lever:.3f} m right of a/gps1 ({want:.3f} sent)")
    vehicle_b = rig.ctl("--vehicle", "b", "status")["status"]["receivers"]
    assert [x["receiver"] for x in vehicle_b] == ["gps1"], vehicle_b

    # b's [[vehicle]] allow: its packets from another sender (127.0.0.2) are
    # dropped as not_allowed and counted in b's drops, not in a's.
    def drops(v):
        return rig.ctl("--vehicle", v, "--receiver", "gps1", "status")["status"]["truth"]["drops"] or {}
    before_b, before_a = drops("b").get("not_allowed", 0), drops("a").get("not_allowed", 0)
    other = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    other.bind(("127.0.0.2", 0))
    lat, lon = EXPECTED[("b", "gps1")]
    for k in range(20):
        msg = {"version": 1, "vehicle": "b", "sim_time_s": 1000.0 + k,
               "lla": {"lat_deg": lat + 0.01, "lon_deg": lon, "height_m": ORIGIN[2]}}
        other.sendto(json.dumps(msg).encode(), ("127.0.0.1", rig.udp_port))
    other.close()
    time.sleep(1.0)
    got_b, got_a = drops("b").get("not_allowed", 0) - before_b, drops("a").get("not_allowed", 0) - before_a
    assert got_b == 20 and got_a == 0, f"not_allowed: b {got_b} (want 20), a {got_a} (want 0)"
    print(f"  b's allow: {got_b} packets for b from 127.0.0.2 dropped as not_allowed in b's drops, a's none")

    # Faults on the receivers named only.
    scen = os.path.join(rig.tmp, "outage.toml")
    with open(scen, "w") as f:
        f.write('[[event]]\ntype = "outage"\nstart_s = 30\nduration_s = 5\n')
    rig.ctl("--vehicle", "b", "inject", scen)
    time.sleep(1.2)  # the status's fault list follows at the next epoch (2 Hz)
    b_faults = rig.ctl("--vehicle", "b", "--receiver", "gps1", "status")["status"]["faults"]
    a_faults = rig.ctl("--vehicle", "a", "--receiver", "gps1", "status")["status"]["faults"]
    assert len(b_faults) == 1 and len(a_faults) == 0, (b_faults, a_faults)
    check_overview(rig)
    cleared = rig.ctl("clear")["cleared"]
    assert cleared == 1, f"clear (every receiver) removed {cleared}"
    bad = subprocess.run([rig.args.gnssemu, "ctl", "--socket", rig.sock, "--vehicle", "zz", "status"],
                         capture_output=True, text=True, timeout=15)
    assert bad.returncode == 1 and "names no vehicle" in bad.stderr, bad.stderr
    print("  ctl: inject on b only, clear on all, an unknown vehicle refused")

    # /api/status?vehicle=
    url = f"http://127.0.0.1:{rig.http_port}/api/status?history=0&vehicle=b&receiver=gps1"
    st = json.loads(urllib.request.urlopen(url, timeout=5).read())
    assert horizontal_m(st["truth"]["lat_deg"], st["truth"]["lon_deg"], *EXPECTED[("b", "gps1")]) < 0.05, st["truth"]
    try:
        urllib.request.urlopen(f"http://127.0.0.1:{rig.http_port}/api/status?vehicle=zz", timeout=5)
        raise AssertionError("/api/status?vehicle=zz answered")
    except urllib.error.HTTPError as e:
        assert e.code == 404, e.code
    print("  /api/status?vehicle=b&receiver=gps1 is b's; an unknown vehicle is 404")

    rig.stop_sending.set()
    rc = rig.stop_all()
    rig.daemon_log.flush()
    log = open(rig.daemon_log_path).read()
    assert rc == 0, f"gnssemud exit {rc}"
    for needle in ["truth: vehicle 'a':", "truth: vehicle 'b':", "unknown_vehicle"]:
        assert needle in log, f"the log lacks {needle!r}"
    assert log.count("dropped 1 packet(s)") + log.count("more packet(s)") < 50, "unknown ids logged per packet"
    print("  exit summary per vehicle; unknown ids counted, logged at a limited rate")


if __name__ == "__main__":
    sys.exit(gpsd_daemon_main(Rig, body, 150, tools=("gpsd", "gpspipe")))
