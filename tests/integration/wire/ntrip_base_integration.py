#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""gnssemud with a [base] and its NTRIP caster (docs/base-station.md).

RTKLIB's str2str pulls the base's RTCM from ntrip://user:pass@127.0.0.1:PORT/MOUNT
for a few seconds; convbin decodes it into RINEX observations of GPS,
GLONASS, Galileo and BeiDou (MSM7) and the ephemerides, and its header
holds 1006's antenna reference point, antenna height and station id. An NTRIP v2 client
(HTTP/1.1, chunked) pulls it too: every chunk well formed, every frame
CRC-clean, one bundle a second, MSMs of all four systems each epoch at 1 s
steps and 1006/1230/ephemerides exactly on the epochs of their 5 s interval;
convbin decodes that pull as well. Then the caster's answers to a wrong
mountpoint (v1: the sourcetable; v2: 404) and wrong credentials (401).

Exit 77 (CTest skip) when str2str or convbin is not installed.
"""
import argparse
import base64
import math
import os
import shutil
import socket
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, free_port  # noqa: E402
from ubx_host import crc24q, rtcm_number  # noqa: E402

MSM7 = {1077: "G", 1087: "R", 1097: "E", 1127: "C"}
STATION_5S = {1006, 1230}
EPHEMERIS_5S = {1019: "G", 1020: "R", 1042: "C", 1046: "E"}


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


def pull_v2(port, auth, seconds):
    """An NTRIP v2 client: HTTP/1.1 GET, then the chunked body for `seconds`.
    Returns (response head, body bytes, [(arrival s, chunk size)]); raises on a
    malformed chunk (NTRIP 2.0 §2.3: the data come as HTTP chunks)."""
    head = ("GET /GEMU HTTP/1.1\r\nHost: 127.0.0.1\r\nNtrip-Version: Ntrip/2.0\r\n"
            "User-Agent: NTRIP gnssemu-test\r\n" + auth + "\r\n")
    buf, body, chunks = b"", b"", []
    t0 = time.monotonic()
    with socket.create_connection(("127.0.0.1", port), timeout=3) as s:
        s.sendall(head.encode())
        while b"\r\n\r\n" not in buf:
            data = s.recv(4096)
            if not data:
                raise AssertionError(f"v2: connection closed in the response head: {buf!r}")
            buf += data
        response, buf = buf.split(b"\r\n\r\n", 1)
        response = response.decode(errors="replace")
        if not response.startswith("HTTP/1.1 200") or "transfer-encoding: chunked" not in response.lower():
            raise AssertionError(f"v2: not a chunked 200: {response!r}")
        while time.monotonic() - t0 < seconds:
            while True:  # every complete chunk in buf
                eol = buf.find(b"\r\n")
                if eol < 0:
                    break
                size = int(buf[:eol], 16)  # ValueError on a bad size line
                if size == 0:
                    raise AssertionError("v2: the caster ended the stream")
                if len(buf) < eol + 2 + size + 2:
                    break
                if buf[eol + 2 + size:eol + 4 + size] != b"\r\n":
                    raise AssertionError("v2: a chunk not followed by CRLF")
                body += buf[eol + 2:eol + 2 + size]
                chunks.append((time.monotonic() - t0, size))
                buf = buf[eol + 4 + size:]
            try:
                data = s.recv(65536)
            except socket.timeout:
                continue
            if not data:
                raise AssertionError("v2: the caster closed the connection")
            buf += data
    return response, body, chunks


def rtcm_frames(body):
    """Every RTCM 3 frame of body in order; raises on a byte outside a frame or
    a CRC-24Q error (the stream must be clean RTCM). A trailing partial frame
    is left out."""
    frames, i = [], 0
    while i + 3 <= len(body):
        if body[i] != 0xD3 or body[i + 1] & 0xFC:
            raise AssertionError(f"v2: byte {i} is not a frame start")
        n = 6 + ((body[i + 1] & 3) << 8 | body[i + 2])
        if i + n > len(body):
            break
        if crc24q(body[i:i + n - 3]) != int.from_bytes(body[i + n - 3:i + n], "big"):
            raise AssertionError(f"v2: CRC-24Q error in the frame at byte {i}")
        frames.append(body[i:i + n])
        i += n
    return frames


def msm_epoch_ms(m):
    """DF004 (GPS/Galileo/BeiDou TOW ms) or DF034 (GLONASS time of day ms) of an MSM frame."""
    v = int.from_bytes(m[3:3 + 8], "big") >> (64 - 24 - 30)
    v &= (1 << 30) - 1
    return v & ((1 << 27) - 1) if rtcm_number(m) == 1087 else v


def check_schedule(frames, interval_s):
    """Epoch bundles from the frame order (each epoch's station and ephemeris
    messages come before its MSMs): every MSM system once per epoch, epochs
    interval_s apart, 1006/1230 and the ephemerides exactly on the epochs whose
    GPS time is a multiple of 5 s. Returns (ok, summary)."""
    epochs, pending = [], []
    for m in frames:
        num = rtcm_number(m)
        if num == 1077:  # GPS leads each epoch's MSMs
            epochs.append({"tow_ms": msm_epoch_ms(m), "pre": pending, "msm": {num}})
            pending = []
        elif num in MSM7:
            if epochs and not pending:
                epochs[-1]["msm"].add(num)
        else:
            pending.append(num)
    ok = len(epochs) >= 8
    steps = sorted({(b["tow_ms"] - a["tow_ms"]) for a, b in zip(epochs, epochs[1:])})
    ok &= steps == [round(interval_s * 1000)]
    on_grid = 0
    for e in epochs[1:]:  # the first may have joined mid-bundle
        ok &= e["msm"] == set(MSM7)
        due5 = e["tow_ms"] % 5000 == 0
        on_grid += due5
        pre = set(e["pre"])
        ok &= (STATION_5S <= pre) if due5 else not (pre & STATION_5S)
        ok &= (set(EPHEMERIS_5S) <= pre) if due5 else not (pre & set(EPHEMERIS_5S))
        ok &= not (pre - STATION_5S - set(EPHEMERIS_5S))
    ok &= on_grid >= 1
    summary = (f"{len(epochs)} MSM epochs, steps {steps} ms, {on_grid} on the 5 s grid, "
               f"per 5 s epoch {[sorted(set(e['pre'])) for e in epochs[1:] if e['tow_ms'] % 5000 == 0][:1]}")
    return ok, summary


def convbin_summary(path):
    """convbin's RINEX 3.04 of an RTCM file: (observation epochs, systems, ephemerides)."""
    conv = ["convbin", "-r", "rtcm3", "-tr", time.strftime("%Y/%m/%d %H:%M:%S", time.gmtime()), "-v", "3.04",
            "-od", "-os", "-o", path + ".obs", "-n", path + ".nav", path]
    subprocess.run(conv, capture_output=True, text=True)
    epochs, systems = 0, set()
    if os.path.exists(path + ".obs"):
        with open(path + ".obs") as f:
            body = False
            for line in f:
                if "END OF HEADER" in line:
                    body = True
                elif body and line.startswith(">"):
                    epochs += 1
                elif body and line[:1] in "GRECJ":
                    systems.add(line[0])
    header = {}
    if os.path.exists(path + ".obs"):
        with open(path + ".obs") as f:
            for line in f:
                if line[60:].startswith("APPROX POSITION XYZ"):
                    header["xyz"] = [float(v) for v in line[:42].split()]
                elif line[60:].startswith("ANTENNA: DELTA H/E/N"):
                    header["delta_h"] = float(line[:14])
                elif line[60:].startswith("MARKER NAME"):
                    header["marker"] = line[:60].strip()
                elif "END OF HEADER" in line:
                    break
    navs = 0
    if os.path.exists(path + ".nav"):
        with open(path + ".nav") as f:
            navs = sum(1 for line in f if line[:1] in "GREC" and line[1:3].isdigit())
    return epochs, systems, navs, header


def ecef(lat_deg, lon_deg, h_m):
    a, f = 6378137.0, 1 / 298.257223563
    e2 = f * (2 - f)
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    n = a / math.sqrt(1 - e2 * math.sin(lat) ** 2)
    return [(n + h_m) * math.cos(lat) * math.cos(lon), (n + h_m) * math.cos(lat) * math.sin(lon),
            (n * (1 - e2) + h_m) * math.sin(lat)]


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
antenna_height_m = 1.5
messages = "1006(5),1077(1),1087(1),1097(1),1127(1),1230(5),1019(5),1020(5),1042(5),1046(5)"
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
        epochs, systems, navs, header = convbin_summary(out)
        print(f"convbin: {epochs} epochs of {sorted(systems)}, {navs} ephemerides")
        # 1006 through RTKLIB: the antenna reference point (0.1 mm resolution), its height, the station id.
        arp = ecef(48.88, 2.30, 95.0)
        off_mm = 1000 * math.dist(header.get("xyz", [0, 0, 0]), arp)
        print(f"convbin header: APPROX POSITION {off_mm:.2f} mm from [base], DELTA H {header.get('delta_h')}, "
              f"MARKER NAME {header.get('marker')!r}")
        ok &= off_mm < 1.0 and header.get("delta_h") == 1.5 and header.get("marker") == "0042"
        ok &= size > 0 and epochs >= 5 and {"G", "R", "E", "C"} <= systems and navs > 0

        good = "Authorization: Basic " + base64.b64encode(b"rover:s3cret").decode() + "\r\n"
        bad = "Authorization: Basic " + base64.b64encode(b"rover:nope").decode() + "\r\n"
        v1_wrong_mount = ask(port, "GET /NOPE HTTP/1.0\r\nUser-Agent: NTRIP test\r\n" + good + "\r\n")
        v1_wrong_pass = ask(port, "GET /GEMU HTTP/1.0\r\nUser-Agent: NTRIP test\r\n" + bad + "\r\n")
        v2 = "Host: 127.0.0.1\r\nNtrip-Version: Ntrip/2.0\r\nUser-Agent: NTRIP test\r\nConnection: close\r\n"
        v2_wrong_mount = ask(port, "GET /NOPE HTTP/1.1\r\n" + v2 + good + "\r\n")
        v2_wrong_pass = ask(port, "GET /GEMU HTTP/1.1\r\n" + v2 + bad + "\r\n")
        response, body, chunks = pull_v2(port, good, 12.0)
        frames = rtcm_frames(body)
        sched_ok, summary = check_schedule(frames, 1.0)
        gaps = [b[0] - a[0] for a, b in zip(chunks, chunks[1:]) if b[0] - a[0] > 0.5]
        print(f"v2 pull: {response.splitlines()[0]}; {len(body)} bytes in {len(chunks)} chunks, "
              f"{len(frames)} frames CRC-clean; {summary}; {sched_ok and 'ok' or 'WRONG'}")
        print(f"v2 pull: bundles {len(gaps) + 1}, spacing {min(gaps):.2f}..{max(gaps):.2f} s" if gaps else
              "v2 pull: no spacing between chunks")
        ok &= sched_ok and bool(gaps) and 0.8 < min(gaps) and max(gaps) < 1.3
        v2_file = os.path.join(rig.tmp, "v2.rtcm3")
        with open(v2_file, "wb") as f:
            f.write(body)
        v2_epochs, v2_systems, v2_navs, _ = convbin_summary(v2_file)
        print(f"v2 pull, convbin: {v2_epochs} epochs of {sorted(v2_systems)}, {v2_navs} ephemerides")
        ok &= v2_epochs >= 8 and {"G", "R", "E", "C"} <= v2_systems and v2_navs > 0
        for name, text, want in [("v1 wrong mountpoint", v1_wrong_mount, "SOURCETABLE 200 OK"),
                                 ("v1 wrong password", v1_wrong_pass, "HTTP/1.0 401 Unauthorized"),
                                 ("v2 wrong mountpoint", v2_wrong_mount, "HTTP/1.1 404 Not Found"),
                                 ("v2 wrong password", v2_wrong_pass, "HTTP/1.1 401 Unauthorized")]:
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
