#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Truth from autopilot SITL instances: each instance's MAVLink SIM_STATE
(message 108, the simulator's true position, velocity and attitude) becomes
a gnssemud truth datagram for one vehicle (docs/sitl.md). Stdlib only.

  mavlink_truth.py --sitl v0=14570 --sitl v1=14571 --sitl v2=14572 \\
                   [--geoid-m 0] [--rate 10] [--host 127.0.0.1] [--port 5500]
  mavlink_truth.py --self-test

--sitl ID=PORT: listen on UDP 127.0.0.1:PORT for one instance's MAVLink (v1
or v2, signed or not; e.g. MAVProxy `--out udp:127.0.0.1:PORT`) and send its
truth as vehicle ID. Until SIM_STATE arrives the bridge asks the instance for
it at --rate Hz (COMMAND_LONG MAV_CMD_SET_MESSAGE_INTERVAL) every 2 s.

SIM_STATE as ArduPilot fills it (libraries/SITL/SITL.cpp, SIM::sim_state_send):
lat/lon float fields carry degrees x 1e7 despite the message definition's
[deg]; newer firmware adds lat_int/lon_int (int32, degE7) as extensions,
preferred here when present (the float fields alone resolve about 1 m).
alt is above mean sea level: --geoid-m (the
geoid undulation at the site, m) turns it into the height above the
ellipsoid that the truth protocol wants.
"""
import argparse
import json
import math
import select
import socket
import struct
import sys
import time

MSG_HEARTBEAT = 0
MSG_COMMAND_LONG = 76
MSG_SIM_STATE = 108
CRC_EXTRA = {MSG_HEARTBEAT: 50, MSG_COMMAND_LONG: 152, MSG_SIM_STATE: 32}
MAV_CMD_SET_MESSAGE_INTERVAL = 511
SIM_STATE_LEN = 92  # 84 + the lat_int/lon_int extensions
BRIDGE_SYSID, BRIDGE_COMPID = 253, 190  # a GCS-side id, away from autopilots (1) and MAVProxy (255)


def crc_x25(data, crc=0xFFFF):
    """CRC-16/MCRF4XX, MAVLink's checksum (check value of b"123456789": 0x6F91)."""
    for b in data:
        tmp = b ^ (crc & 0xFF)
        tmp = (tmp ^ (tmp << 4)) & 0xFF
        crc = ((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4)) & 0xFFFF
    return crc


def frames(datagram):
    """The MAVLink frames of one UDP datagram (senders put whole frames in a
    datagram) as (msgid, sysid, compid, payload). Bytes before a start
    marker, a start marker inside a payload (its frame would not fit or its
    checksum fails), frames of messages whose CRC_EXTRA we do not know and a
    cut frame at the end are skipped."""
    buf = datagram
    out = []
    i = 0
    while True:
        starts = [j for j in (buf.find(b"\xfe", i), buf.find(b"\xfd", i)) if j >= 0]
        if not starts:
            return out
        i = min(starts)
        if buf[i] == 0xFE:  # v1: FE len seq sys comp msg payload crc
            n = buf[i + 1] if i + 1 < len(buf) else 0
            end = i + 6 + n + 2
            if len(buf) < end:
                i += 1
                continue
            msgid, sysid, compid = buf[i + 5], buf[i + 3], buf[i + 4]
            body = buf[i + 1:i + 6 + n]
        else:  # v2: FD len incompat compat seq sys comp msgid(3) payload crc [signature 13]
            if len(buf) - i < 12:
                i += 1
                continue
            n = buf[i + 1]
            signed = buf[i + 2] & 0x01
            end = i + 10 + n + 2 + (13 if signed else 0)
            if len(buf) < end:
                i += 1
                continue
            msgid = buf[i + 7] | buf[i + 8] << 8 | buf[i + 9] << 16
            sysid, compid = buf[i + 5], buf[i + 6]
            body = buf[i + 1:i + 10 + n]
        extra = CRC_EXTRA.get(msgid)
        crc_at = i + len(body) + 1
        if extra is None or crc_x25(bytes([extra]), crc_x25(body)) != struct.unpack_from("<H", buf, crc_at)[0]:
            i += 1  # not a frame after all, or not ours: resynchronise on the next marker
            continue
        payload = body[5:] if buf[i] == 0xFE else body[9:]
        out.append((msgid, sysid, compid, payload))
        i = end


def encode_v2(msgid, payload, seq=0, sysid=BRIDGE_SYSID, compid=BRIDGE_COMPID, incompat=0):
    """A MAVLink 2 frame (trailing zero bytes of the payload truncated, as the spec asks); incompat bit 0
    announces a signature, which the caller appends."""
    payload = payload.rstrip(b"\x00") or payload[:1]
    body = struct.pack("<BBBBBB", len(payload), incompat, 0, seq & 0xFF, sysid, compid) + \
        struct.pack("<I", msgid)[:3] + payload
    return b"\xfd" + body + struct.pack("<H", crc_x25(bytes([CRC_EXTRA[msgid]]), crc_x25(body)))


def encode_v1(msgid, payload, seq=0, sysid=1, compid=1):
    body = struct.pack("<BBBBB", len(payload), seq & 0xFF, sysid, compid, msgid) + payload
    return b"\xfe" + body + struct.pack("<H", crc_x25(bytes([CRC_EXTRA[msgid]]), crc_x25(body)))


def interval_request(target_sys, target_comp, rate_hz):
    """COMMAND_LONG SET_MESSAGE_INTERVAL(SIM_STATE, 1e6 / rate_hz us)."""
    params = (float(MSG_SIM_STATE), 1e6 / rate_hz, 0.0, 0.0, 0.0, 0.0, 0.0)
    return encode_v2(MSG_COMMAND_LONG, struct.pack("<7fHBBB", *params, MAV_CMD_SET_MESSAGE_INTERVAL,
                                                   target_sys, target_comp, 0))


def sim_state(payload):
    """SIM_STATE payload -> dict (lat/lon deg, alt_msl m, vn/ve/vd m/s, roll/pitch/yaw rad) or None if the
    position is not set (0, 0) or out of range."""
    p = payload.ljust(SIM_STATE_LEN, b"\x00")
    f = struct.unpack_from("<21f", p)
    lat_int, lon_int = struct.unpack_from("<ii", p, 84)
    if lat_int or lon_int:
        lat, lon = lat_int * 1e-7, lon_int * 1e-7
    else:
        lat, lon = f[13], f[14]
        if abs(lat) > 90.0 or abs(lon) > 180.0:  # ArduPilot's degE7 in the float fields
            lat, lon = lat * 1e-7, lon * 1e-7
    if not all(math.isfinite(x) for x in (lat, lon, f[15], f[18], f[19], f[20])):
        return None
    if (lat == 0.0 and lon == 0.0) or abs(lat) > 90.0 or abs(lon) > 180.0:
        return None
    return {"lat_deg": lat, "lon_deg": lon, "alt_msl_m": f[15], "vn": f[18], "ve": f[19], "vd": f[20],
            "roll_rad": f[4], "pitch_rad": f[5], "yaw_rad": f[6]}


def truth_packet(vehicle, sim_time_s, s, geoid_m):
    msg = {"version": 1, "vehicle": vehicle, "sim_time_s": sim_time_s,
           "lla": {"lat_deg": s["lat_deg"], "lon_deg": s["lon_deg"], "height_m": s["alt_msl_m"] + geoid_m},
           "vel_enu": {"e_m_s": s["ve"], "n_m_s": s["vn"], "u_m_s": -s["vd"]}}
    return json.dumps(msg, allow_nan=False).encode()


def run(args):
    out = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    links = []  # one per SITL instance
    for spec in args.sitl:
        vehicle, _, port = spec.partition("=")
        if not vehicle or not port.isdigit() or not 0 < int(port) < 65536:
            sys.exit(f"--sitl {spec!r}: want ID=PORT (e.g. v0=14570)")
        s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        try:
            s.bind(("127.0.0.1", int(port)))
        except OSError as e:
            sys.exit(f"--sitl {spec}: cannot listen on 127.0.0.1:{port}: {e}")
        links.append({"vehicle": vehicle, "sock": s, "peer": None, "target": None,
                      "asked": 0.0, "got": 0, "sent": 0, "t0": time.monotonic(), "last_t": -1.0})
    print(f"mavlink_truth: {len(links)} instance(s) -> {args.host}:{args.port}", flush=True)
    by_fd = {l["sock"].fileno(): l for l in links}
    while True:
        ready, _, _ = select.select(list(by_fd), [], [], 0.5)
        now = time.monotonic()
        for fd in ready:
            link = by_fd[fd]
            data, peer = link["sock"].recvfrom(65536)
            link["peer"] = peer
            for msgid, sysid, compid, payload in frames(data):
                if msgid == MSG_HEARTBEAT and link["target"] is None and sysid != 255:
                    link["target"] = (sysid, compid)
                if msgid != MSG_SIM_STATE:
                    continue
                link["got"] += 1
                state = sim_state(payload)
                t = now - link["t0"]
                if state is None or t <= link["last_t"]:
                    continue
                link["last_t"] = t
                out.sendto(truth_packet(link["vehicle"], t, state, args.geoid_m), (args.host, args.port))
                link["sent"] += 1
        for link in links:
            if link["got"] == 0 and link["peer"] and link["target"] and now - link["asked"] > 2.0:
                link["sock"].sendto(interval_request(*link["target"], args.rate), link["peer"])
                link["asked"] = now


def self_test():
    assert crc_x25(b"123456789") == 0x6F91, hex(crc_x25(b"123456789"))
    lat, lon, alt = -35.3632621, 149.1652374, 584.09
    floats = [1, 0, 0, 0, 0.01, -0.02, 1.5, 0, 0, -9.8, 0, 0, 0, lat * 1e7, lon * 1e7, alt, 0, 0, 3.0, 4.0, -0.5]
    full = struct.pack("<21f", *floats) + struct.pack("<ii", round(lat * 1e7), round(lon * 1e7))
    old = struct.pack("<21f", *floats)  # firmware without the extensions
    stream = b"junk\xfe\x03" + encode_v2(MSG_SIM_STATE, full, 1) + encode_v1(MSG_SIM_STATE, old, 2)
    stream += encode_v2(MSG_SIM_STATE, full, 3, incompat=0x01) + bytes(13)  # signed: 13 bytes after the checksum
    bad = bytearray(encode_v2(MSG_SIM_STATE, full, 4))
    bad[20] ^= 0xFF  # corrupted payload: dropped
    stream += bytes(bad) + encode_v2(MSG_HEARTBEAT, bytes(9), 5)
    stream += encode_v2(MSG_SIM_STATE, full, 6)
    got = frames(stream + encode_v2(MSG_SIM_STATE, full, 7)[:40])  # a cut frame at the end: skipped
    assert [m for m, *_ in got] == [MSG_SIM_STATE] * 3 + [MSG_HEARTBEAT, MSG_SIM_STATE], [m for m, *_ in got]
    assert frames(b"") == [] and frames(b"\xfd") == [] and frames(b"\xfe\xff") == []
    for k, (_, _, _, payload) in enumerate(got[:3]):
        s = sim_state(payload)
        tol = 2e-5 if k == 1 else 1e-7  # float32 degE7 of old firmware: 128e-7 deg steps at 149 deg
        assert abs(s["lat_deg"] - lat) < tol and abs(s["lon_deg"] - lon) < tol, s
        assert abs(s["alt_msl_m"] - alt) < 1e-3 and (s["vn"], s["ve"], s["vd"]) == (3.0, 4.0, -0.5), s
    pkt = json.loads(truth_packet("v0", 1.5, sim_state(got[0][3]), 20.0))
    assert pkt["vehicle"] == "v0" and abs(pkt["lla"]["height_m"] - (alt + 20.0)) < 1e-3, pkt
    assert pkt["vel_enu"] == {"e_m_s": 4.0, "n_m_s": 3.0, "u_m_s": 0.5}, pkt
    unset = struct.pack("<21f", *([0.0] * 21))
    assert sim_state(unset) is None
    req = frames(interval_request(1, 1, 10.0))
    assert req and req[0][0] == MSG_COMMAND_LONG
    p = struct.unpack("<7fHBBB", req[0][3].ljust(33, b"\x00"))
    assert p[0] == 108.0 and p[1] == 100000.0 and p[7] == MAV_CMD_SET_MESSAGE_INTERVAL and p[8:10] == (1, 1), p
    print("mavlink_truth self-test: passed")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--sitl", action="append", default=[], metavar="ID=PORT",
                   help="a SITL instance's MAVLink on UDP 127.0.0.1:PORT, truth sent as vehicle ID (repeat)")
    p.add_argument("--geoid-m", type=float, default=0.0,
                   help="geoid undulation at the site, m: SIM_STATE alt (MSL) + this = height above the ellipsoid")
    p.add_argument("--rate", type=float, default=10.0, help="SIM_STATE rate asked of each instance, Hz")
    p.add_argument("--host", default="127.0.0.1")
    p.add_argument("--port", type=int, default=5500, help="gnssemud's [truth] port")
    p.add_argument("--self-test", action="store_true", help="check the frame parser and conversions, then exit")
    args = p.parse_args()
    if args.self_test:
        self_test()
        return
    if not args.sitl:
        p.error("give at least one --sitl ID=PORT (or --self-test)")
    if not 0.1 <= args.rate <= 400:
        p.error("--rate: want 0.1 .. 400 Hz")
    try:
        run(args)
    except KeyboardInterrupt:
        pass


if __name__ == "__main__":
    main()
