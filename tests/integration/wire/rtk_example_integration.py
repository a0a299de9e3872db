#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""config/examples/rtk.toml as docs/rtk.md runs it (its contract: the base's
RTCM on the tcp output "base", the rover's NMEA/UBX on the pty output
"rover", which takes RTCM 3 in).

tools/senders/rtcm_forward.py copies the base's bytes into the rover's pty;
a second port of the rover's chip feeds a read-only gpsd, whose TPV status
goes RTK float, then RTK fixed (when gpsd is installed);
the rover counts them (RXM-RTCM per message once a host enables it with
CFG-MSG; corrections in /api/status), the correction age stays near one
epoch while the feed runs and grows once it stops.

The example is copied with its ports, paths and nav file made local to the
run; nothing else changes.
"""
import argparse
import json
import os
import re
import select
import shutil
import socket
import subprocess
import sys
import time
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, free_port, run_rig  # noqa: E402
from ubx_host import crc24q  # noqa: E402

RXM_RTCM = b"\xb5\x62\x02\x32\x08\x00"
DGNSSTO_KEY = 0x201100C4  # CFG-NAVSPG-CONSTR_DGNSSTO, U1 s
DGNSS_TIMEOUT_S = 10


def ubx(cls, mid, payload):
    body = bytes([cls, mid, len(payload) & 0xFF, len(payload) >> 8]) + bytes(payload)
    a = b = 0
    for c in body:
        a = (a + c) & 0xFF
        b = (b + a) & 0xFF
    return b"\xb5\x62" + body + bytes([a, b])


def read_some(fd):
    """What the pty has within 0.5 s (b"" if nothing)."""
    r, _, _ = select.select([fd], [], [], 0.5)
    if not r:
        return b""
    try:
        return os.read(fd, 65536)
    except BlockingIOError:
        return b""


def status(port):
    with urllib.request.urlopen(f"http://127.0.0.1:{port}/api/status?history=0", timeout=5) as r:
        return json.loads(r.read())


def wait_for(pred, limit_s, what):
    deadline = time.monotonic() + limit_s
    while time.monotonic() < deadline:
        v = pred()
        if v:
            return v
        time.sleep(0.2)
    raise AssertionError(f"no {what} within {limit_s:.0f} s")


def local_example(source, tmp):
    """The example with this run's ports and paths; (config path, ports)."""
    text = open(os.path.join(source, "config/examples/rtk.toml")).read()
    # The contract the docs and other tests rely on.
    assert re.search(r'\[\[base\.output\]\][^\[]*name = "base"[^\[]*type = "tcp"', text), "no tcp [[base.output]] 'base'"
    assert re.search(r'\[\[output\]\][^\[]*name = "rover"[^\[]*type = "pty"', text), "no pty [[output]] 'rover'"
    assert '"rtcm3"' in text, "the rover's port does not take RTCM 3"
    ports = {"base": free_port(socket.SOCK_STREAM), "truth": free_port(socket.SOCK_DGRAM),
             "status": free_port(socket.SOCK_STREAM)}
    nav = os.path.join(source, "config/nav/BRDC00IGS_R_20240100000_01D_MN_gnssemu.rnx.gz")
    text = text.replace('"../nav/BRDC00IGS_R_20240100000_01D_MN_gnssemu.rnx.gz"', json.dumps(nav))
    text = text.replace('path = "/tmp/gnssemu/rover"', f'path = "{tmp}/rover"')
    text = re.sub(r"(\[\[base\.output\]\][^\[]*port = )2102", rf"\g<1>{ports['base']}", text)
    text = re.sub(r"(\[truth\][^\[]*port = )5500", rf"\g<1>{ports['truth']}", text)
    text += f"\n[status]\nport = {ports['status']}\n"
    # A second port of the rover's chip for gpsd (read-only), NMEA as the first sends it.
    text += (f'\n[[output]]\nname = "rover-gpsd"\ntype = "pty"\npath = "{tmp}/rover-gpsd"\nbaud = 115200\n'
             'sentences = ["GGA", "RMC", "GSA", "GSV", "GST"]\n')
    path = os.path.join(tmp, "rtk.toml")
    open(path, "w").write(text)
    return path, ports, ("generation = \"f9p\"" in text)


GGA_QUALITY = re.compile(rb"\$G[NP]GGA,[^,]*,[^,]*,[^,]*,[^,]*,[^,]*,(\d)")


def check_rtk_quality(received, t_first_fixed, is_f9p):
    """An F9P rover with the feed running: GGA quality 5 (float) before 4
    (fixed), and fixed in the end; another chip reports no RTK state."""
    qualities = [int(m.group(1)) for m in GGA_QUALITY.finditer(received)]
    print(f"GGA qualities in order of first sight: {list(dict.fromkeys(qualities))}, "
          f"fixed {t_first_fixed if t_first_fixed is None else round(t_first_fixed, 1)} s after the feed started")
    if not is_f9p:
        assert not {4, 5} & set(qualities), "a chip without RTK reported an RTK state"
        return
    assert 4 in qualities, f"no RTK fixed GGA (qualities {sorted(set(qualities))})"
    first_fixed = qualities.index(4)
    assert 5 in qualities[:first_fixed], "RTK fixed without float before it"
    assert qualities[-1] == 4, f"the last GGA is quality {qualities[-1]}, not fixed"


class Rig(RigBase):
    def __init__(self, a):
        super().__init__("gnssemu-rtk-")
        self.a = a


def body(rig):
    a = rig.a
    cfg, ports, is_f9p = local_example(os.path.abspath(a.source), rig.tmp)
    rig.daemon_log = open(os.path.join(rig.tmp, "gnssemud.log"), "w")
    rig.daemon = rig.spawn([a.gnssemud, "--config", cfg], stdout=subprocess.DEVNULL, stderr=rig.daemon_log)
    pty = os.path.join(rig.tmp, "rover")
    wait_for(lambda: os.path.exists(pty), 20, "rover pty")
    wait_for(lambda: status(ports["status"]), 20, "status page")
    fd = os.open(pty, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
    os.write(fd, ubx(0x06, 0x01, [0x02, 0x32, 1]))  # CFG-MSG: RXM-RTCM on this port
    gpsd = shutil.which("gpsd") is not None and shutil.which("gpspipe") is not None
    if gpsd:
        wait_for(lambda: os.path.exists(os.path.join(rig.tmp, "rover-gpsd")), 10, "rover-gpsd pty")
        rig.watch_gpsd(rig.spawn_gpsd(os.path.join(rig.tmp, "rover-gpsd")).stdout)
    fwd_log = open(os.path.join(rig.tmp, "forward.log"), "w")
    fwd = rig.spawn([sys.executable, os.path.join(a.source, "tools/senders/rtcm_forward.py"),
                     "--from", f"127.0.0.1:{ports['base']}", "--to", pty, "--report", "2"],
                    stdout=fwd_log, stderr=subprocess.STDOUT)
    received = b""
    t_feed = time.monotonic()
    t_first_fixed = None
    # At least 12 s; an F9P until it has been fixed for 3 s (at most 90 s).
    while True:
        now = time.monotonic()
        if now - t_feed >= 12 and (not is_f9p or now - t_feed >= 90 or
                                   (t_first_fixed is not None and now - t_feed >= t_first_fixed + 3)):
            break
        received += read_some(fd)
        if t_first_fixed is None and any(m.group(1) == b"4" for m in GGA_QUALITY.finditer(received)):
            t_first_fixed = time.monotonic() - t_feed
    reports = received.count(RXM_RTCM)
    s = status(ports["status"])["corrections"]
    print(f"feeding: RXM-RTCM {reports}, status corrections {s}")
    assert reports >= 5, f"only {reports} RXM-RTCM"
    assert s["messages"] >= 5 and s["used"] >= 5, s
    assert s["epochs"] >= 3, s
    assert s["station_id"] == 42, s
    assert s["age_s"] is not None and s["age_s"] <= 2.5, s
    check_rtk_quality(received, t_first_fixed, is_f9p)
    if gpsd and is_f9p:
        # gpsd 3.22 (gps.h): TPV status 4 RTK float, 3 RTK fixed, from the GGA quality.
        statuses = []
        while not rig.tpvs.empty():
            statuses.append(rig.tpvs.get()[1].get("status", 1))
        seen = list(dict.fromkeys(statuses))
        print(f"gpsd on the rover's second port: TPV statuses in order of first sight {seen}, "
              f"{statuses.count(3)} of {len(statuses)} TPVs RTK fixed")
        assert 3 in statuses and 4 in statuses[:statuses.index(3)], f"gpsd TPV statuses {seen}: no float then fixed"
        assert statuses[-1] == 3, f"gpsd's last TPV status {statuses[-1]}, not RTK fixed"

    if is_f9p:
        # As a host does: corrections older than 10 s are not used (CFG-NAVSPG-CONSTR_DGNSSTO, RAM).
        os.write(fd, ubx(0x06, 0x8A, [0, 1, 0, 0] + list(DGNSSTO_KEY.to_bytes(4, "little")) + [DGNSS_TIMEOUT_S]))
    rig.stop(fwd)
    fwd_log.close()
    t_stop = time.monotonic()
    after_stop = b""
    while time.monotonic() - t_stop < 6:
        after_stop += read_some(fd)
    after = status(ports["status"])["corrections"]
    print(f"feed stopped 6 s: status corrections {after}")
    assert after["age_s"] >= s["age_s"] + 4.0, (s, after)
    assert after["messages"] == s["messages"] or after["messages"] - s["messages"] < 20
    if is_f9p:
        # Back to a standalone (1) or differential (2) fix once the corrections time out.
        t_standalone = None
        while time.monotonic() - t_stop < DGNSS_TIMEOUT_S + 20 and t_standalone is None:
            after_stop += read_some(fd)
            tail = [int(m.group(1)) for m in GGA_QUALITY.finditer(after_stop)][-2:]
            if tail and all(q in (1, 2) for q in tail) and 1 in tail:
                t_standalone = time.monotonic() - t_stop
        seen = list(dict.fromkeys(int(m.group(1)) for m in GGA_QUALITY.finditer(after_stop)))
        print(f"feed stopped: GGA qualities {seen}, standalone {t_standalone} s after the stop "
              f"(DGNSS timeout {DGNSS_TIMEOUT_S} s)")
        assert t_standalone is not None, f"still RTK/DGNSS {DGNSS_TIMEOUT_S + 20} s after the feed stopped: {seen}"
        assert t_standalone >= DGNSS_TIMEOUT_S - 3, f"standalone after {t_standalone:.1f} s, before the timeout"
    # Bad RTCM from the host (rtk-raw.md §2.1): a 1005 frame with a broken
    # CRC-24Q, then one cut short by a UBX poll. Counted as CRC failures; the
    # chip still answers the poll and its status page still serves.
    payload = bytes([0x3E, 0xD0, 0x2A]) + bytes(16)
    frame = bytes([0xD3, 0x00, len(payload)]) + payload
    frame += crc24q(frame).to_bytes(3, "big")
    broken = frame[:-1] + bytes([frame[-1] ^ 0xFF])
    mon_ver = b"\xb5\x62\x0a\x04"
    before_bad = status(ports["status"])["corrections"]["crc_failed"]
    os.write(fd, broken + frame[:8] + ubx(0x0A, 0x04, []))
    answer = b""
    t_bad = time.monotonic()
    while time.monotonic() - t_bad < 3 and mon_ver not in answer:
        answer += read_some(fd)
    after_bad = before_bad
    while time.monotonic() - t_bad < 5 and after_bad == before_bad:  # the page takes the chip's counts each epoch
        time.sleep(0.5)
        after_bad = status(ports["status"])["corrections"]["crc_failed"]
    print(f"bad RTCM from the host: crc_failed {before_bad} -> {after_bad}, "
          f"MON-VER answered: {mon_ver in answer}")
    assert after_bad >= before_bad + 1, (before_bad, after_bad)
    assert mon_ver in answer, "no MON-VER after a truncated RTCM frame"
    os.close(fd)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--source", required=True, help="the project's source tree")
    a = ap.parse_args()
    return run_rig(Rig(a), body, 200)


if __name__ == "__main__":
    sys.exit(main())
