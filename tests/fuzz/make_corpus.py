#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Writes the hand-made seed inputs (corpus/<target>/) and dictionaries
(dict/<target>.dict) of the fuzz targets: what tests/data lacks (truth
packets, host command sequences, gzip and binary variants) and the keywords
of each format. Run from anywhere; rewrites the files, so the result is
reviewable in git. Layouts: docs/truth-protocol.md, docs/ubx.md, the PLY and
OBJ readers in core/scene, docs/configuration.md.
"""
import gzip
import math
import pathlib
import re
import struct
import sys

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent.parent


def write(target, name, data):
    d = HERE / "corpus" / target
    d.mkdir(parents=True, exist_ok=True)
    (d / name).write_bytes(data if isinstance(data, bytes) else data.encode())


def write_dict(target, words):
    lines = ["# libFuzzer dictionary for fuzz_%s (written by make_corpus.py)" % target]
    for w in sorted(set(words)):
        esc = "".join(c if 0x20 <= ord(c) < 0x7F and c not in '"\\' else "\\x%02X" % ord(c) for c in w)
        lines.append('"%s"' % esc)
    (HERE / "dict").mkdir(exist_ok=True)
    (HERE / "dict" / ("%s.dict" % target)).write_text("\n".join(lines) + "\n")


# --- truth packets (docs/truth-protocol.md) ----------------------------------

def truth_record(flags, vehicle=b"ego", sim=12.3, week=0, tow=0.0, pos=(0, 0, 0), vel=(0, 0, 0), att=(0, 0, 0)):
    rec = bytes([0xF7]) + b"GTR" + struct.pack("<BBH", 1, flags, week) + vehicle.ljust(64, b"\0")
    rec += struct.pack("<dd", sim, tow) + struct.pack("<3d", *pos) + struct.pack("<3d", *vel) + struct.pack("<3d", *att)
    assert len(rec) == 160
    return rec


def truth_corpus():
    write("truth_packet", "lla.json",
          '{"version":1,"vehicle":"ego","sim_time_s":12.3,"lla":{"lat_deg":48.87,"lon_deg":2.29,"height_m":100}}')
    write("truth_packet", "ecef_vel.json",
          '{"version":1,"vehicle":"car 2","sim_time_s":0.01,"ecef":{"x_m":4201575.4,"y_m":168406.6,"z_m":4779210.7},'
          '"vel_ecef":{"x_m_s":1.5,"y_m_s":-2.0,"z_m_s":0.1}}')
    write("truth_packet", "enu_gps_time.json",
          '{"version":1,"vehicle":"ego","sim_time_s":100.0,"enu":{"e_m":10.5,"n_m":-3.25,"u_m":1.5},'
          '"vel_enu":{"e_m_s":5,"n_m_s":0,"u_m_s":0},"gps_week":2190,"gps_tow_s":522000.0}')
    write("truth_packet", "nan_literal.json",
          '{"version":1,"vehicle":"ego","sim_time_s":NaN,"lla":{"lat_deg":48.87,"lon_deg":2.29,"height_m":100}}')
    write("truth_packet", "repeated_key.json",
          '{"version":1,"vehicle":"ego","vehicle":"b","sim_time_s":1,"lla":{"lat_deg":1,"lon_deg":2,"height_m":3}}')
    write("truth_packet", "lla.bin", truth_record(0x00, pos=(48.87, 2.29, 100.0)))
    write("truth_packet", "ecef_vel_att_gps.bin",
          truth_record(0x01 | 0x08 | 0x10 | 0x20, vehicle=b"truck-7", week=2190, tow=522000.5,
                       pos=(4201575.4, 168406.6, 4779210.7), vel=(1.0, 2.0, 0.5), att=(0.1, -0.05, math.pi / 2)))
    write("truth_packet", "enu_vel_enu.bin", truth_record(0x02 | 0x04, pos=(10.0, -20.0, 2.0), vel=(3.0, 4.0, 0.0)))


# --- host input to the emulated u-blox (docs/ubx.md) -------------------------

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "integration"))
from ubx_host import frame as ubx  # noqa: E402  (one UBX framer for hosts and seeds)


def nmea(body):
    cs = 0
    for c in body.encode():
        cs ^= c
    return ("$%s*%02X\r\n" % (body, cs)).encode()


def px4_m9_probe():
    from ubx_host import px4_m9_probe_payload  # noqa: E402
    return px4_m9_probe_payload()


def px4_m9_valsets():
    """The CFG-VALSET payloads of PX4's M9 configuration (ubx_host.px4_startup_m9)."""
    from ubx_host import px4_m9_valset_payloads  # noqa: E402
    return [payload for payload, _ in px4_m9_valset_payloads()]


def ubx_corpus():
    # PX4's start-up (tests/integration/ubx_host.py px4_startup).
    nav5 = bytearray(36)
    struct.pack_into("<HBB", nav5, 0, 0x0005, 7, 3)
    px4 = bytes.fromhex("B5620601FF03") + ubx(0x0A, 0x04)
    px4 += ubx(0x06, 0x8A, bytes([0, 1, 0, 0]) + struct.pack("<II", 0x40520001, 115200))
    px4 += ubx(0x06, 0x00, struct.pack("<BBHIIHHHH", 1, 0, 0, 0x08D0, 9600, 1, 1, 0, 0))
    px4 += ubx(0x0A, 0x04) + ubx(0x06, 0x08, struct.pack("<HHH", 200, 1, 0)) + ubx(0x06, 0x24, bytes(nav5))
    for cls, mid, rate in ((1, 7, 1), (1, 3, 1), (1, 4, 1), (1, 0x30, 5), (0x0A, 9, 5)):
        px4 += ubx(0x06, 0x01, bytes([cls, mid, rate]))
    px4 += ubx(0x01, 0x03) + ubx(0x06, 0x04, bytes([0xFF, 0xFF, 0x02, 0x00]))
    write("ubx_device", "px4_startup.bin", px4)
    # ArduPilot's probe and poll / set / poll-compare.
    ap = nmea("PUBX,41,1,0023,0001,230400,0")
    for (cls, mid), rate in {(1, 7): 1, (1, 3): 1, (1, 6): 1, (1, 0x12): 1, (1, 4): 2, (0x0A, 9): 2}.items():
        ap += ubx(0x06, 0x01, bytes([cls, mid])) + ubx(0x06, 0x01, bytes([cls, mid, rate]))
    ap += ubx(0x06, 0x08) + ubx(0x06, 0x08, struct.pack("<HHH", 200, 1, 0)) + ubx(0x06, 0x00, bytes([1]))
    ap += ubx(0x06, 0x24) + ubx(0x06, 0x3E) + ubx(0x06, 0x16) + ubx(0x06, 0x16, bytes([0, 3, 3, 0, 0, 0, 0, 0]))
    ap += ubx(0x0A, 0x04) + ubx(0x01, 0x30)
    write("ubx_device", "ardupilot_startup.bin", ap)
    # NMEA host commands and polls, CFG-CFG save/clear/load, resets, other ports.
    misc = nmea("PUBX,40,GGA,0,1,0,0,0,0") + nmea("PUBX,40,ZDA,0,1,0,0,0,0") + nmea("GPGPQ,GGA") + nmea("EIGNQ,RMC")
    misc += nmea("PUBX,41,1,0003,0003,38400,0") + b"$GPGGA,garbage*00\r\n"
    misc += ubx(0x06, 0x09, struct.pack("<III", 0, 0xFFFF, 0) + bytes([0x17]))  # save all
    misc += ubx(0x06, 0x09, struct.pack("<III", 0xFFFF, 0, 0xFFFF))  # clear + load
    misc += ubx(0x06, 0x00, bytes([3])) + ubx(0x06, 0x00, bytes([0])) + ubx(0x06, 0x00, bytes([4]))
    misc += ubx(0x06, 0x01, bytes([0xF0, 0x00, 0, 1, 0, 1, 0, 0]))  # CFG-MSG all ports
    misc += ubx(0x06, 0x31, bytes([0])) + ubx(0x06, 0x02, bytes([1])) + ubx(0x06, 0x17) + ubx(0x06, 0x1B)
    misc += ubx(0x06, 0x04, bytes([0, 0, 1, 0])) + ubx(0x06, 0x04, bytes([0, 0, 8, 0]))
    write("ubx_device", "commands_polls_resets.bin", misc)

    # PX4's M9 start-up (ubx_host.px4_startup_m9) and the rest of the
    # configuration interface: VALSET transactions and bad sets, VALGET of
    # single keys, a group and every key (paged), VALDEL. The last byte (the
    # first control byte) 0x02 makes the chip an M9.
    m9 = ubx(0x06, 0x8A, px4_m9_probe()) + ubx(0x06, 0x8A, bytes([0, 1, 0, 0]) + struct.pack("<II", 0x40520001, 115200))
    m9 += ubx(0x0A, 0x04) + b"".join(ubx(0x06, 0x8A, p) for p in px4_m9_valsets())
    rate = struct.pack("<IH", 0x30210001, 200)
    m9 += ubx(0x06, 0x8A, bytes([1, 1, 1, 0]) + rate) + ubx(0x06, 0x8A, bytes([1, 1, 2, 0]) + struct.pack("<IB", 0x20910007, 1))
    m9 += ubx(0x06, 0x8A, bytes([1, 1, 3, 0])) + ubx(0x06, 0x8A, bytes([1, 3, 2, 0]))  # apply; ongoing without start
    m9 += ubx(0x06, 0x8A, bytes([0, 1, 0, 0]) + struct.pack("<IB", 0x20110021, 1))  # dynModel 1: NAK
    m9 += ubx(0x06, 0x8A, bytes([0, 6, 0, 0]) + struct.pack("<II", 0x40520001, 115200))  # BBR+Flash baud
    m9 += ubx(0x06, 0x8B, struct.pack("<BBHII", 0, 0, 0, 0x30210001, 0x20910007))
    m9 += ubx(0x06, 0x8B, struct.pack("<BBHI", 0, 7, 0, 0x0021FFFF))
    m9 += ubx(0x06, 0x8B, struct.pack("<BBHI", 0, 1, 64, 0x0FFFFFFF))
    m9 += ubx(0x06, 0x8C, struct.pack("<BBHI", 0, 2, 0, 0x0091FFFF)) + ubx(0x06, 0x09, struct.pack("<III", 0, 0, 0xFFFF))
    write("ubx_device", "px4_m9_valset_valget.bin", m9 + b"\x02")

    # CFG-GNSS (M8) as PX4 sends it (GPS + SBAS + GLONASS), then impossible sets:
    # four major GNSS, more channels than the chip has, numTrkChUse > numTrkChHw,
    # an enabled system without a signal, GPS L2C, unknown gnssId 7, 8 blocks;
    # MON-GNSS and MON-HW2 polls; CFG-MSG MON-HW2 at 5 (docs/ubx.md "Multi-GNSS").
    def blk(gnss_id, res, mx, flags):
        return struct.pack("<BBBBI", gnss_id, res, mx, 0, flags)
    good = bytes([0, 0, 0xFF, 3]) + blk(0, 8, 16, 0x10001) + blk(1, 1, 3, 0x10001) + blk(6, 8, 14, 0x10001)
    gnss = ubx(0x06, 0x3E) + ubx(0x06, 0x3E, good) + ubx(0x0A, 0x28)
    gnss += ubx(0x06, 0x3E, bytes([0, 32, 32, 2]) + blk(2, 4, 8, 0x10001) + blk(3, 8, 16, 0x10001))
    gnss += ubx(0x06, 0x3E, bytes([0, 32, 32, 1]) + blk(0, 200, 255, 0x10001))
    gnss += ubx(0x06, 0x3E, bytes([0, 32, 99, 1]) + blk(0, 8, 16, 0x10001))
    gnss += ubx(0x06, 0x3E, bytes([0, 32, 32, 1]) + blk(0, 8, 16, 0x00001))
    gnss += ubx(0x06, 0x3E, bytes([0, 32, 32, 1]) + blk(0, 8, 16, 0x110001))
    gnss += ubx(0x06, 0x3E, bytes([0, 32, 32, 1]) + blk(7, 0, 8, 0x10001))
    gnss += ubx(0x06, 0x3E, bytes([0, 32, 32, 8]) + b"".join(blk(i % 7, 1, 4, 0x10001) for i in range(8)))
    gnss += ubx(0x06, 0x01, bytes([0x0A, 0x0B, 5])) + ubx(0x0A, 0x0B) + ubx(0x01, 0x23) + ubx(0x01, 0x24)
    write("ubx_device", "cfg_gnss_impossible.bin", gnss)

    # CFG-SIGNAL VALSETs on the M9: PX4's five ENA keys, SBAS alone, then a key the
    # M9 lacks (QZSS_L1S_ENA), Galileo on without E1, every major GNSS off.
    def sig(*kv):
        return ubx(0x06, 0x8A, bytes([0, 1, 0, 0]) + b"".join(struct.pack("<IB", k, v) for k, v in kv))
    sigs = sig((0x1031001F, 1), (0x10310024, 1), (0x10310021, 0), (0x10310022, 0), (0x10310025, 1))
    sigs += sig((0x10310020, 0)) + sig((0x10310014, 1)) + sig((0x10310007, 0), (0x10310021, 1))
    sigs += sig((0x1031001F, 0), (0x10310021, 0), (0x10310022, 0), (0x10310025, 0)) + ubx(0x0A, 0x28) + ubx(0x01, 0x43)
    sigs += ubx(0x06, 0x8B, struct.pack("<BBHI", 0, 0, 0, 0x1031FFFF))
    write("ubx_device", "cfg_signal_impossible.bin", sigs + b"\x02")

    # Raw data: CFG-MSG RXM-RAWX and RXM-SFRBX on (short and all-port forms),
    # their CFG-MSG polls, RAWX/SFRBX polls (no answer), CFG-MSGOUT keys on the
    # M9; the control byte 0x06 makes the chip an M9 on raw-data firmware.
    raw = ubx(0x06, 0x01, bytes([0x02, 0x15, 1])) + ubx(0x06, 0x01, bytes([0x02, 0x13, 0, 1, 0, 1, 0, 0]))
    raw += ubx(0x06, 0x01, bytes([0x02, 0x15])) + ubx(0x06, 0x01, bytes([0x02, 0x13])) + ubx(0x02, 0x15) + ubx(0x02, 0x13)
    raw += ubx(0x06, 0x8A, bytes([0, 1, 0, 0]) + struct.pack("<IBIB", 0x209102A5, 1, 0x20910232, 1))
    raw += ubx(0x06, 0x8B, struct.pack("<BBHII", 0, 0, 0, 0x209102A5, 0x20910232))
    write("ubx_device", "raw_rawx_sfrbx.bin", raw + b"\x06")
    # The same input, then epochs of 96 satellites of every system (make_fix
    # spreads them over the SatId order), 16 tracked: GPS, GLONASS (with its
    # channel byte), Galileo, BeiDou MEO/IGSO and GEO (C02, C04: D2), QZSS,
    # SBAS; at tows on which every system finishes an ephemeris unit the fuzz
    # store's sets fill (GPS subframes, GLONASS strings 1-5, Galileo I/NAV
    # words, BeiDou D1 subframes 1-3 and D2 pages), so RXM-RAWX and RXM-SFRBX
    # of each system are composed. Control bytes in the order
    # fuzz_ubx_device.cpp reads them (from the file's end backwards): identity
    # (M9, raw firmware), 1 Hz, one output at 115200 with UBX out and only RAWX
    # and SFRBX of the 14 rated messages on, NMEA version, the feed of the
    # whole payload, then the epochs (make_fix, make_raw).
    write("ubx_device", "raw_epochs.bin", raw + raw_epoch_controls(len(raw), RAW_EPOCH_TOWS))


# Tows (s of GPS week 2190) of raw_epochs.bin's epochs, each + 0.1 s x its
# index (make_fix), 2 s apart from 36 s after the store's toe: over them the
# replay composes 14 RXM-RAWX (210 second-band entries) and RXM-SFRBX of GPS
# 6, GLONASS 12, Galileo 30, BeiDou 14 (GEO D2 pages included), QZSS 4; the
# test fuzz_replay.ubx_device_raw_seed requires every system of them.
RAW_EPOCH_TOWS = [7236 + 2 * i for i in range(14)]
RAW_EPOCH_TRACKED = {0, 1, 2, 16, 17, 18, 30, 31, 32, 48, 49, 50, 55, 79, 80, 84}


def raw_epoch_controls(feed_len, tows):
    ctl = [6, 0, 0, 3, 3, 1] + [0] * 8 + [1, 1] + [0] * 4 + [0]
    ctl += [0, 0, 0, (feed_len - 1) >> 8, (feed_len - 1) & 0xFF]
    sizes = [("G", 32), ("R", 27), ("E", 36), ("C", 63), ("J", 10), ("S", 39)]  # core/common/sat_id.hpp
    system_of = [sys for sys, n in sizes for _ in range(n)]
    step = len(system_of) // 96
    for tow in tows:
        ctl += [15, 0, 100]  # epoch, host 0, 1 s
        # kind 3D, week then tow, leap 18, no leap second, lat, lon, height (2
        # each), geoid, speed, course (2 each), climb, h_acc (2), noise, 96 satellites.
        ctl += [3, 2190 >> 8, 2190 & 0xFF, tow >> 8, tow & 0xFF, 18, 1] + [0] * 6 + [0] + [0] * 4 + [0]
        ctl += [0, 10, 0, 96]
        for k in range(96):
            glonass = [k % 14] if system_of[k * step] == "R" else []  # channel k - 7
            ctl += glonass + ([150, 0, 90, 45] if k in RAW_EPOCH_TRACKED else [0, 0, 0])  # el 60 / -90 deg
        # Per tracked satellite: make_raw's fields, then its second band (control 1: two bands) with a
        # 0.5 m code offset; SBAS has none and reads no more.
        for k in sorted(RAW_EPOCH_TRACKED):
            ctl += [0, 0, 0, 0, 60, 0, 30, 3, 5, 15] + ([1, 50] if system_of[k * step] != "S" else [1])
    return bytes(reversed(ctl))


# --- RINEX observation files, gzip (as spp / calibrate read them) -----------

def obs_corpus():
    for name in ("nya1_v211_mixed.o", "nya1_v305_events.rnx"):
        data = (ROOT / "tests/data/obs" / name).read_bytes()
        write("rinex_obs", name + ".gz", gzip.compress(data, mtime=0))


# --- meshes ------------------------------------------------------------------

CUBE_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_F = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]


def ply(fmt, extra_element=False):
    head = ["ply", "format %s 1.0" % fmt, "comment cube", "element vertex 8", "property float x",
            "property float y", "property double z", "property uchar red"]
    if extra_element:
        head += ["element edge 1", "property int vertex1", "property int vertex2"]
    head += ["element face 6", "property list uchar int vertex_indices", "end_header"]
    out = ("\n".join(head) + "\n").encode()
    if fmt == "ascii":
        out += "".join("%g %g %g 255\n" % v for v in CUBE_V).encode()
        if extra_element:
            out += b"0 1\n"
        out += "".join("4 %d %d %d %d\n" % f for f in CUBE_F).encode()
        return out
    e = "<" if fmt == "binary_little_endian" else ">"
    out += b"".join(struct.pack(e + "ffdB", *v, 255) for v in CUBE_V)
    if extra_element:
        out += struct.pack(e + "ii", 0, 1)
    out += b"".join(struct.pack(e + "B4i", 4, *f) for f in CUBE_F)
    return out


def mesh_corpus():
    write("ply", "cube_ascii.ply", ply("ascii"))
    write("ply", "cube_le.ply", ply("binary_little_endian", extra_element=True))
    write("ply", "cube_be.ply", ply("binary_big_endian"))
    obj = "# cube\nmtllib x.mtl\no cube\n" + "".join("v %g %g %g\n" % v for v in CUBE_V)
    obj += "vt 0 0\nvn 0 0 1\nusemtl concrete\n"
    obj += "f 1/1/1 4/1/1 3/1/1 2/1/1\nf 5//1 6//1 7//1 8//1\nusemtl glass\n"
    obj += "f -8 -7 -3 -4\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
    write("obj", "cube_materials.obj", obj)
    write("footprints", "two_buildings_ground.toml",
          '[[building]]\nfootprint = [[0, 0], [20, 0], [20, 10], [0, 10]]\nheight_m = 15.0\nmaterial = "concrete"\n\n'
          '[[building]]\nfootprint = [[30, 0], [40, 5], [30, 10]]\nheight_m = 30.5\nbase_m = 2.0\nmaterial = "glass"\n\n'
          '[ground]\nhalf_size_m = 200.0\nheight_m = -0.5\nmaterial = "asphalt"\n')


# --- dictionaries ------------------------------------------------------------

def dictionaries():
    write_dict("truth_packet", ["version", "vehicle", "sim_time_s", "lla", "lat_deg", "lon_deg", "height_m", "ecef",
                                "x_m", "y_m", "z_m", "enu", "e_m", "n_m", "u_m", "vel_enu", "e_m_s", "n_m_s", "u_m_s",
                                "vel_ecef", "x_m_s", "y_m_s", "z_m_s", "gps_week", "gps_tow_s", "NaN", "Infinity",
                                "1e999", "-0", "true", "null", "\xf7GTR\x01", "\\u0000"])
    write_dict("ubx_device", ["\xb5\x62", "\xb5\x62\x06", "\xb5\x62\x0a\x04\x00\x00", "$PUBX,41,", "$PUBX,40,",
                              "GPQ,", "GNQ,", "*", "\r\n", "$GP", "$GN", "\xb5\x62\x06\x8a", "\xb5\x62\x06\x8b",
                              "\xb5\x62\x06\x8c", "\xff\xff\xff\x0f", "\x01\x00\x21\x30", "\x07\x00\x91\x20",
                              "\xb5\x62\x02\x15", "\xb5\x62\x02\x13", "\x02\x15", "\x02\x13", "\xa5\x02\x91\x20",
                              "\x32\x02\x91\x20"])
    # RINEX header labels (columns 61-80) from the test files.
    labels = set()
    for p in list((ROOT / "tests/data/nav").iterdir()) + list((ROOT / "tests/data/obs").glob("*.[or]*")):
        if p.suffix == ".gz":
            continue
        for line in p.read_text(errors="replace").splitlines():
            if len(line) > 60 and line[60:].strip():
                labels.add(line[60:].rstrip())
            if "END OF HEADER" in line:
                break
    for target in ("rinex_nav", "rinex_obs"):
        write_dict(target, sorted(labels) + ["G01", "G32", "R01", "E11", "> 2024", "D+00", "E-01", "0.9999e9",
                                             "C01", "C59", "J02", "S27", "I02", "X01", "N: GNSS NAV DATA",
                                             "G: GLONASS NAV DATA", "H: GEO NAV MSG DATA", "M: MIXED", "E: GALILEO",
                                             "BDSA", "BDSB", "GAL ", "GLUT", "CORR TO SYSTEM TIME",
                                             "5.130000000000E+02", "7.730000000000E+02", "-7.000000000000E+00"])
    write_dict("almanac", ["******** Week", "ID:", "Health:", "Eccentricity:", "Time of Applicability(s):",
                           "Orbital Inclination(rad):", "Rate of Right Ascen(r/s):", "SQRT(A)  (m 1/2):",
                           "Right Ascen at Week(rad):", "Argument of Perigee(rad):", "Mean Anom(rad):", "Af0(s):",
                           "Af1(s/s):", "week:", "E-001", "E+000"])
    keys = set(re.findall(r"^\| `([a-z_0-9.]+)`", (ROOT / "docs/configuration.md").read_text(), re.M))
    sections = set(re.findall(r"^\s*(\[\[?[a-z_.]+\]\]?)", (ROOT / "config/default.toml").read_text(), re.M))
    sections |= {"[scene]", "[scene.material_loss_db]", "[[output]]"}
    write_dict("config", sorted(keys) + sorted(sections) + ["true", "false", "inf", "nan", "1979-05-27T07:32:00Z",
                                                             "\"pty\"", "\"tcp\"", "\"udp\"", "\"file\"", "\"serial\""])
    write_dict("ply", ["ply", "format ascii 1.0", "format binary_little_endian 1.0", "format binary_big_endian 1.0",
                       "element vertex ", "element face ", "property float ", "property double ", "property uchar ",
                       "property list uchar int vertex_indices", "end_header", "comment", "obj_info", "1e-320",
                       "nan", "inf"])
    write_dict("obj", ["v ", "vt ", "vn ", "f ", "usemtl ", "mtllib ", "o ", "g ", "s off", "//", "/", "-1", "1e-320",
                       "nan", "inf", "1e400"])
    write_dict("footprints", ["[[building]]", "footprint", "height_m", "base_m", "material", "[ground]",
                              "half_size_m", "[[", "]]", "1e308", "nan", "inf"])


# --- multi-GNSS navigation files (one record of every system) ----------------

def nav_corpus():
    """Mixed RINEX 3 (3.04 and 3.05 with 5-line GLONASS), RINEX 2 GLONASS (.g)
    and SBAS (.h): one record of each system, taken from the cut IGS file."""
    src = gzip.open(ROOT / "tests/data/nav/BRDC00IGS_R_20240100000_01D_MN_cut.rnx.gz", "rt").read().splitlines()
    end = next(i for i, l in enumerate(src) if "END OF HEADER" in l)
    first = {}
    i = end + 1
    while i < len(src):
        j = i + 1
        while j < len(src) and src[j][:1] == " ":
            j += 1
        first.setdefault(src[i][0], src[i:j])
        i = j
    irnss = ["I02 2024 01 10 00 00 00 4.565306007862E-04 1.591615728103E-11 0.000000000000E+00"] + \
        ["     1.000000000000E+00-2.153125000000E+02 2.960837010622E-09 1.270870789390E+00"] * 6 + \
        ["     2.592000000000E+05"]
    head = ["     3.04           N: GNSS NAV DATA    M: MIXED            RINEX VERSION / TYPE",
            "BDSA   3.8184E-08 -6.7055E-08 -2.9802E-07  5.9605E-07 W 02  IONOSPHERIC CORR",
            "GAL    4.6250E+01  2.1094E-01  3.2349E-03  0.0000E+00       IONOSPHERIC CORR",
            "%-60sTIME SYSTEM CORR" % ("GLUT %17.10E%16.9E%7d%5d" % (-9.3132257462e-10, 0.0, 0, 0)),
            "    18                                                      LEAP SECONDS",
            "                                                            END OF HEADER"]
    body = [l for k in "GRECJS" for l in first[k]] + irnss
    mixed = "\n".join(head + body) + "\n"
    write("rinex_nav", "mixed_every_system.rnx", mixed)
    write("rinex_nav", "mixed_every_system.rnx.gz", gzip.compress(mixed.encode(), mtime=0))
    glo5 = first["R"] + ["     1.790000000000E+02-2.793967723846E-09 2.000000000000E+00 0.000000000000E+00"]
    v305 = [head[0].replace("3.04", "3.05")] + head[1:] + glo5 + first["G"]
    write("rinex_nav", "mixed_v305_glonass.rnx", "\n".join(v305) + "\n")
    v2g = (ROOT / "tests/data/nav/SYNT0100.24g").read_text()
    write("rinex_nav", "glonass_v2.g", v2g)
    # RINEX 2.11 Table A16: GEO navigation (H), PRN - 100, D19.12 values.
    s = first["S"]
    def d19(x):
        v = float(x)
        exp = 0 if v == 0.0 else int(math.floor(math.log10(abs(v)))) + 1
        return ("%15.12f" % (v / 10 ** exp)).rjust(15) + "D%+03d" % exp
    f = s[0][4:23].split()
    vals0 = [s[0][23 + 19 * k:42 + 19 * k] for k in range(3)]
    rec = ["%2d %02d %2d %2d %2d %2d%5.1f" % (int(s[0][1:3]), int(f[0]) % 100, int(f[1]), int(f[2]), int(f[3]),
                                             int(f[4]), float(f[5])) + "".join(d19(v) for v in vals0)]
    for line in s[1:]:
        rec.append("   " + "".join(d19(line[4 + 19 * k:23 + 19 * k]) for k in range(4)))
    h = ["     2.11           H: GEO NAV MSG DATA                     RINEX VERSION / TYPE",
         "                                                            END OF HEADER"]
    write("rinex_nav", "sbas_v2.h", "\n".join(h + rec) + "\n")


if __name__ == "__main__":
    truth_corpus()
    ubx_corpus()
    obs_corpus()
    mesh_corpus()
    nav_corpus()
    dictionaries()
