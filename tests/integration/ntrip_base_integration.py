#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""gnssemud with a [base] and its NTRIP caster (docs/base-station.md).

RTKLIB's str2str pulls the base's RTCM from ntrip://user:pass@127.0.0.1:PORT/MOUNT
for a few seconds; convbin decodes it into RINEX observations of GPS,
GLONASS, Galileo and BeiDou (MSM7) and the ephemerides. Then the caster's answers to a wrong
mountpoint (v1: the sourcetable; v2: 404) and wrong credentials (401).

Exit 77 (CTest skip) when str2str or convbin is not installed.
"""
import argparse
import base64
import os
import shutil
import socket
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from itlib import RigBase, free_port  # noqa: E402


def ask(port, head):
    """The caster's answer to a request head (its first 4 KiB or until close)."""
    with socket.create_connection(("127.0.0.1", port), timeout=5) as s:
        s.sendall(head.encode())
        data = b""
        deadline = time.monotonic() + 3
        while time.monotonic() < deadline and len(data) < 4096:
            try:
                chunk = s.recv(4096)
            except socket.timeout:
                break
            if not chunk:
                break
            data += chunk
            if b"\r\n" in data and not data.startswith(b"HTTP/1.1 200") and not data.startswith(b"ICY"):
                if b"ENDSOURCETABLE" in data or b"\r\n\r\n" in data:
                    break
            if data.startswith(b"ICY") or data.startswith(b"HTTP/1.1 200"):
                break
    return data.decode(errors="replace")


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--nav", required=True)
    a = ap.parse_args()
    if shutil.which("str2str") is None or shutil.which("convbin") is None:
        print("str2str or convbin not installed (Debian rtklib)")
        return 77
    rig = RigBase("gnssemu-ntrip-")
    port = free_port(socket.SOCK_STREAM)
    cfg = os.path.join(rig.tmp, "base.toml")
    with open(cfg, "w") as f:
        f.write(f"""
[origin]
lat_deg = 48.8738
lon_deg = 2.2950
height_m = 100.0
[nav]
file = "{os.path.abspath(a.nav)}"
[receiver]
constellations = ["G", "R", "E", "C"]
[truth]
port = {free_port(socket.SOCK_DGRAM)}
[demo]
enabled = true
[base]
lat_deg = 48.88
lon_deg = 2.30
height_m = 95.0
station_id = 42
messages = "1005(5),1077(1),1087(1),1097(1),1127(1),1230(5),1019(5),1020(5),1042(5),1046(5)"
seed = 7
[base.ntrip]
port = {port}
mountpoint = "GEMU"
user = "rover"
password = "s3cret"
""")
    log = open(os.path.join(rig.tmp, "gnssemud.log"), "w")
    ok = True
    try:
        rig.daemon = rig.spawn([a.gnssemud, "--config", cfg], stdout=subprocess.DEVNULL, stderr=log)
        deadline = time.monotonic() + 20
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=0.5).close()
                break
            except OSError:
                if time.monotonic() > deadline or rig.daemon.poll() is not None:
                    raise AssertionError("the caster did not open its port")
                time.sleep(0.2)
        out = os.path.join(rig.tmp, "x.rtcm3")
        pull = ["str2str", "-in", f"ntrip://rover:s3cret@127.0.0.1:{port}/GEMU", "-out", f"file://{out}"]
        print(" ".join(pull))
        p = rig.spawn(pull, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(12)
        rig.stop(p)
        size = os.path.getsize(out) if os.path.exists(out) else 0
        print(f"str2str: {size} bytes")
        week_tow = time.gmtime()
        conv = ["convbin", "-r", "rtcm3", "-tr", time.strftime("%Y/%m/%d %H:%M:%S", week_tow), "-v", "3.04",
                "-od", "-os", "-o", out + ".obs", "-n", out + ".nav", out]
        subprocess.run(conv, capture_output=True, text=True)
        epochs, systems = 0, set()
        if os.path.exists(out + ".obs"):
            with open(out + ".obs") as f:
                body = False
                for line in f:
                    if "END OF HEADER" in line:
                        body = True
                    elif body and line.startswith(">"):
                        epochs += 1
                    elif body and line[:1] in "GRECJ":
                        systems.add(line[0])
        navs = 0
        if os.path.exists(out + ".nav"):
            with open(out + ".nav") as f:
                navs = sum(1 for line in f if line[:1] in "GREC" and line[1:3].isdigit())
        print(f"convbin: {epochs} epochs of {sorted(systems)}, {navs} ephemerides")
        ok &= size > 0 and epochs >= 5 and {"G", "R", "E", "C"} <= systems and navs > 0

        good = "Authorization: Basic " + base64.b64encode(b"rover:s3cret").decode() + "\r\n"
        bad = "Authorization: Basic " + base64.b64encode(b"rover:nope").decode() + "\r\n"
        v1_wrong_mount = ask(port, "GET /NOPE HTTP/1.0\r\nUser-Agent: NTRIP test\r\n" + good + "\r\n")
        v1_wrong_pass = ask(port, "GET /GEMU HTTP/1.0\r\nUser-Agent: NTRIP test\r\n" + bad + "\r\n")
        v2 = "Host: 127.0.0.1\r\nNtrip-Version: Ntrip/2.0\r\nUser-Agent: NTRIP test\r\nConnection: close\r\n"
        v2_wrong_mount = ask(port, "GET /NOPE HTTP/1.1\r\n" + v2 + good + "\r\n")
        v2_wrong_pass = ask(port, "GET /GEMU HTTP/1.1\r\n" + v2 + bad + "\r\n")
        v2_ok = ask(port, "GET /GEMU HTTP/1.1\r\n" + v2 + good + "\r\n")
        for name, text, want in [("v1 wrong mountpoint", v1_wrong_mount, "SOURCETABLE 200 OK"),
                                 ("v1 wrong password", v1_wrong_pass, "HTTP/1.0 401 Unauthorized"),
                                 ("v2 wrong mountpoint", v2_wrong_mount, "HTTP/1.1 404 Not Found"),
                                 ("v2 wrong password", v2_wrong_pass, "HTTP/1.1 401 Unauthorized"),
                                 ("v2 data", v2_ok, "HTTP/1.1 200 OK")]:
            good_answer = text.startswith(want)
            print(f"{name}: {text.splitlines()[0] if text else '(nothing)'} {'ok' if good_answer else 'WRONG'}")
            ok &= good_answer
        ok &= "STR;GEMU;" in v1_wrong_mount and "ENDSOURCETABLE" in v1_wrong_mount
    except AssertionError as e:
        print(e)
        ok = False
    finally:
        rc = rig.stop_all()
        log.close()
        if not ok:
            rig.dump_logs()
        rig.remove_tmp()
    ok &= rc == 0
    print("PASS" if ok else "FAIL", f"(gnssemud exit {rc})")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
