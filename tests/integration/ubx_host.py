# SPDX-License-Identifier: Apache-2.0
"""The host side of a u-blox line for the integration tests: UBX framing, a
timed message stream, and PX4's and ArduPilot's UBX start-up sequences as
their drivers send them (docs/ports.md §Tests).

Time-outs, from the hosts' sources:
- PX4 (PX4-GPSDrivers src/ubx.h, UBX_CONFIG_TIMEOUT): 250 ms for every ACK
  and for the MON-VER reply; a miss restarts the whole configuration
  (ubx.cpp configure / configureDevicePreV27). CFG-VALSET waits 2000 ms on a
  UART (an M8 NAKs it; no answer means the same: legacy protocol).
- ArduPilot (libraries/AP_GPS/AP_GPS_UBLOX.cpp read()): no reply time-out;
  it sends its next configuration request every 300 ms until the first
  NAV-PVT (750 ms after) and repeats a poll whose answer did not read back
  right. A reply later than 300 ms costs a repeated request, not the
  start-up; no message at all for 4 s (AP_GPS.cpp GPS_TIMEOUT_MS) drops
  the driver.
"""
import os
import select
import struct
import subprocess
import time

PX4_REPLY_LIMIT_S = 0.25        # UBX_CONFIG_TIMEOUT
PX4_VALSET_LIMIT_S = 2.0        # waitForAck(UBX_MSG_CFG_VALSET, 2000, ...) on a UART
ARDUPILOT_REQUEST_S = 0.3       # _delay_time before the first NAV-PVT


def frame(cls, mid, payload=b""):
    body = bytes([cls, mid]) + struct.pack("<H", len(payload)) + payload
    a = b = 0
    for x in body:
        a = (a + x) & 0xFF
        b = (b + a) & 0xFF
    return b"\xb5\x62" + body + bytes([a, b])


def ack(cls, mid, ok=True):
    return frame(0x05, 0x01 if ok else 0x00, bytes([cls, mid]))


def nmea(body):
    cs = 0
    for ch in body.encode():
        cs ^= ch
    return f"${body}*{cs:02X}\r\n".encode()


def crc24q(data):
    """RTCM 3's CRC-24Q (RTCM 10403.3 §4.2)."""
    crc = 0
    for x in data:
        crc ^= x << 16
        for _ in range(8):
            crc <<= 1
            if crc & 0x1000000:
                crc ^= 0x1864CFB
    return crc & 0xFFFFFF


def rtcm_number(m):
    """Message number of an RTCM 3 frame (DF002)."""
    return (m[3] << 4) | (m[4] >> 4)


def split_stream(data):
    """(kind, bytes) for every complete UBX frame / NMEA line / RTCM 3 frame
    (CRC checked); rest returned."""
    out = []
    i = 0
    while i < len(data):
        if data[i] == 0xD3 and (i + 1 >= len(data) or data[i + 1] & 0xFC == 0):
            if i + 3 > len(data):
                break
            n = 6 + ((data[i + 1] & 3) << 8 | data[i + 2])
            if i + n > len(data):
                break
            if crc24q(data[i:i + n - 3]) == int.from_bytes(data[i + n - 3:i + n], "big"):
                out.append(("rtcm", data[i:i + n]))
                i += n
            else:
                i += 1
        elif data[i:i + 2] == b"\xb5\x62":
            if i + 6 > len(data):
                break
            n = 8 + struct.unpack_from("<H", data, i + 4)[0]
            if i + n > len(data):
                break
            out.append(("ubx", data[i:i + n]))
            i += n
        elif data[i:i + 1] == b"$":
            j = data.find(b"\n", i)
            if j < 0:
                break
            out.append(("nmea", data[i:j + 1]))
            i = j + 1
        else:
            i += 1
    return out, data[i:]


def is_ubx(cls, mid):
    return lambda k, m: k == "ubx" and m[2] == cls and m[3] == mid


def is_ack_for(cls, mid):
    return lambda k, m: k == "ubx" and m[2] == 0x05 and m[6:8] == bytes([cls, mid])


def pvt_fix_ok(k, m):
    return k == "ubx" and m[2:4] == b"\x01\x07" and m[6 + 21] & 1


def pvt_lost_after(stream, t0, t1):
    """NAV-PVTs without gnssFixOK that arrived in (t0, t1], monotonic times:
    a chip that restarts its GNSS engine drops its fix for a moment."""
    return sum(1 for t, k, m in stream.seen
               if t0 < t <= t1 and k == "ubx" and m[2:4] == b"\x01\x07" and not m[6 + 21] & 1)


class Stream:
    """Reads a fd, splits messages, keeps arrival times. msgs is consumed by
    wait_for; seen keeps every message for analysis afterwards."""

    def __init__(self, fd):
        self.fd = fd
        self.buf = b""
        self.msgs = []  # (t, kind, bytes)
        self.seen = []

    def pump(self, timeout):
        r, _, _ = select.select([self.fd], [], [], max(0.0, timeout))
        if not r:
            return
        try:
            chunk = os.read(self.fd, 65536)
        except BlockingIOError:
            return
        t = time.monotonic()
        msgs, self.buf = split_stream(self.buf + chunk)
        self.msgs += [(t, k, m) for k, m in msgs]
        self.seen += [(t, k, m) for k, m in msgs]

    def collect(self, seconds):
        """Everything that arrives in the next seconds (msgs cleared first)."""
        self.msgs.clear()
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.pump(end - time.monotonic())
        return list(self.msgs)

    def wait_for(self, pred, limit_s, what):
        deadline = time.monotonic() + limit_s
        while True:
            for idx, (t, k, m) in enumerate(self.msgs):
                if pred(k, m):
                    del self.msgs[:idx + 1]
                    return t, m
            self.msgs.clear()
            if time.monotonic() > deadline:
                raise AssertionError(f"no {what} within {limit_s} s")
            self.pump(deadline - time.monotonic())

    def frame_of(self, cls, mid, limit_s=2.0):
        return self.wait_for(is_ubx(cls, mid), limit_s, f"UBX {cls:02X}-{mid:02X}")[1]


def send(fd, data):
    os.write(fd, data)


def stty_speed(path):
    out = subprocess.run(["stty", "-F", path, "speed"], capture_output=True, text=True).stdout.strip()
    return int(out) if out.isdigit() else -1


class Replies:
    """How long each reply took: (what, seconds) in order."""

    def __init__(self):
        self.times = []

    def timed(self, s, fd, data, pred, limit_s, what):
        t0 = time.monotonic()
        send(fd, data)
        t, m = s.wait_for(pred, limit_s, what)
        self.times.append((what, t - t0))
        return m

    def worst(self):
        return max(self.times, key=lambda x: x[1])

    def summary(self):
        what, dt = self.worst()
        return f"{len(self.times)} replies, slowest {dt * 1000:.1f} ms ({what})"


# --- PX4 ---------------------------------------------------------------------

def mon_ver_frame(sw, hw, *extensions):
    """MON-VER as a u-blox sends it: swVersion CH[30], hwVersion CH[10], CH[30] extensions, NUL-padded."""
    pad = lambda txt, n: txt.encode().ljust(n, b"\0")
    return frame(0x0A, 0x04, pad(sw, 30) + pad(hw, 10) + b"".join(pad(e, 30) for e in extensions))


def mon_ver_m8():
    return mon_ver_frame("ROM CORE 3.01 (107888)", "00080000", "FWVER=SPG 3.01", "PROTVER=18.00", "GPS;GLO;GAL;BDS",
                         "SBAS;IMES;QZSS")


def px4_startup(s, fd, after_mon_ver=None):
    """PX4's legacy (protocol < 27) UART start-up, byte for byte: CFG-VALSET
    -> NAK, CFG-PRT at the current baud (UBX only) -> ACK, MON-VER -> the
    M8's reply, then CFG-RATE 200 ms, CFG-NAV5 airborne <2g, CFG-MSG
    NAV-PVT/STATUS/DOP/SVINFO (5)/MON-HW (5) -> ACK each; every reply within
    PX4's time-out. after_mon_ver(): called once PX4 knows the board (a fault
    injected while it configures). Returns the Replies."""
    r = Replies()
    m = r.timed(s, fd, frame(0x06, 0x8A, bytes([0, 1, 0, 0]) + struct.pack("<II", 0x40520001, 115200)),
                is_ack_for(0x06, 0x8A), PX4_VALSET_LIMIT_S, "reply to CFG-VALSET")
    assert m == ack(0x06, 0x8A, False), f"VALSET: want NAK, got {m.hex()}"
    prt = struct.pack("<BBHIIHHHH", 1, 0, 0, 0x08D0, 9600, 0x0001, 0x0001, 0, 0)
    m = r.timed(s, fd, frame(0x06, 0x00, prt), is_ack_for(0x06, 0x00), 1.0, "reply to CFG-PRT")
    assert m == ack(0x06, 0x00), f"CFG-PRT: got {m.hex()}"
    m = r.timed(s, fd, frame(0x0A, 0x04), is_ubx(0x0A, 0x04), 1.0, "MON-VER")
    assert m == mon_ver_m8(), f"MON-VER: {m!r}"
    if after_mon_ver:
        after_mon_ver()
    steps = [(0x06, 0x08, struct.pack("<HHH", 200, 1, 0))]
    nav5 = bytearray(36)
    struct.pack_into("<HBB", nav5, 0, 0x0005, 7, 3)
    steps.append((0x06, 0x24, bytes(nav5)))
    for cls, mid, rate in ((0x01, 0x07, 1), (0x01, 0x03, 1), (0x01, 0x04, 1), (0x01, 0x30, 5), (0x0A, 0x09, 5)):
        steps.append((0x06, 0x01, bytes([cls, mid, rate])))
    for cls, mid, payload in steps:
        what = f"reply to {cls:02X}-{mid:02X} {payload.hex()}"
        m = r.timed(s, fd, frame(cls, mid, payload), is_ack_for(cls, mid), 1.0, what)
        assert m == ack(cls, mid), f"{cls:02X}-{mid:02X} {payload.hex()}: got {m.hex()}"
    late = [(w, dt) for w, dt in r.times[1:] if dt >= PX4_REPLY_LIMIT_S]
    assert not late, f"replies after PX4's 250 ms (it restarts its configuration): {late}"
    return r


def mon_ver_m9():
    return mon_ver_frame("EXT CORE 4.04 (7f89f7)", "00190000", "ROM BASE 0x118B2060", "FWVER=SPG 4.04",
                         "PROTVER=32.01", "MOD=NEO-M9N", "GPS;GLO;GAL;BDS", "SBAS;QZSS")


def mon_ver_f9p():
    """The emulated ZED-F9P's MON-VER (docs/ubx.md "ZED-F9P")."""
    return mon_ver_frame("EXT CORE 1.00 (f4c834)", "00190000", "ROM BASE 0x118B2060", "FWVER=HPG 1.32",
                         "PROTVER=27.31", "MOD=ZED-F9P", "GPS;GLO;GAL;BDS", "SBAS;QZSS")


def key_value_bytes(key):
    """Bytes of a configuration key's value, from the key id's bits 28-30
    (1 and 2 one byte, 3 two, 4 four, 5 eight)."""
    return {1: 1, 2: 1, 3: 2, 4: 4, 5: 8}[key >> 28 & 7]


def valset(pairs, layers=1, version=0):
    """CFG-VALSET payload (version 0, or 1 with transaction 0 = none);
    pairs: (key id, value), each value key_value_bytes(key) long."""
    out = bytes([version, layers, 0, 0])
    for key, value in pairs:
        out += struct.pack("<I", key) + value.to_bytes(key_value_bytes(key), "little")
    return out


def valget(keys, layer=0, position=0):
    return struct.pack("<BBH", 0, layer, position) + b"".join(struct.pack("<I", k) for k in keys)


# PX4-GPSDrivers src/ubx.h key ids (facts; values as PX4 sends them).
K_UART1_BAUDRATE, K_UART1_STOPBITS, K_UART1_DATABITS, K_UART1_PARITY = 0x40520001, 0x20520002, 0x20520003, 0x20520004
K_UART1IN_UBX, K_UART1IN_NMEA, K_UART1IN_RTCM3X = 0x10730001, 0x10730002, 0x10730004
K_UART1OUT_UBX, K_UART1OUT_NMEA = 0x10740001, 0x10740002
K_USBIN_UBX, K_USBIN_NMEA, K_USBIN_RTCM3X, K_USBOUT_UBX, K_USBOUT_NMEA = \
    0x10770001, 0x10770002, 0x10770004, 0x10780001, 0x10780002
K_I2CIN_UBX, K_I2CIN_NMEA, K_I2CIN_RTCM3X, K_I2COUT_UBX, K_I2COUT_NMEA = \
    0x10710001, 0x10710002, 0x10710004, 0x10720001, 0x10720002
K_NAVSPG_FIXMODE, K_NAVSPG_UTCSTANDARD, K_NAVSPG_DYNMODEL = 0x20110011, 0x2011001C, 0x20110021
K_ODO = (0x10220001, 0x10220002, 0x10220003, 0x10220004)  # USE_ODO, USE_COG, OUTLPVEL, OUTLPCOG
K_ITFM_ENABLE, K_RATE_MEAS, K_RATE_NAV, K_RATE_TIMEREF = 0x1041000D, 0x30210001, 0x30210002, 0x20210003
K_NAVHPG_DGNSSMODE = 0x20140011
# CFG-SIGNAL-*_ENA (multi-gnss.md §8; PX4 configureDevice sends these five, then SBAS).
K_SIGNAL_GPS_ENA, K_SIGNAL_SBAS_ENA, K_SIGNAL_GAL_ENA, K_SIGNAL_BDS_ENA, K_SIGNAL_QZSS_ENA, K_SIGNAL_GLO_ENA = (
    0x1031001F, 0x10310020, 0x10310021, 0x10310022, 0x10310024, 0x10310025)
# CFG-MSGOUT I2C ids; PX4's cfgValsetPort sets UART1 (+1) and USB (+3).
K_MSGOUT_NAV_PVT, K_MSGOUT_NAV_DOP, K_MSGOUT_NAV_SAT, K_MSGOUT_NAV_STATUS, K_MSGOUT_MON_RF, K_MSGOUT_RXM_RTCM = \
    0x20910006, 0x20910038, 0x20910015, 0x2091001A, 0x20910359, 0x20910268
PX4_M9_RATE_MEAS_MS = 125  # configureDevice: 8 Hz on everything but an F9P
PX4_F9P_RATE_MEAS_MS = 100  # configureDevice: 10 Hz on an F9P in normal mode, 8 Hz (125) for heading
# UART2 and heading keys of PX4's RoverWithMovingBase mode (configureDevice).
K_UART1OUT_RTCM3X = 0x10740004
K_UART2_BAUDRATE, K_UART2_STOPBITS, K_UART2_DATABITS, K_UART2_PARITY = 0x40530001, 0x20530002, 0x20530003, 0x20530004
K_UART2IN_UBX, K_UART2IN_NMEA, K_UART2IN_RTCM3X = 0x10750001, 0x10750002, 0x10750004
K_UART2OUT_UBX, K_UART2OUT_RTCM3X = 0x10760001, 0x10760004
K_MSGOUT_NAV_RELPOSNED, K_MSGOUT_NAV_HPPOSLLH = 0x2091008D, 0x20910033


def px4_m9_probe_payload():
    """PX4's CFG-VALSET probe on a UART (configure(), protocol 27+ test)."""
    return valset([(K_UART1_STOPBITS, 1), (K_UART1_DATABITS, 0), (K_UART1_PARITY, 0), (K_UART1IN_UBX, 1),
                   (K_UART1IN_NMEA, 0), (K_UART1OUT_UBX, 1), (K_UART1OUT_NMEA, 0)])


def px4_m9_valset_payloads(dyn_model=7, sat_rate=10, f9p=False, heading=False, uart2_baud=230400):
    """PX4's configureDevice() VALSET blocks for a NEO-M9N (Board::u_blox9)
    or, with f9p, a ZED-F9P (10 Hz, or 8 Hz as a moving-baseline rover with
    heading, then its UART2/RELPOSNED block) on a UART, output mode GPS, no
    GNSS selection, I2C protocols off, in order, with whether PX4 requires
    their ACK (the DGNSSMODE block: never; an M9N NAKs it)."""
    port = lambda key, v: [(key + 1, v), (key + 3, v)]  # cfgValsetPort: UART1 and USB
    rate = PX4_M9_RATE_MEAS_MS if heading or not f9p else PX4_F9P_RATE_MEAS_MS
    blocks = [
        (valset([(K_UART1IN_RTCM3X, 1), (K_USBIN_UBX, 1), (K_USBIN_RTCM3X, 1), (K_USBIN_NMEA, 0),
                 (K_USBOUT_UBX, 1), (K_USBOUT_NMEA, 0)]), True),
        (valset([(K_NAVSPG_FIXMODE, 3), (K_NAVSPG_UTCSTANDARD, 3), (K_NAVSPG_DYNMODEL, dyn_model)] +
                [(k, 0) for k in K_ODO] +
                [(K_ITFM_ENABLE, 1), (K_RATE_MEAS, rate), (K_RATE_NAV, 1), (K_RATE_TIMEREF, 0)]), True),
        (valset([(K_NAVHPG_DGNSSMODE, 3)]), False),  # RTK: F9P only, NAK tolerated
        (valset(port(K_MSGOUT_NAV_PVT, 1) + port(K_MSGOUT_NAV_DOP, 1) + port(K_MSGOUT_NAV_SAT, sat_rate) +
                port(K_MSGOUT_NAV_STATUS, 1) + port(K_MSGOUT_MON_RF, 1) + port(K_MSGOUT_RXM_RTCM, 1)), True),
        (valset([(K_I2CIN_UBX, 0), (K_I2CIN_NMEA, 0), (K_I2CIN_RTCM3X, 0), (K_I2COUT_UBX, 0), (K_I2COUT_NMEA, 0)] +
                ([(0x10720004, 0)] if f9p else [])), True),  # I2COUTPROT_RTCM3X: F9P only
    ]
    if heading:
        blocks.append((valset([(K_UART1OUT_UBX, 1), (K_UART1OUT_RTCM3X, 0)] + port(K_MSGOUT_NAV_RELPOSNED, 1) +
                              port(K_MSGOUT_NAV_HPPOSLLH, 1) +
                              [(K_UART2_STOPBITS, 1), (K_UART2_DATABITS, 0), (K_UART2_PARITY, 0), (K_UART2IN_UBX, 0),
                               (K_UART2IN_RTCM3X, 1), (K_UART2IN_NMEA, 0), (K_UART2OUT_UBX, 0), (K_UART2OUT_RTCM3X, 0),
                               (K_UART2_BAUDRATE, uart2_baud)]), True))
    return blocks


def px4_startup_m9(s, fd, path, baud=115200, f9p=False, heading=False):
    """PX4's protocol-27+ UART start-up against an M9, byte for byte
    (PX4-GPSDrivers ubx.cpp configure / configureDevice): the VALSET probe
    (UART1 8N1, UBX only) -> ACK; VALSET UART1 baud -> ACK at the old rate,
    then the line switches (PX4 switches its side too); MON-VER -> the
    M9N's; then configureDevice's VALSET blocks, each ACKed within PX4's
    250 ms except the F9P-only DGNSSMODE, which an M9N NAKs. Returns the
    Replies."""
    r = Replies()
    m = r.timed(s, fd, frame(0x06, 0x8A, px4_m9_probe_payload()), is_ack_for(0x06, 0x8A), PX4_VALSET_LIMIT_S,
                "reply to the CFG-VALSET probe")
    assert m == ack(0x06, 0x8A), f"VALSET probe: want ACK (protocol 27+), got {m.hex()}"
    m = r.timed(s, fd, frame(0x06, 0x8A, valset([(K_UART1_BAUDRATE, baud)])), is_ack_for(0x06, 0x8A), 1.0,
                "reply to VALSET CFG-UART1-BAUDRATE")
    assert m == ack(0x06, 0x8A), f"VALSET baud: got {m.hex()}"
    deadline = time.monotonic() + 1.0
    while stty_speed(path) != baud and time.monotonic() < deadline:
        s.pump(0.02)
    assert stty_speed(path) == baud, f"line at {stty_speed(path)}, want {baud} after the ACK"
    m = r.timed(s, fd, frame(0x0A, 0x04), is_ubx(0x0A, 0x04), 1.0, "MON-VER")
    assert m == (mon_ver_f9p() if f9p else mon_ver_m9()), f"MON-VER: {m!r}"
    for payload, required in px4_m9_valset_payloads(f9p=f9p, heading=heading):
        required = required or f9p  # an F9P ACKs every block, DGNSSMODE included
        what = f"reply to VALSET {payload[4:8][::-1].hex()}.."
        m = r.timed(s, fd, frame(0x06, 0x8A, payload), is_ack_for(0x06, 0x8A), 1.0, what)
        assert m == ack(0x06, 0x8A, required), f"{what}: got {m.hex()} (want {'ACK' if required else 'NAK'})"
    late = [(w, dt) for w, dt in r.times[1:] if dt >= PX4_REPLY_LIMIT_S]
    assert not late, f"replies after PX4's 250 ms (it restarts its configuration): {late}"
    return r


def valget_values(s, fd, keys, layer=0):
    """VALGET keys; {key: value} of the reply (then ACK-ACK)."""
    send(fd, frame(0x06, 0x8B, valget(keys, layer)))
    data = s.frame_of(0x06, 0x8B, 1.0)
    a = s.wait_for(is_ack_for(0x06, 0x8B), 1.0, "ACK after VALGET")[1]
    assert a == ack(0x06, 0x8B), a.hex()
    p, out, off = data[6:-2], {}, 4
    while off < len(p):
        key = struct.unpack_from("<I", p, off)[0]
        n = key_value_bytes(key)
        out[key] = int.from_bytes(p[off + 4:off + 4 + n], "little")
        off += 4 + n
    return out


def px4_rates(s, seconds=3.0, fix_limit_s=4.0):
    """After PX4's start-up: the first gnssFixOK within fix_limit_s, then
    NAV-PVT at 5 Hz (iTOW on 200 ms steps and boundaries) with gnssFixOK and
    3D, no NMEA, NAV-STATUS and NAV-DOP every epoch, NAV-SVINFO and MON-HW
    every 5th. Returns the messages of those seconds."""
    s.wait_for(pvt_fix_ok, fix_limit_s, "the first gnssFixOK")
    msgs = s.collect(seconds)
    pvts = [m for _, k, m in msgs if k == "ubx" and m[2:4] == b"\x01\x07"]
    nmeas = [m for _, k, m in msgs if k == "nmea"]
    assert not nmeas, f"NMEA still sent after CFG-PRT out=UBX: {nmeas[:2]}"
    want = 5 * seconds
    assert len(pvts) >= want - 3, f"{len(pvts)} NAV-PVT in {seconds} s, want ~{want:.0f} at 5 Hz"
    itows = [struct.unpack_from("<I", m, 6)[0] for m in pvts]
    steps_ms = {b - a for a, b in zip(itows, itows[1:])}
    assert steps_ms == {200}, f"iTOW steps {sorted(steps_ms)} ms, want 200"
    assert all(itow % 200 == 0 for itow in itows), "epochs not on 200 ms boundaries"
    flags = [m[6 + 21] for m in pvts]
    fix_types = [m[6 + 20] for m in pvts]
    assert all(f & 1 for f in flags) and all(ft == 3 for ft in fix_types), f"flags {flags} fixType {fix_types}"
    count = lambda c, i: sum(1 for _, k, m in msgs if k == "ubx" and m[2] == c and m[3] == i)
    for name, c, i in (("NAV-STATUS", 1, 3), ("NAV-DOP", 1, 4)):
        assert abs(count(c, i) - len(pvts)) <= 1, f"{count(c, i)} {name} for {len(pvts)} NAV-PVT (rate 1)"
    for name, c, i in (("NAV-SVINFO", 1, 0x30), ("MON-HW", 0x0A, 9)):
        assert abs(count(c, i) - len(pvts) / 5) <= 1, f"{count(c, i)} {name} for {len(pvts)} NAV-PVT (rate 5)"
    return msgs


# --- ArduPilot ---------------------------------------------------------------

def poll_cfg(s, fd, mid, payload=b"", replies=None, limit_s=1.0):
    """CFG poll: the data frame, then ACK-ACK (data first)."""
    t0 = time.monotonic()
    send(fd, frame(0x06, mid, payload))
    t, data = s.wait_for(is_ubx(0x06, mid), limit_s, f"CFG {mid:02X} poll answer")
    a = s.wait_for(is_ack_for(0x06, mid), limit_s, f"ACK after CFG {mid:02X} poll")[1]
    assert a == ack(0x06, mid), a.hex()
    if replies is not None:
        replies.times.append((f"CFG {mid:02X} poll {payload.hex()}", t - t0))
    return data[6:-2]


def set_cfg(s, fd, mid, payload, replies=None, limit_s=1.0):
    t0 = time.monotonic()
    send(fd, frame(0x06, mid, payload))
    t, a = s.wait_for(is_ack_for(0x06, mid), limit_s, f"ACK of CFG {mid:02X} set")
    assert a == ack(0x06, mid), f"CFG {mid:02X} set: {a.hex()}"
    if replies is not None:
        replies.times.append((f"CFG {mid:02X} set", t - t0))


def ardupilot_probe(fd, path, probe, baud=230400):
    """Send ArduPilot's probe; its $PUBX,41 moves the line to baud (the pty's termios follows)."""
    send(fd, probe)
    deadline = time.monotonic() + 3
    while stty_speed(path) != baud:
        assert time.monotonic() < deadline, f"pty termios {stty_speed(path)} after $PUBX,41"
        time.sleep(0.05)


ARDUPILOT_RATES = {(0x01, 0x07): 1, (0x01, 0x03): 1, (0x01, 0x06): 1, (0x01, 0x12): 1, (0x01, 0x04): 2, (0x0A, 0x09): 2}


def px4_cfg_gnss(mask):
    """The M8 CFG-GNSS PX4 sends for its GPS_1_GNSS mask (PX4-GPSDrivers src/ubx.cpp,
    configureDevicePreV27): bit 0 GPS+QZSS, 1 SBAS, 2 Galileo, 3 BeiDou, 4 GLONASS.
    msgVer 0, numTrkChHw 0, numTrkChUse 0xFF, 7 blocks in its order (gnssId, resTrkCh,
    maxTrkCh, flags); a disabled system's block is all zero."""
    gps, sbas, gal, bds, glo = (bool(mask >> i & 1) for i in range(5))
    on = 0x00010001
    blocks = [(0, 8, 16, gps), (5, 0, 3, gps), (1, 1, 3, sbas), (2, 4, 8, gal), (3, 8, 16, bds), (6, 8, 14, glo),
              (4, 0, 0, False)]
    out = bytes([0, 0, 0xFF, len(blocks)])
    for gid, res, mx, en in blocks:
        out += struct.pack("<BBBBI", gid, res if en else 0, mx if en else 0, 0, on if en else 0)
    return out


def ardupilot_cfg_gnss(polled, mode):
    """ArduPilot's CFG-GNSS for GPS_GNSS_MODE mode (AP_GPS_UBLOX.cpp,
    MSG_CFG_GNSS), from the polled payload: a wanted system (bit = gnssId)
    gets resTrkCh (numTrkChHw - 3) / (2 * systems other than SBAS), maxTrkCh
    numTrkChHw (Galileo on an M8: 8; SBAS 1/3) and the enable bit; the others
    0/0 without it (docs/ubx.md "What the hosts send")."""
    out = bytearray(polled)
    count = sum(1 for i in range(7) if (mode >> i) & 1 and i != 1)
    hw = out[1]
    for b in range(out[3]):
        o = 4 + 8 * b
        g = out[o]
        if (mode >> g) & 1:
            out[o + 1] = 1 if g == 1 else (hw - 3) // (count * 2)
            out[o + 2] = 3 if g == 1 else 8 if g == 2 else hw
            out[o + 4] |= 0x01
        else:
            out[o + 1] = out[o + 2] = 0
            out[o + 4] &= 0xFE
    return bytes(out)


def ardupilot_startup(s, fd, path, after_msg_rates=None, fix_limit_s=4.0):
    """ArduPilot's probe and configuration: $PUBX,41 (UBX+NMEA+RTCM3 in, UBX
    out, 230400; the pty's termios follows), then poll / set / poll-compare
    of CFG-MSG (NAV-PVT/STATUS/SOL/VELNED 1, NAV-DOP/MON-HW 2), CFG-RATE
    200 ms, CFG-PRT, CFG-NAV5 airborne <4g, CFG-GNSS, CFG-SBAS off, MON-VER
    (hwVersion 00080000) and its NAV-SVINFO poll (chipGen 4 = M8).
    after_msg_rates(): called once the message rates are set (a fault
    injected while it configures). The NAV-SVINFO poll waits for the first
    gnssFixOK (fix_limit_s). Returns (Replies, NAV-SVINFO frame)."""
    r = Replies()
    ardupilot_probe(fd, path, nmea("PUBX,41,1,0023,0001,230400,0"))
    for (cls, mid), rate in ARDUPILOT_RATES.items():
        before = poll_cfg(s, fd, 0x01, bytes([cls, mid]), r)
        assert len(before) == 8 and before[:2] == bytes([cls, mid]) and before[3] == 0, before.hex()
        set_cfg(s, fd, 0x01, bytes([cls, mid, rate]), r)
        after = poll_cfg(s, fd, 0x01, bytes([cls, mid]), r)
        assert after[3] == rate, f"CFG-MSG {cls:02X}-{mid:02X} read back UART1 rate {after[3]}, set {rate}"
    if after_msg_rates:
        after_msg_rates()
    rate = poll_cfg(s, fd, 0x08, b"", r)
    assert len(rate) == 6 and struct.unpack("<HHH", rate) == (1000, 1, 1), rate.hex()
    new_rate = struct.pack("<HHH", 200, 1, 0)
    set_cfg(s, fd, 0x08, new_rate, r)
    assert poll_cfg(s, fd, 0x08, b"", r) == new_rate
    prt = poll_cfg(s, fd, 0x00, bytes([1]), r)
    assert len(prt) == 20 and prt[0] == 1, prt.hex()
    assert struct.unpack_from("<IHH", prt, 8) == (230400, 0x0023, 0x0001), prt.hex()
    nav5 = poll_cfg(s, fd, 0x24, b"", r)
    assert len(nav5) == 36, len(nav5)
    new_nav5 = bytearray(nav5)
    struct.pack_into("<HBB", new_nav5, 0, 0x0005, 8, 2)
    set_cfg(s, fd, 0x24, bytes(new_nav5), r)
    back = poll_cfg(s, fd, 0x24, b"", r)
    assert back[2:4] == bytes([8, 2]), f"NAV5 read back dyn {back[2]} fix {back[3]}"
    gnss = poll_cfg(s, fd, 0x3E, b"", r)
    assert len(gnss) == 4 + 8 * gnss[3] and gnss[3] >= 1, gnss.hex()
    sbas = poll_cfg(s, fd, 0x16, b"", r)
    assert len(sbas) == 8, sbas.hex()
    new_sbas = bytes([0, 3, 3, 0]) + struct.pack("<I", 0)  # SBAS disabled
    set_cfg(s, fd, 0x16, new_sbas, r)
    assert poll_cfg(s, fd, 0x16, b"", r) == new_sbas
    mv = r.timed(s, fd, frame(0x0A, 0x04), is_ubx(0x0A, 0x04), 2.0, "MON-VER")
    assert mv[6 + 30:6 + 38] == b"00080000", mv[36:46]
    # Satellites are listed once the receiver has had an epoch.
    s.wait_for(pvt_fix_ok, fix_limit_s, "the first gnssFixOK")
    sv = r.timed(s, fd, frame(0x01, 0x30), is_ubx(0x01, 0x30), 2.0, "NAV-SVINFO poll")
    num_ch = sv[6 + 4]
    assert len(sv) == 8 + 8 + 12 * num_ch and num_ch >= 4, f"NAV-SVINFO {len(sv)} bytes, numCh {num_ch}"
    assert sv[6 + 5] & 7 == 4, f"chipGen {sv[6 + 5] & 7}, want 4 (M8)"
    return r, sv


def ardupilot_rates(s, seconds=2.0, rates=None):
    """After ArduPilot's configuration: NAV-PVT at 5 Hz with gnssFixOK and
    3D, the other messages at the rates it set (rates, default
    ARDUPILOT_RATES: NAV-DOP and MON-HW every 2nd epoch; rate 0: none), no
    NMEA. Returns the messages of those seconds."""
    msgs = s.collect(seconds)
    count = lambda c, i: sum(1 for _, k, m in msgs if k == "ubx" and m[2] == c and m[3] == i)
    pvts = [m for _, k, m in msgs if k == "ubx" and m[2:4] == b"\x01\x07"]
    assert pvts and all(m[6 + 21] & 1 and m[6 + 20] == 3 for m in pvts), "NAV-PVT without gnssFixOK / 3D fix"
    pvt = count(0x01, 0x07)
    want = 5 * seconds
    assert want - 2 <= pvt <= want + 1, f"{pvt} NAV-PVT in {seconds} s at 5 Hz"
    assert not any(k == "nmea" for _, k, _ in msgs), "NMEA sent after $PUBX,41 out=UBX"
    for (c, i), rate in (rates or ARDUPILOT_RATES).items():
        want = pvt / rate if rate else 0
        assert abs(count(c, i) - want) <= 1.5, f"{count(c, i)} of {c:02X}-{i:02X} for {pvt} NAV-PVT (rate {rate})"
    return msgs


# ArduPilot 4.5's legacy configuration loop (AP_GPS_UBLOX _request_next_config,
# the path it takes for every u-blox but F9/M10): CFG-MSG rates read back on
# the port CFG-PRT names, once NAV-PVT is seen.
ARDUPILOT_M9_RATES = {(0x01, 0x07): 1, (0x01, 0x06): 0, (0x01, 0x03): 0, (0x01, 0x02): 0, (0x01, 0x12): 0,
                      (0x01, 0x20): 5, (0x01, 0x04): 1, (0x0A, 0x09): 5, (0x0A, 0x0B): 5}
# AP_GPS's u-blox probe: CFG-MSG NAV-SOL rate 1, then $PUBX,41 to 230400.
ARDUPILOT_PROBE = bytes.fromhex("B5 62 06 01 03 00 01 06 01 12 4F") + b"$PUBX,41,1,0023,0001,230400,0*1E\r\n"


def ardupilot_rate_step(s, fd, cls, mid, rate, replies):
    """One rate step: CFG-MSG poll; a set on the current port if the port's
    rate differs; the next pass polls it again and must read the rate."""
    before = poll_cfg(s, fd, 0x01, bytes([cls, mid]), replies)
    assert len(before) == 8 and before[:2] == bytes([cls, mid]), before.hex()
    if before[2 + 1] != rate:
        set_cfg(s, fd, 0x01, bytes([cls, mid, rate]), replies)
        after = poll_cfg(s, fd, 0x01, bytes([cls, mid]), replies)
        assert after[2 + 1] == rate, f"CFG-MSG {cls:02X}-{mid:02X} read back UART1 rate {after[3]}, set {rate}"


def ardupilot_startup_m9(s, fd, path, fix_limit_s=4.0, probe=ARDUPILOT_PROBE, baud=230400, save=True):
    """ArduPilot 4.5 against a NEO-M9N: the probe, CFG-PRT poll (port id),
    NAV-PVT rate and CFG-RATE 200 ms, then (NAV-PVT seen) SOL/STATUS/POSLLH/
    VELNED off, TIMEGPS 5, the NAV-SVINFO poll it sends while the generation
    is unknown (an M9 has no NAV-SVINFO: no answer, no NAK), CFG-NAV5 airborne
    <4g, CFG-GNSS poll, DOP 1, MON-HW/MON-HW2 5, MON-VER ("EXT CORE 4" with
    00190000 is UBLOX_M9), CFG-CFG save. Nothing may be NAKed: ArduPilot
    ignores a NAK and asks again forever. Returns (Replies, MON-VER frame)."""
    r = Replies()
    ardupilot_probe(fd, path, probe, baud)
    prt = poll_cfg(s, fd, 0x00, b"", r)
    assert len(prt) == 20 and prt[0] == 1, prt.hex()
    ardupilot_rate_step(s, fd, 0x01, 0x07, 1, r)
    rate = poll_cfg(s, fd, 0x08, b"", r)
    assert len(rate) == 6, rate.hex()
    if struct.unpack("<HHH", rate) != (200, 1, 0):
        set_cfg(s, fd, 0x08, struct.pack("<HHH", 200, 1, 0), r)
        assert poll_cfg(s, fd, 0x08, b"", r) == struct.pack("<HHH", 200, 1, 0)
    s.wait_for(pvt_fix_ok, fix_limit_s, "the first NAV-PVT with gnssFixOK")

    def steps(ids):
        for c, i in ids:
            ardupilot_rate_step(s, fd, c, i, ARDUPILOT_M9_RATES[(c, i)], r)

    steps([(0x01, 0x06), (0x01, 0x03), (0x01, 0x02), (0x01, 0x12), (0x01, 0x20)])  # SOL .. TIMEGPS
    # STEP_POLL_SVINFO, STEP_POLL_NAV, STEP_POLL_GNSS.
    s.msgs.clear()
    send(fd, frame(0x01, 0x30))
    end = time.monotonic() + 0.5
    while time.monotonic() < end:
        s.pump(end - time.monotonic())
    assert not [m for _, k, m in s.msgs if k == "ubx" and (m[2:4] == b"\x01\x30" or m[2] == 0x05)], \
        "an M9 answered a NAV-SVINFO poll"
    nav5 = bytearray(poll_cfg(s, fd, 0x24, b"", r))
    assert len(nav5) == 36, len(nav5)
    if nav5[2] != 8:
        struct.pack_into("<HB", nav5, 0, 0x0001, 8)
        set_cfg(s, fd, 0x24, bytes(nav5), r)
        assert poll_cfg(s, fd, 0x24, b"", r)[2] == 8
    gnss = poll_cfg(s, fd, 0x3E, b"", r)
    assert len(gnss) == 4 + 8 * gnss[3] and gnss[3] >= 1, gnss.hex()
    steps([(0x01, 0x04), (0x0A, 0x09), (0x0A, 0x0B)])  # DOP, MON-HW, MON-HW2
    mv = r.timed(s, fd, frame(0x0A, 0x04), is_ubx(0x0A, 0x04), 2.0, "MON-VER")
    if save:
        ardupilot_save(s, fd, r)
    return r, mv


def ardupilot_save(s, fd, r):
    """CFG-CFG save (_save_cfg: saveMask SAVE_CFG_ALL 0x061F) once configured;
    nothing NAKed up to here."""
    set_cfg(s, fd, 0x09, struct.pack("<III", 0, 0x061F, 0), r)
    naks = [m for _, k, m in s.seen if k == "ubx" and m[2:4] == b"\x05\x00"]
    assert not naks, f"NAKed: {[m[6:8].hex() for m in naks]}"


# --- ArduPilot on an F9 (protocol 27) ------------------------------------------
# AP_GPS_UBLOX.cpp/.h (4.4-4.5): MON-VER hwVersion "00190000" with swVersion
# "EXT CORE 1" is UBLOX_F9, which has supports_F9_config(). The legacy CFG
# loop above still runs; on the pass after MON-VER, STEP_TMODE VALGETs
# CFG-TMODE-MODE and sets 0 if it is not, and for GPS_TYPE 17/18
# STEP_RTK_MOVBASE runs _configure_config_set over the moving-baseline list.
# _configure_config_set: one CFG-VALGET (version 0, layer 0 = RAM, position
# 0) naming every key of the list. _parse_gps(MSG_CFG_VALGET): for each key
# of the reply whose value differs, at once a CFG-VALSET of that key alone
# (_configure_valset: version 1, layers = UBX_VALSET_LAYER_ALL 7 by default,
# transaction 0); the list is done when a later VALGET reads every key as
# listed (done_mask). ACKs are not waited for: while unconfigured the loop
# sends its next step every 750 ms (_delay_time) and walks the list again,
# so a reply later than that costs a repeated VALGET, not the start-up.
# A NAK of the many-key VALGET makes it fall back to one key per VALGET.
AP_TMODE_MODE = 0x20030001
AP_VALSET_LAYERS = 0x07          # UBX_VALSET_LAYER_ALL
ARDUPILOT_CONFIG_STEP_S = 0.75   # _delay_time while unconfigured, once NAV-PVT is seen
K_UART2_ENABLED = 0x10530005
# CFG-MSGOUT-RTCM_3X_TYPE{4072_0, 4072_1, 1077, 1087, 1097, 1127, 1230}, I2C ids (UART1 +1, UART2 +2).
AP_MB_RTCM_I2C = (0x209102FE, 0x20910381, 0x209102CC, 0x209102D1, 0x20910318, 0x209102D6, 0x20910303)
RTK_MB_RTCM_RATE = 1
# AP_GPS.cpp send_blob_start: GPS_TYPE 17/18 without GPS_DRV_OPTIONS
# UBX_MBUseUart2 probe at 460800 (RTCM between the receivers goes through the
# autopilot); otherwise 230400.
ARDUPILOT_PROBE_460800 = bytes.fromhex("B5 62 06 01 03 00 01 06 01 12 4F") + b"$PUBX,41,1,0023,0001,460800,0*11\r\n"


def ardupilot_mb_list(role, uart2):
    """config_MB_{Base,Rover}_uart{1,2} of AP_GPS_UBLOX.cpp, in order: (key, value)."""
    rel = lambda port, v: (K_MSGOUT_NAV_RELPOSNED + port, v)
    rtcm = lambda port, v: [(k + port, v) for k in AP_MB_RTCM_I2C]
    if role == "base" and not uart2:
        return ([(K_UART1OUT_RTCM3X, 1), (K_UART2OUT_RTCM3X, 0), rel(1, 0), rel(2, 0)] +
                rtcm(1, RTK_MB_RTCM_RATE) + rtcm(2, 0))
    if role == "base":
        return ([(K_UART2_ENABLED, 1), (K_UART2_BAUDRATE, 460800), (K_UART2OUT_RTCM3X, 1), (K_UART1OUT_RTCM3X, 0),
                 (K_UART1IN_RTCM3X, 1), rel(2, 0), rel(1, 0)] + rtcm(2, RTK_MB_RTCM_RATE) + rtcm(1, 0))
    if role == "rover" and not uart2:
        return ([(K_UART2OUT_RTCM3X, 0), (K_UART1IN_RTCM3X, 1), (K_UART2IN_RTCM3X, 0), rel(1, 1), rel(2, 0)] +
                rtcm(1, 0) + rtcm(2, 0))
    if role == "rover":
        return ([(K_UART2_ENABLED, 1), (K_UART2_BAUDRATE, 460800), (K_UART2OUT_RTCM3X, 0), (K_UART2IN_RTCM3X, 1),
                 (K_UART1IN_RTCM3X, 0), rel(1, 1), rel(2, 0)] + rtcm(2, 0) + rtcm(1, 0))
    raise ValueError(f"role {role!r}: want 'base' or 'rover'")


def parse_valget(data):
    """{key: value} of a CFG-VALGET reply frame, keys in reply order."""
    p, out, off = data[6:-2], {}, 4
    while off < len(p):
        key = struct.unpack_from("<I", p, off)[0]
        n = key_value_bytes(key)
        assert off + 4 + n <= len(p), f"VALGET reply cut inside key {key:08x}"
        out[key] = int.from_bytes(p[off + 4:off + 4 + n], "little")
        off += 4 + n
    return out


def ardupilot_config_set(s, fd, pairs, r, what, limit_s=ARDUPILOT_CONFIG_STEP_S):
    """One walk of _configure_config_set over pairs: the VALGET of every key,
    its reply then ACK within limit_s; one VALSET v1 (layers 7) per key read
    back different, sent back to back, each ACKed within limit_s of the
    reply. Returns the keys it set, {key: value read before}."""
    t0 = time.monotonic()
    send(fd, frame(0x06, 0x8B, valget([k for k, _ in pairs])))
    t, data = s.wait_for(lambda k, m: k == "ubx" and m[2:4] in (b"\x06\x8b", b"\x05\x00"), limit_s,
                         f"{what}: VALGET reply")
    assert data[2:4] == b"\x06\x8b", f"{what}: VALGET of {len(pairs)} keys NAKed (ArduPilot then asks one by one)"
    r.times.append((f"{what} VALGET", t - t0))
    a = s.wait_for(is_ack_for(0x06, 0x8B), limit_s, f"{what}: ACK after VALGET")[1]
    assert a == ack(0x06, 0x8B), a.hex()
    got = parse_valget(data)
    assert list(got) == [k for k, _ in pairs], f"{what}: reply keys {[hex(k) for k in got]} not the list's"
    wrong = {k: got[k] for k, v in pairs if got[k] != v}
    t1 = time.monotonic()
    for k, v in pairs:
        if k in wrong:
            send(fd, frame(0x06, 0x8A, valset([(k, v)], AP_VALSET_LAYERS, version=1)))
    for k in wrong:
        t, a = s.wait_for(is_ack_for(0x06, 0x8A), limit_s, f"{what}: ACK of VALSET {k:08x}")
        assert a == ack(0x06, 0x8A), f"{what}: VALSET {k:08x} NAKed"
        r.times.append((f"{what} VALSET {k:08x}", t - t1))
    return wrong


def ardupilot_f9_steps(s, fd, r, role=None, uart2=False):
    """The F9 steps of the pass after MON-VER: STEP_TMODE, then for role
    'base'/'rover' (GPS_TYPE 17/18) STEP_RTK_MOVBASE; each repeated until
    a VALGET reads every key as wanted (at most 3 walks). Returns
    {step: keys set on the first walk}."""
    steps = [("TMODE", [(AP_TMODE_MODE, 0)])]
    if role:
        steps.append((f"MB {role}{' uart2' if uart2 else ''}", ardupilot_mb_list(role, uart2)))
    out = {}
    for what, pairs in steps:
        out[what] = ardupilot_config_set(s, fd, pairs, r, what)
        for _ in range(2):
            if not ardupilot_config_set(s, fd, pairs, r, what):
                break
        else:
            raise AssertionError(f"{what}: keys still differ after three walks")
    return out


def ardupilot_startup_f9p(s, fd, path, role=None, uart2=False, fix_limit_s=4.0):
    """ArduPilot 4.5 against a ZED-F9P with GPS_TYPE 1 (role None), 17
    ('base') or 18 ('rover'): the probe (460800 for 17/18 unless uart2),
    the legacy pass of ardupilot_startup_m9 with MON-VER giving UBLOX_F9,
    then ardupilot_f9_steps and CFG-CFG save; nothing NAKed. Returns
    (Replies, MON-VER frame, {step: keys set})."""
    mb_uart1 = role is not None and not uart2
    r, mv = ardupilot_startup_m9(s, fd, path, fix_limit_s, probe=ARDUPILOT_PROBE_460800 if mb_uart1 else ARDUPILOT_PROBE,
                                 baud=460800 if mb_uart1 else 230400, save=False)
    sw, hw = mv[6:6 + 30], mv[6 + 30:6 + 40]
    assert hw.startswith(b"00190000") and sw.startswith(b"EXT CORE 1"), f"not UBLOX_F9 to ArduPilot: {sw!r} {hw!r}"
    set_keys = ardupilot_f9_steps(s, fd, r, role, uart2)
    ardupilot_save(s, fd, r)
    return r, mv, set_keys


# --- reading what the host got -----------------------------------------------

def svinfo_channels(m):
    """NAV-SVINFO channels: [(svid, used, quality, cno_dbhz)]."""
    n = m[6 + 4]
    out = []
    for i in range(n):
        chn, svid, flags, quality, cno = struct.unpack_from("<BBBBB", m, 6 + 8 + 12 * i)
        out.append((svid, bool(flags & 1), quality & 0x0F, cno))
    return out


def mon_hw_jam(m):
    """MON-HW (agcCnt, jamInd)."""
    return struct.unpack_from("<H", m, 6 + 18)[0], m[6 + 45]


def nav_status_spoof(m):
    """NAV-STATUS spoofDetState (flags2 bits 3-4)."""
    return (m[6 + 7] >> 3) & 3
