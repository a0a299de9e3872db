#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""gnssemud as a u-blox M8 on real ports, end to end (docs/ports.md §Tests).

Cases (each bounded, every process killed and the temp dir removed on exit):
  px4        a line glitch first (a truncated UBX header announcing 1023 bytes):
             the next MON-VER poll is answered within 1 s (idle resync); then
             PX4's UBX start-up sequence over a pty, byte for byte, then
             NAV-PVT with gnssFixOK at the rate PX4 set (CFG-RATE 200 ms); then
             CFG-RST (GNSS-only hot start): no ACK, NAV-STATUS msss restarts,
             the fix comes back within about a second and ttff counts from
             the reset (the sequences: ubx_host.py)
  ardupilot  ArduPilot's poll / set / poll-compare sequence over a pty, its
             NAV-SVINFO poll (chipGen 4 = M8), NAV-PVT gnssFixOK and the
             rates it set
  px4_faults, ardupilot_faults
             the same start-ups while a scenario's jammer, satellite step
             and port latency run and a fault is injected with gnssemu ctl
             (ubx_startup_faults.py)
  gpsd_ubx   gpsd (not read-only) probes and configures the receiver itself:
             DEVICE driver "u-blox" in native mode, then TPV mode 3
  gpsd_nmea  an NMEA-only port: gpsd reports driver NMEA0183 and TPV mode 3
  gpsdecode  a file port's UBX log decoded by gpsdecode equals the fixes the
             daemon logged (debug log) and the NMEA log of the same epochs
  serial     a `type = "serial"` port on one end of a socat pty pair. It runs
             the daemon's termios path: libserialport 0.1.1 refuses
             /dev/pts/N, so libserialport itself is NOT exercised here (only
             on a real UART). Baud switch by $PUBX,41 and by CFG-PRT after the
             drain (termios speed checked); PX4's way (CFG-PRT at the current
             baud, CFG-PRT with the target baud, host side switched, CFG-PRT
             again at the target baud, ACKed there); reopen after the device
             disappears
  wallclock  use_wall_clock_date: iTOW on whole seconds at 1 Hz, and on
             200 ms boundaries after CFG-RATE 200
  net        TCP server (two clients, replies to the asking client only) and
             UDP output on loopback
  budget     9600 baud with NAV-SAT + NAV-SVINFO + NMEA at 5 Hz: the line
             carries at most baud/10 bytes/s, messages dropped, one warning
  jamming    MON-HW noisePerMS / agcCnt / jamInd with [signal] noise_rise_db
             30 dB differ from the quiet (1 dB) daemon as docs/ubx.md maps
             them
  nav5       CFG-NAV5 dynModel drives the receiver: on the demo circle
             (5 m/s) NAV-PVT gSpeed is ~5 m/s, exactly 0 with the stationary
             model (velocity restricted to 0), ~5 m/s again with automotive
  px4_m9_gnss, px4_m8_gnss, ardupilot_gnss, ardupilot_m9_gnss, gpsd_m9_sky
             on the multi-GNSS nav (--nav-mgnss): PX4's GPS_1_GNSS = GPS +
             Galileo on the M9 (CFG-SIGNAL VALSET) and ArduPilot's
             GPS_GNSS_MODE = 5 on the M8 (CFG-GNSS) leave exactly those
             systems in NAV-SAT / NAV-SVINFO after the chip's restart, with a
             fix; gpsd 3.22 reports SKY gnssid for every system of the M9,
             from UBX and (gpsd_m9_sky_nmea) from an NMEA-only port
  state_file a host's saved configuration (5 Hz, NAV-PVT, UBX only) is what
             the chip runs after a gnssemud restart; CFG-CFG clear and
             another restart: factory-fresh
  cold_start gpsd (read-only, NMEA) reads the pty; after the power-on hot
             start's fix (mode 3) a host sends CFG-RST cold start: gpsd sees
             no fix (mode 1) for about the M8's cold TTFF (data sheet 29 s,
             GPS), then mode 3 again; NAV-STATUS ttff counts from the reset
             (about 70 s, the one slow case)
usage: ubx_ports_integration.py --gnssemud PATH [--gnssemu PATH] --nav FILE CASE
"""
import argparse
import datetime
import json
import math
import os
import re
import select
import shutil
import signal
import socket
import struct
import subprocess
import sys
import termios
import time
import tty

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from itlib import RigBase, free_port  # noqa: E402
from ubx_startup_faults import case_ardupilot_faults, case_px4_faults  # noqa: E402
from ubx_host import (ARDUPILOT_M9_RATES, AP_TMODE_MODE, ardupilot_startup_f9p, rtcm_number, is_ubx, K_SIGNAL_BDS_ENA, K_SIGNAL_GAL_ENA, K_SIGNAL_GLO_ENA, K_SIGNAL_GPS_ENA,  # noqa: E402
                      K_SIGNAL_QZSS_ENA, K_SIGNAL_SBAS_ENA, ardupilot_cfg_gnss, valset, K_MSGOUT_MON_RF, K_MSGOUT_NAV_PVT, K_NAVSPG_DYNMODEL, K_RATE_MEAS, K_UART1_BAUDRATE,
                      PX4_M9_RATE_MEAS_MS, PX4_F9P_RATE_MEAS_MS, K_NAVHPG_DGNSSMODE, K_UART2_BAUDRATE, K_UART2IN_RTCM3X, Stream, ack, ardupilot_rates, ardupilot_startup, ardupilot_startup_m9, frame, is_ack_for, nmea,
                      poll_cfg, pvt_fix_ok, pvt_lost_after, px4_cfg_gnss, px4_rates, px4_startup, px4_startup_m9, send, set_cfg, split_stream,
                      stty_speed, valget_values)

ORIGIN = (48.8738, 2.2950, 100.0)
CASE_LIMIT_S = 60
CASE_LIMITS_S = {"cold_start": 100, "power_on_cold": 100, "ardupilot_gnss": 100, "ardupilot_f9p_heading": 100}  # a cold TTFF (~30 s) plus gpsd's start

# --- rig ---------------------------------------------------------------------

class Rig(RigBase):
    def __init__(self, args):
        super().__init__("gnssemu-ubx-it-")
        self.args = args
        self.nav = None  # a case's own nav file (the multi-GNSS one); None: --nav
        self.fds = []
        self.banner = []

    def start_daemon(self, outputs, rate_hz=1.0, verbose=False, n_outputs=None, extra_toml="", scenario=None,
                     receiver_toml=""):
        cfg = os.path.join(self.tmp, "it.toml")
        with open(cfg, "w") as f:
            f.write(f"""
[origin]
lat_deg = {ORIGIN[0]}
lon_deg = {ORIGIN[1]}
height_m = {ORIGIN[2]}
[nav]
file = "{os.path.abspath(self.nav or self.args.nav)}"
[receiver]
rate_hz = {rate_hz}
{receiver_toml}
[truth]
port = {free_port(socket.SOCK_DGRAM)}
[demo]
enabled = true
{extra_toml}
{outputs}
""")
        self.daemon_log_path = os.path.join(self.tmp, "gnssemud.log")
        self.daemon_log = open(self.daemon_log_path, "w")
        argv = [self.args.gnssemud, "--config", cfg] + (["-v"] if verbose else []) + \
            (["--scenario", scenario] if scenario else [])
        self.daemon = self.spawn(argv, stdout=subprocess.PIPE, stderr=self.daemon_log, text=True)
        n = outputs.count("[[output]]") if n_outputs is None else n_outputs
        for _ in range(n + 1):
            line = self.daemon.stdout.readline()
            if not line:
                raise AssertionError("gnssemud exited: " + open(self.daemon_log_path).read()[-2000:])
            self.banner.append(line.strip())
            print("  " + line.strip())

    def open_tty(self, path):
        fd = os.open(path, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
        tty.setraw(fd)
        self.fds.append(fd)
        return fd

    def daemon_log_text(self):
        self.daemon_log.flush()
        return open(self.daemon_log_path).read()

    def close(self, failed):
        for fd in self.fds:
            try:
                os.close(fd)
            except OSError:
                pass
        rc = self.stop_all()
        if failed:
            self.dump_logs()
        self.remove_tmp()
        return rc


def pty_output(rig, name="gps0", extra=""):
    path = os.path.join(rig.tmp, name)
    return path, f'[[output]]\nname = "{name}"\ntype = "pty"\npath = "{path}"\n{extra}\n'


# --- cases -------------------------------------------------------------------

def case_px4(rig):
    path, out = pty_output(rig)
    rig.start_daemon(out)
    fd = rig.open_tty(path)
    s = Stream(fd)
    # 0. A line glitch: a truncated header announcing a 1023-byte payload. The
    # host's next command must not wait for 1031 bytes: after ~100 ms of
    # silence the receiver gives the partial frame up and finds the poll.
    send(fd, bytes.fromhex("B562 0601 FF03"))
    t0 = time.monotonic()
    send(fd, frame(0x0A, 0x04))
    t, _ = s.wait_for(lambda k, m: k == "ubx" and m[2:4] == b"\x0a\x04", 1.0, "MON-VER after a truncated header")
    print(f"  px4: MON-VER answered {t - t0:.3f} s after a truncated header")
    # 1.-4. PX4's start-up, byte for byte, every reply within its 250 ms.
    replies = px4_startup(s, fd)
    # 5. NAV-PVT at 5 Hz with gnssFixOK (the first epoch waits for a whole GPS
    # second, time.use_wall_clock_date; the hot start's fix a second later);
    # NMEA is off (PX4's CFG-PRT).
    msgs = px4_rates(s)
    pvts = sum(1 for _, k, m in msgs if k == "ubx" and m[2:4] == b"\x01\x07")
    print(f"  px4: every step answered byte for byte ({replies.summary()}); {pvts} NAV-PVT in 3 s, "
          f"iTOW step 200 ms, gnssFixOK")
    # 6. CFG-RST, GNSS-only hot start (configuration kept): no ACK, the
    # receiver restarts: msss from the reset, fix reacquired (hot start: about
    # 1 s), ttff from the reset.
    s.msgs.clear()
    send(fd, frame(0x01, 0x03))
    st = s.frame_of(0x01, 0x03)
    ttff0, msss0 = struct.unpack_from("<II", st, 6 + 8)
    assert msss0 > 3000 and 0 < ttff0 <= msss0, (ttff0, msss0)
    s.msgs.clear()
    t_rst = time.monotonic()
    send(fd, frame(0x06, 0x04, bytes([0x00, 0x00, 0x02, 0x00])))
    end = t_rst + 0.5
    while time.monotonic() < end:
        s.pump(end - time.monotonic())
    assert not any(k == "ubx" and m[2] == 0x05 for _, k, m in s.msgs), "CFG-RST was ACKed"
    # A NAV-PVT composed before the reset may still be on the line as it is
    # sent: only what arrives after these 0.5 s counts as the fix coming back.
    s.msgs.clear()
    _, pvt = s.wait_for(lambda k, m: k == "ubx" and m[2:4] == b"\x01\x07" and m[6 + 21] & 1, 3.0,
                        "NAV-PVT with gnssFixOK after the reset")
    s.msgs.clear()
    send(fd, frame(0x01, 0x03))
    st = s.frame_of(0x01, 0x03)
    ttff, msss = struct.unpack_from("<II", st, 6 + 8)
    since = (time.monotonic() - t_rst) * 1000
    assert msss <= since + 50, f"msss {msss} ms but the reset was {since:.0f} ms ago"
    assert 0 < ttff <= msss, f"ttff {ttff} msss {msss}"
    assert "CFG-RST hot start (navBbrMask 0x0000): the receiver restarts" in rig.daemon_log_text(), \
        "no receiver restart logged"
    print(f"  px4: CFG-RST: msss {msss0} -> {msss} ms, ttff {ttff} ms from the reset, fix back")


M9 = 'generation = "m9"'


def case_px4_m9(rig):
    """PX4 against an emulated NEO-M9N: its protocol-27+ start-up by
    CFG-VALSET (PX4-GPSDrivers ubx.cpp configure/configureDevice), then
    NAV-PVT at its 8 Hz with gnssFixOK, NAV-DOP/STATUS every epoch, NAV-SAT
    every 10th, no NMEA, and MON-RF (PX4 reads jamming from it)."""
    path, out = pty_output(rig)
    rig.start_daemon(out, receiver_toml=M9)
    fd = rig.open_tty(path)
    s = Stream(fd)
    replies = px4_startup_m9(s, fd, path)
    s.wait_for(pvt_fix_ok, 4.0, "the first gnssFixOK")
    seconds = 3.0
    msgs = s.collect(seconds)
    pvts = [m for _, k, m in msgs if k == "ubx" and m[2:4] == b"\x01\x07"]
    assert not [m for _, k, m in msgs if k == "nmea"], "NMEA still sent after CFG-UART1OUTPROT-NMEA 0"
    hz = 1000 / PX4_M9_RATE_MEAS_MS
    assert len(pvts) >= hz * seconds - 3, f"{len(pvts)} NAV-PVT in {seconds} s, want ~{hz * seconds:.0f} at {hz} Hz"
    itows = [struct.unpack_from("<I", m, 6)[0] for m in pvts]
    steps_ms = {b - a for a, b in zip(itows, itows[1:])}
    assert steps_ms == {PX4_M9_RATE_MEAS_MS}, f"iTOW steps {sorted(steps_ms)} ms, want {PX4_M9_RATE_MEAS_MS}"
    assert all(m[6 + 21] & 1 and m[6 + 20] == 3 for m in pvts), "NAV-PVT without gnssFixOK / 3D"
    count = lambda c, i: sum(1 for _, k, m in msgs if k == "ubx" and m[2] == c and m[3] == i)
    for name, c, i in (("NAV-STATUS", 1, 3), ("NAV-DOP", 1, 4)):
        assert abs(count(c, i) - len(pvts)) <= 1, f"{count(c, i)} {name} for {len(pvts)} NAV-PVT (rate 1)"
    assert abs(count(1, 0x35) - len(pvts) / 10) <= 1, f"{count(1, 0x35)} NAV-SAT for {len(pvts)} NAV-PVT (rate 10)"
    # What PX4 set reads back through VALGET (RAM), the UART1 rates included.
    uart1 = lambda key: key + 1
    got = valget_values(s, fd, [K_RATE_MEAS, K_NAVSPG_DYNMODEL, K_UART1_BAUDRATE, uart1(K_MSGOUT_NAV_PVT),
                                uart1(K_MSGOUT_MON_RF)])
    want = {K_RATE_MEAS: PX4_M9_RATE_MEAS_MS, K_NAVSPG_DYNMODEL: 7, K_UART1_BAUDRATE: 115200,
            uart1(K_MSGOUT_NAV_PVT): 1, uart1(K_MSGOUT_MON_RF): 1}
    assert got == want, f"VALGET {got}, want {want}"
    rf = count(0x0A, 0x38)
    assert abs(rf - len(pvts)) <= 1, f"{rf} MON-RF for {len(pvts)} NAV-PVT (PX4 set rate 1)"
    rf_note = f"{rf} MON-RF"
    print(f"  px4_m9: VALSET start-up answered byte for byte ({replies.summary()}); {len(pvts)} NAV-PVT in "
          f"{seconds:.0f} s, iTOW step {PX4_M9_RATE_MEAS_MS} ms, gnssFixOK; {rf_note}")


F9P = 'generation = "f9p"'


def px4_f9p_run(rig, heading):
    """PX4 against an emulated ZED-F9P, in normal mode and as a dual-F9P
    heading rover (UBXMode::RoverWithMovingBase): the protocol-27 start-up
    with every block ACKed, DGNSSMODE included (PX4-GPSDrivers ubx.cpp
    configureDevice), then NAV-PVT at 10 Hz (8 Hz with heading) with
    gnssFixOK, and with heading NAV-RELPOSNED and NAV-HPPOSLLH every epoch,
    RELPOSNED's iTOW equal to NAV-PVT's (what ArduPilot checks too)."""
    if True:
        path, out = pty_output(rig)
        rig.start_daemon(out, receiver_toml=F9P)
        fd = rig.open_tty(path)
        s = Stream(fd)
        replies = px4_startup_m9(s, fd, path, f9p=True, heading=heading)
        s.wait_for(pvt_fix_ok, 4.0, "the first gnssFixOK")
        seconds = 2.0
        msgs = s.collect(seconds)
        period = PX4_M9_RATE_MEAS_MS if heading else PX4_F9P_RATE_MEAS_MS
        pvts = [m for _, k, m in msgs if k == "ubx" and m[2:4] == b"\x01\x07"]
        itows = [struct.unpack_from("<I", m, 6)[0] for m in pvts]
        steps_ms = {b - a for a, b in zip(itows, itows[1:])}
        assert steps_ms == {period}, f"iTOW steps {sorted(steps_ms)} ms, want {period}"
        assert all(m[6 + 21] & 1 for m in pvts), "NAV-PVT without gnssFixOK"
        rel = [m for _, k, m in msgs if k == "ubx" and m[2:4] == b"\x01\x3c"]
        hp = [m for _, k, m in msgs if k == "ubx" and m[2:4] == b"\x01\x14"]
        if heading:
            assert abs(len(rel) - len(pvts)) <= 1 and abs(len(hp) - len(pvts)) <= 1, (len(rel), len(hp), len(pvts))
            assert all(len(m) == 8 + 64 and m[6] == 1 for m in rel), "NAV-RELPOSNED not version 1, 64 bytes"
            rel_itows = {struct.unpack_from("<I", m, 6 + 4)[0] for m in rel}
            assert rel_itows <= set(itows) | {itows[-1] + period}, "RELPOSNED iTOW not a NAV-PVT's"
        else:
            assert not rel, "NAV-RELPOSNED without PX4 asking for it"
        got = valget_values(s, fd, [K_RATE_MEAS, K_NAVHPG_DGNSSMODE] + ([K_UART2_BAUDRATE, K_UART2IN_RTCM3X] if heading else []))
        want = {K_RATE_MEAS: period, K_NAVHPG_DGNSSMODE: 3}
        if heading:
            want.update({K_UART2_BAUDRATE: 230400, K_UART2IN_RTCM3X: 1})
        assert got == want, f"VALGET {got}, want {want}"
        print(f"  px4_f9p{' heading' if heading else ''}: VALSET start-up answered, DGNSSMODE ACKed "
              f"({replies.summary()}); {len(pvts)} NAV-PVT in {seconds:.0f} s, iTOW step {period} ms, gnssFixOK; "
              f"{len(rel)} NAV-RELPOSNED, {len(hp)} NAV-HPPOSLLH")


def case_px4_f9p(rig):
    px4_f9p_run(rig, heading=False)


def case_px4_f9p_heading(rig):
    px4_f9p_run(rig, heading=True)


def case_ardupilot(rig):
    path, out = pty_output(rig)
    rig.start_daemon(out)
    fd = rig.open_tty(path)
    s = Stream(fd)
    replies, sv = ardupilot_startup(s, fd, path)
    msgs = ardupilot_rates(s)
    count = lambda c, i: sum(1 for _, k, m in msgs if k == "ubx" and m[2] == c and m[3] == i)
    print(f"  ardupilot: every poll answered and read back as set ({replies.summary()}); chipGen 4 "
          f"({sv[6 + 4]} channels); {count(1, 7)} NAV-PVT with gnssFixOK and {count(1, 4)} NAV-DOP in 2 s")


def case_ardupilot_m9(rig):
    """ArduPilot 4.5 against an emulated NEO-M9N: it configures an M9 with
    the legacy CFG messages as an M8 (only F9 and M10 get CFG-VALSET), finds
    the generation from MON-VER, and must finish: nothing NAKed, every rate
    read back, then the rates it set on the line."""
    path, out = pty_output(rig)
    rig.start_daemon(out, receiver_toml=M9)
    fd = rig.open_tty(path)
    s = Stream(fd)
    replies, mv = ardupilot_startup_m9(s, fd, path)
    sw, hw = mv[6:6 + 30].rstrip(b"\0"), mv[6 + 30:6 + 40].rstrip(b"\0")
    assert sw.startswith(b"EXT CORE 4") and hw == b"00190000", (sw, hw)
    seconds = 3.0
    msgs = ardupilot_rates(s, seconds, ARDUPILOT_M9_RATES)  # MON-HW2 included (docs/ubx.md "MON-HW2")
    count = lambda c, i: sum(1 for _, k, m in msgs if k == "ubx" and m[2] == c and m[3] == i)
    print(f"  ardupilot_m9: {sw.decode()} / {hw.decode()}; every step answered, nothing NAKed "
          f"({replies.summary()}); {count(1, 7)} NAV-PVT, {count(1, 4)} NAV-DOP, {count(1, 0x20)} NAV-TIMEGPS, "
          f"{count(0x0A, 9)} MON-HW, {count(0x0A, 0x0B)} MON-HW2 in {seconds:.0f} s")


def ardupilot_f9p_run(rig, role=None, uart2=False):
    """ArduPilot 4.5 against an emulated ZED-F9P (ubx_host.ardupilot_startup_f9p):
    GPS_TYPE 1 (role None) with CFG-TMODE-MODE left at survey-in by an
    earlier user (STEP_TMODE must set it back to 0), or GPS_TYPE 17/18 with
    the moving-baseline list (uart2: GPS_DRV_OPTIONS UBX_MBUseUart2). Every
    VALGET reply and VALSET ACK within ArduPilot's 750 ms step, every key
    it set reads back as listed, then NAV-PVT at 5 Hz with gnssFixOK and
    fixType 3, the rates it set; the rover: NAV-RELPOSNED every epoch with
    NAV-PVT's iTOW (the match AP_GPS_UBLOX waits for); the base: RTCM 3
    4072.0 and MSM7 of four systems on UART1 (uart1 list; 4072.1 is not
    emulated)."""
    if role == "base":
        rig.nav = rig.args.nav_mgnss
    path, out = pty_output(rig)
    rig.start_daemon(out, receiver_toml=F9P)
    fd = rig.open_tty(path)
    s = Stream(fd)
    t_open = time.monotonic()
    if role is None:
        # An earlier user left the chip a survey-in base (factory UART1: 38400).
        send(fd, frame(0x06, 0x8A, valset([(AP_TMODE_MODE, 1)])))
        a = s.wait_for(is_ack_for(0x06, 0x8A), 1.0, "ACK of the TMODE-MODE 1 VALSET")[1]
        assert a == ack(0x06, 0x8A), a.hex()
        s.msgs.clear()
    replies, mv, set_keys = ardupilot_startup_f9p(s, fd, path, role, uart2)
    t_done = time.monotonic()
    if role is None:
        assert set_keys["TMODE"] == {AP_TMODE_MODE: 1}, f"STEP_TMODE set {set_keys['TMODE']}, want TMODE-MODE 1 -> 0"
    else:
        mb = [v for w, v in set_keys.items() if w.startswith("MB")][0]
        assert mb, "STEP_RTK_MOVBASE found every key already as listed: nothing exercised"
    vg = [dt for w, dt in replies.times if w.endswith("VALGET")]
    vs = [dt for w, dt in replies.times if " VALSET " in w]
    seconds = 3.0
    msgs = ardupilot_rates(s, seconds, ARDUPILOT_M9_RATES)
    pvts = [m for _, k, m in msgs if k == "ubx" and m[2:4] == b"\x01\x07"]
    itows = [struct.unpack_from("<I", m, 6)[0] for m in pvts]
    assert {b - a for a, b in zip(itows, itows[1:])} == {200}, f"NAV-PVT iTOW steps {sorted(set(itows))}"
    rel = [m for _, k, m in msgs if k == "ubx" and m[2:4] == b"\x01\x3c"]
    rtcm = [m for _, k, m in msgs if k == "rtcm"]
    note = ""
    if role == "rover":
        assert abs(len(rel) - len(pvts)) <= 1, f"{len(rel)} NAV-RELPOSNED for {len(pvts)} NAV-PVT (rate 1 on UART1)"
        rel_itows = [struct.unpack_from("<I", m, 6 + 4)[0] for m in rel]
        assert set(rel_itows) <= set(itows) | {itows[-1] + 200}, "RELPOSNED iTOW not a NAV-PVT's"
        assert not rtcm, f"{len(rtcm)} RTCM 3 frames from a rover (list sets every RTCM output 0)"
        note = f"; {len(rel)} NAV-RELPOSNED, iTOW equal to NAV-PVT's"
    elif role == "base":
        assert not rel, "NAV-RELPOSNED from a moving base (list sets it 0)"
    print(f"  ardupilot_f9p{'_' + role if role else ''}{'_uart2' if uart2 else ''}: "
          f"{mv[6:6 + 30].rstrip(bytes(1)).decode()} -> UBLOX_F9; "
          f"{len(replies.times)} replies, slowest {replies.worst()[1] * 1000:.1f} ms ({replies.worst()[0]}); "
          f"VALGET replies {min(vg) * 1000:.1f}-{max(vg) * 1000:.1f} ms, {len(vs)} VALSET ACKs "
          f"{(max(vs) * 1000 if vs else 0):.1f} ms at worst; set "
          + ", ".join(f"{w}: {len(k)} keys" for w, k in set_keys.items()) +
          f"; configured {t_done - t_open:.1f} s after open; {len(pvts)} NAV-PVT in {seconds:.0f} s, fixType 3{note}")
    if role == "base" and not uart2:
        want = {4072, 1077, 1087, 1097, 1127, 1230}
        got = {}
        for m in rtcm:
            got[rtcm_number(m)] = got.get(rtcm_number(m), 0) + 1
        assert want <= set(got), f"moving base: UART1 carried RTCM {got}, want {sorted(want)}"
        print(f"  ardupilot_f9p_base: RTCM 3 frames on UART1 in {seconds:.0f} s: {dict(sorted(got.items()))}")


def case_ardupilot_f9p(rig):
    ardupilot_f9p_run(rig)


def case_ardupilot_f9p_mb_rover(rig):
    ardupilot_f9p_run(rig, "rover")


def case_ardupilot_f9p_mb_rover_uart2(rig):
    ardupilot_f9p_run(rig, "rover", uart2=True)


def case_ardupilot_f9p_mb_base(rig):
    ardupilot_f9p_run(rig, "base")


# AP_GPS_UBLOX.cpp MSG_RELPOSNED: a heading is used only with all of
# valid_mask and none of invalid_mask (NAV-RELPOSNED flags bits).
RELPOSNED_VALID = (1 << 8) | (1 << 2) | (1 << 0) | (1 << 5) | (1 << 4)  # headingValid relPosValid gnssFixOK isMoving carrSolnFixed
RELPOSNED_INVALID = (1 << 6) | (1 << 7) | (1 << 3)                       # refPosMiss refObsMiss carrSolnFloat
MB_BASE_ARM_M = (0.0, 0.0, 0.0)
MB_ROVER_ARM_M = (0.5, 1.0, 0.0)  # forward, right, down
MB_YAW_DEG = 0.0                  # a standing vehicle without attitude faces north (docs/configuration.md "Lever arm")


def relposned(m):
    """NAV-RELPOSNED v1 fields: iTOW ms, relPosD m, length m, heading deg, accHeading deg, flags."""
    p = 6
    itow = struct.unpack_from("<I", m, p + 4)[0]
    d_cm, length_cm, heading = struct.unpack_from("<iii", m, p + 16)
    hp_d, hp_len = struct.unpack_from("<bb", m, p + 34)[0], struct.unpack_from("<b", m, p + 35)[0]
    acc_heading, flags = struct.unpack_from("<I", m, p + 52)[0], struct.unpack_from("<I", m, p + 60)[0]
    return (itow, d_cm * 0.01 + hp_d * 1e-4, length_cm * 0.01 + hp_len * 1e-4, heading * 1e-5, acc_heading * 1e-5,
            flags)


def case_ardupilot_f9p_heading(rig):
    """Two emulated ZED-F9Ps on one vehicle (lever arms MB_BASE_ARM_M and
    MB_ROVER_ARM_M) as ArduPilot's GPS_TYPE 17 and 18 (RTCM through the
    autopilot: the uart1 lists): both configured (ardupilot_startup_f9p),
    the base's RTCM 3 from its UART1 copied into the rover's, as
    AP_GPS injects it. The rover's NAV-RELPOSNED must then pass what
    AP_GPS_UBLOX checks: flags valid_mask without invalid_mask (diffSoln
    too), iTOW equal to a NAV-PVT's, and calculate_moving_base_yaw's length
    within 20 % of the lever-arm separation and relPosD within 20 % of it
    (level vehicle); its heading minus the arms' bearing is the vehicle's
    yaw within 3 accHeading + 1 deg; and at least 90 % of them after the
    first pass. The vehicle stands (demo speed 0: yaw north), as before
    take-off. The rover time-matches the base's epochs (docs/rtk.md
    "Relative position"): each RELPOSNED comes after the NAV-PVT of equal
    iTOW, once the base's RTCM of that epoch is in, and before the next
    epoch's NAV-PVT (ArduPilot holds a NAV-PVT until the RELPOSNED of its
    iTOW): the delay from that NAV-PVT, p50/p95, must stay under one epoch
    period."""
    rig.nav = rig.args.nav_mgnss
    base_path, rover_path = os.path.join(rig.tmp, "base"), os.path.join(rig.tmp, "rover")
    arm = lambda a: "[" + ", ".join(f"{x:.3f}" for x in a) + "]"
    vehicle = f"""
[[vehicle]]
id = "ego"
[[vehicle.receiver]]
name = "base"
lever_arm_m = {arm(MB_BASE_ARM_M)}
[[vehicle.receiver.output]]
type = "pty"
name = "base"
path = "{base_path}"
[[vehicle.receiver]]
name = "rover"
lever_arm_m = {arm(MB_ROVER_ARM_M)}
seed = 2
[[vehicle.receiver.output]]
type = "pty"
name = "rover"
path = "{rover_path}"
"""
    rig.start_daemon(vehicle, n_outputs=2, receiver_toml=F9P, extra_toml="speed_m_s = 0.0")
    fb, fr = rig.open_tty(base_path), rig.open_tty(rover_path)
    sb, sr = Stream(fb), Stream(fr)
    rb, _, set_b = ardupilot_startup_f9p(sb, fb, base_path, "base")
    rr, _, set_r = ardupilot_startup_f9p(sr, fr, rover_path, "rover")
    sep = math.dist(MB_BASE_ARM_M, MB_ROVER_ARM_M)
    bearing = math.degrees(math.atan2(MB_ROVER_ARM_M[1] - MB_BASE_ARM_M[1], MB_ROVER_ARM_M[0] - MB_BASE_ARM_M[0]))
    sb.msgs.clear()
    sr.msgs.clear()
    t0 = time.monotonic()
    forwarded = {}
    pvt_itow = {}
    first_fixed = None
    good, checked, errs, accs, lags = 0, 0, [], [], []
    last_pvt = None
    before_next, after_next = 0, 0  # RELPOSNEDs before / after the next epoch's NAV-PVT
    seen_flags = {}  # flags -> (count, last length m, last relPosD m)
    rejected = {}    # which of ArduPilot's checks a RELPOSNED failed
    end = t0 + 45.0
    while time.monotonic() < end:
        sb.pump(0.005)
        for _, k, m in sb.msgs:
            if k == "rtcm":
                send(fr, m)
                forwarded[rtcm_number(m)] = forwarded.get(rtcm_number(m), 0) + 1
        sb.msgs.clear()
        sr.pump(0.005)
        for t, k, m in sr.msgs:
            if k != "ubx":
                continue
            if m[2:4] == b"\x01\x07":
                itow = struct.unpack_from("<I", m, 6)[0]
                pvt_itow[itow] = t
                last_pvt = itow
            elif m[2:4] == b"\x01\x3c":
                itow, d_m, length_m, heading, acc, flags = relposned(m)
                seen_flags[flags] = (seen_flags.get(flags, (0,))[0] + 1, round(length_m, 3), round(d_m, 3))
                why = [w for w, bad in (("flags", flags & RELPOSNED_VALID != RELPOSNED_VALID or
                                             flags & RELPOSNED_INVALID or not flags & 2),
                                            ("iTOW", itow not in pvt_itow),
                                            ("length", abs(length_m - sep) > 0.2 * min(sep, length_m)),
                                            ("relPosD", abs(d_m) > 0.2 * min(sep, length_m))) if bad]
                ok = not why
                for w in why:
                    rejected[w] = rejected.get(w, 0) + 1
                if first_fixed is not None:
                    assert itow in pvt_itow, f"RELPOSNED iTOW {itow} before any NAV-PVT of that iTOW"
                    lags.append(t - pvt_itow[itow])  # after its epoch's NAV-PVT
                    if itow == last_pvt:
                        before_next += 1
                    else:
                        after_next += 1
                if first_fixed is None:
                    if ok:
                        first_fixed = t
                    continue
                checked += 1
                if ok:
                    good += 1
                    err = (heading - bearing - MB_YAW_DEG + 180.0) % 360.0 - 180.0
                    errs.append(err)
                    accs.append(acc)
                    assert abs(err) <= 3 * acc + 1.0, \
                        f"heading {heading:.2f} - arms {bearing:.2f} vs yaw {MB_YAW_DEG:.2f}: {err:.2f} deg (accHeading {acc:.2f})"
        sr.msgs.clear()
        if first_fixed is not None and time.monotonic() - first_fixed > 10.0:
            break
    assert forwarded, "no RTCM 3 from the moving base's UART1"
    assert first_fixed is not None, (f"no NAV-RELPOSNED passing ArduPilot's checks in 45 s (RTCM forwarded "
                                     f"{dict(sorted(forwarded.items()))}; flags seen: "
                                     + ", ".join(f"{f:#05x}: {v}" for f, v in seen_flags.items()) + ")")
    assert checked >= 30 and errs, f"{good}/{checked} NAV-RELPOSNED usable after the first; rejected by {rejected}"
    rms = math.sqrt(sum(e * e for e in errs) / len(errs))
    accs.sort()
    lags.sort()
    itows = sorted(pvt_itow)
    period_ms = sorted(b - a for a, b in zip(itows, itows[1:]))[(len(itows) - 1) // 2]
    p50_ms, p95_ms = lags[len(lags) // 2] * 1000, lags[min(len(lags) - 1, int(0.95 * len(lags)))] * 1000
    report = (f"base set {sum(len(v) for v in set_b.values())} keys, rover "
              f"{sum(len(v) for v in set_r.values())} (slowest replies {rb.worst()[1] * 1000:.1f} / "
              f"{rr.worst()[1] * 1000:.1f} ms); RTCM forwarded {dict(sorted(forwarded.items()))}; first RELPOSNED "
              f"passing ArduPilot's checks {first_fixed - t0:.1f} s after the feed; then {good}/{checked} usable "
              f"(rejected by {rejected}; flags seen {dict((hex(f), v[0]) for f, v in seen_flags.items())}); "
              f"heading error vs yaw + {bearing:.2f} deg: RMS {rms:.2f} deg, max {max(abs(e) for e in errs):.2f} deg, "
              f"accHeading median {accs[len(accs) // 2]:.2f} deg; separation {sep:.3f} m; RELPOSNED after the "
              f"NAV-PVT of its iTOW: p50 {p50_ms:.0f} ms, p95 {p95_ms:.0f} ms, max {lags[-1] * 1000:.0f} ms "
              f"(epoch period {period_ms} ms); {before_next} before the next epoch's NAV-PVT, {after_next} after")
    print(f"  ardupilot_f9p_heading: {report}")
    assert p95_ms < period_ms, f"RELPOSNED p95 {p95_ms:.0f} ms after its NAV-PVT, not within the {period_ms} ms epoch: {report}"
    assert before_next >= 0.95 * (before_next + after_next), f"RELPOSNED after the next epoch's NAV-PVT: {report}"
    assert good >= 0.9 * checked, f"RTK fixed and usable in {good}/{checked} epochs after the first, want 90 %: {report}"


def gpsd_rig(rig, path, readonly):
    return rig.spawn_gpsd(path, readonly)


def read_json(pipe, limit_s, pred, what, last_of=None):
    """The first gpsd JSON object within limit_s that satisfies pred; on a
    timeout the error shows the last object of class last_of."""
    deadline = time.monotonic() + limit_s
    fd = pipe.stdout.fileno()
    last = None
    while time.monotonic() < deadline:
        r, _, _ = select.select([fd], [], [], deadline - time.monotonic())
        if not r:
            break
        line = pipe.stdout.readline()
        if not line:
            break
        try:
            m = json.loads(line)
        except ValueError:
            continue
        if pred(m):
            return m
        if last_of and m.get("class") == last_of:
            last = m
    raise AssertionError(f"no {what} within {limit_s} s" + (f"; last {last_of}: {last}" if last_of else ""))


def case_gpsd_ubx(rig):
    path, out = pty_output(rig)  # factory M8 port: NMEA out, UBX+NMEA in
    rig.start_daemon(out)
    pipe = gpsd_rig(rig, path, readonly=False)
    dev = read_json(pipe, 20, lambda m: m.get("class") == "DEVICE" and m.get("driver") == "u-blox",
                    "DEVICE with driver u-blox")
    assert "00080000" in dev.get("subtype", ""), dev
    tpv = read_json(pipe, 15, lambda m: m.get("class") == "TPV" and m.get("mode") == 3, "TPV mode 3")
    log = rig.daemon_log_text()
    replies = re.search(r"output gps0: .*", log)
    print(f"  gpsd_ubx: driver {dev['driver']} ({dev['subtype']}), native {dev.get('native')}; TPV mode 3 "
          f"at {tpv['lat']:.6f} {tpv['lon']:.6f}")
    # gpsd switched the port to binary: UBX NAV-PVT carries the fix now.
    dev2 = read_json(pipe, 10, lambda m: m.get("class") == "DEVICE" and m.get("native") == 1, "native-mode DEVICE") \
        if dev.get("native") != 1 else dev
    assert dev2.get("native") == 1
    del replies


def socat_dump_frames(dump_path, direction):
    """UBX frames and NMEA lines of one direction ('>' left to right, '<'
    back) of a `socat -x` hex dump."""
    data, take = b"", False
    for line in open(dump_path, errors="replace"):
        if line.startswith((">", "<")):
            take = line.startswith(direction)
        elif take and line.startswith(" "):
            data += bytes.fromhex(line.strip())
    return split_stream(data)[0]


def case_gpsd_m9(rig):
    gpsd_gen9(rig, M9, "32.01", "gpsd_m9")


def case_gpsd_f9p(rig):
    """gpsd identifies the emulated ZED-F9P (MON-VER MOD=ZED-F9P, PROTVER
    27.31) over the pty and reports mode 3, as gpsd_m9 does for the M9N."""
    dev = gpsd_gen9(rig, 'generation = "f9p"', "27.31", "gpsd_f9p")
    assert "ZED-F9P" in json.dumps(dev), dev


def gpsd_gen9(rig, receiver_toml, protver, label):
    """gpsd 3.22 (read-write) against an emulated M9, through socat so that
    what gpsd writes is on record: its u-blox driver identifies the M9N
    (MON-VER hwVersion 00190000, protocol 32.01) and reports mode 3. Every
    UBX command gpsd sends is answered; a CFG-VALSET/VALGET it sends (protocol
    >= 27) gets an ACK, not the M8's NAK."""
    path, out = pty_output(rig)  # factory port: NMEA out, UBX+NMEA in
    rig.start_daemon(out, receiver_toml=receiver_toml)
    host = os.path.join(rig.tmp, "gpsd-side")
    dump = os.path.join(rig.tmp, "socat-dump.txt")
    with open(dump, "w") as f:
        rig.spawn(["socat", "-x", f"PTY,link={host},rawer,echo=0", f"OPEN:{path},rawer,echo=0"], stdout=f, stderr=f)
    deadline = time.monotonic() + 5
    while not os.path.exists(host):
        assert time.monotonic() < deadline, "socat did not create its pty"
        time.sleep(0.05)
    pipe = gpsd_rig(rig, host, readonly=False)
    dev = read_json(pipe, 20, lambda m: m.get("class") == "DEVICE" and m.get("driver") == "u-blox",
                    "DEVICE with driver u-blox")
    if "00190000" not in dev.get("subtype", ""):
        dev = read_json(pipe, 10, lambda m: m.get("class") == "DEVICE" and "00190000" in m.get("subtype", ""),
                        "DEVICE subtype with hwVersion 00190000")
    assert f"PROTVER {protver}" in dev.get("subtype1", "") or protver in json.dumps(dev), dev
    tpv = read_json(pipe, 15, lambda m: m.get("class") == "TPV" and m.get("mode") == 3, "TPV mode 3")
    if dev.get("native") != 1:  # gpsd switches the port to UBX (CFG-PRT) once it knows the chip
        read_json(pipe, 10, lambda m: m.get("class") == "DEVICE" and m.get("native") == 1, "native-mode DEVICE")
    time.sleep(1.0)  # let socat flush the last exchange
    sent = [m for k, m in socat_dump_frames(dump, ">") if k == "ubx"]
    back = [m for k, m in socat_dump_frames(dump, "<") if k == "ubx"]
    ids = sorted({(m[2], m[3]) for m in sent})
    val = [m for m in sent if m[2] == 0x06 and m[3] in (0x8A, 0x8B, 0x8C)]
    naks = {(m[6], m[7]) for m in back if m[2:4] == b"\x05\x00"}
    acks = {(m[6], m[7]) for m in back if m[2:4] == b"\x05\x01"}
    for m in val:
        assert (0x06, m[3]) not in naks, f"gpsd's CFG-VAL* {m.hex()} was NAKed"
        assert (0x06, m[3]) in acks, f"gpsd's CFG-VAL* {m.hex()} got no ACK"
    # The only CFG command an M9 refuses is CFG-MSG for NAV-SVINFO, a message
    # protocol 27+ does not have (gpsd 3.22 asks for it on every chip).
    svinfo_msgs = sum(1 for m in sent if m[2:4] == b"\x06\x01" and m[6:8] == b"\x01\x30")
    cfg_msg_naks = sum(1 for m in back if m[2:4] == b"\x05\x00" and m[6:8] == b"\x06\x01")
    assert cfg_msg_naks == svinfo_msgs, f"{cfg_msg_naks} CFG-MSG NAKed, {svinfo_msgs} of them for NAV-SVINFO"
    cfg_naked = sorted({c for c in naks if c[0] == 0x06 and c != (0x06, 0x01) and c in {(m[2], m[3]) for m in sent}})
    assert not cfg_naked, f"CFG commands of gpsd NAKed: {cfg_naked}"
    names = ", ".join(f"{c:02X}-{i:02X}" for c, i in ids)
    vals = f"{len(val)} CFG-VAL*, all ACKed" if val else f"no CFG-VAL* (it configures protocol {protver} by CFG-PRT/CFG-MSG)"
    print(f"  {label}: driver {dev['driver']} ({dev['subtype']}), native mode; TPV mode 3 at {tpv['lat']:.6f} "
          f"{tpv['lon']:.6f}; gpsd sent UBX {names}: {vals}; {svinfo_msgs} CFG-MSG NAV-SVINFO NAKed (no such "
          f"message from protocol 27), nothing else")
    return dev


def case_gpsd_nmea(rig):
    path, out = pty_output(rig, extra='protocols_in = ["nmea"]\nprotocols_out = ["nmea"]')
    rig.start_daemon(out)
    pipe = gpsd_rig(rig, path, readonly=False)
    dev = read_json(pipe, 20, lambda m: m.get("class") == "DEVICE" and "driver" in m, "DEVICE with a driver")
    assert dev["driver"] == "NMEA0183", dev
    tpv = read_json(pipe, 15, lambda m: m.get("class") == "TPV" and m.get("mode") == 3, "TPV mode 3")
    # Probes (UBX polls gpsd writes) were ignored: the port takes NMEA only.
    time.sleep(2)
    print(f"  gpsd_nmea: driver {dev['driver']}; TPV mode 3 at {tpv['lat']:.6f} {tpv['lon']:.6f}")


def case_gpsdecode(rig):
    ubx_log = os.path.join(rig.tmp, "out.ubx")
    nmea_log = os.path.join(rig.tmp, "out.nmea")
    outs = (f'[[output]]\nname = "ubxlog"\ntype = "file"\npath = "{ubx_log}"\nprotocols_out = ["ubx"]\n'
            'ubx_messages = ["NAV-PVT", "NAV-DOP", "NAV-SAT", "NAV-TIMEUTC", "NAV-EOE"]\n'
            f'[[output]]\nname = "nmealog"\ntype = "file"\npath = "{nmea_log}"\nprotocols_out = ["nmea"]\n'
            'sentences = ["RMC", "GGA"]\n')
    rig.start_daemon(outs, rate_hz=2.0, verbose=True)
    time.sleep(6)
    rig.stop(rig.daemon)
    dec = subprocess.run(["gpsdecode", "-j"], stdin=open(ubx_log, "rb"), capture_output=True, text=True, timeout=30)
    tpvs = [json.loads(l) for l in dec.stdout.splitlines() if '"class":"TPV"' in l]
    fixes = {}
    # The daemon's own record of each fix (-v): tow, lat, lon, h.
    for m in re.finditer(r"epoch tow ([\d.]+): fix (\d) nsat (\d+) lat (-?[\d.]+) lon (-?[\d.]+) h (-?[\d.]+)",
                         rig.daemon_log_text()):
        fixes[round(float(m.group(1)), 2)] = tuple(float(x) for x in m.groups()[1:])
    assert len(tpvs) >= 8, f"gpsdecode gave {len(tpvs)} TPVs: {dec.stdout[:500]} {dec.stderr[:500]}"
    matched = 0
    worst = 0.0
    for t in tpvs:
        if t.get("mode") != 3 or "lat" not in t:
            continue
        tow = None
        # gpsdecode time is UTC; match by lat/lon to the nearest logged epoch instead of leap arithmetic.
        best = min(fixes.values(), key=lambda f: abs(f[2] - t["lat"]) + abs(f[3] - t["lon"]))
        dlat = abs(best[2] - t["lat"]) * 111e3
        dlon = abs(best[3] - t["lon"]) * 73e3
        dh = abs(best[4] - t["altHAE"])
        worst = max(worst, dlat, dlon)
        assert dlat < 0.02 and dlon < 0.02 and dh < 0.1, f"UBX decode {t} vs fix {best}"
        del tow
        matched += 1
    assert matched >= 8, f"only {matched} mode-3 TPVs matched the daemon's fixes"
    # NMEA of the same epochs decodes to the same places (5 decimals of minutes ~ 2 cm).
    nd = subprocess.run(["gpsdecode", "-j"], stdin=open(nmea_log, "rb"), capture_output=True, text=True, timeout=30)
    ntpv = {json.loads(l)["time"]: json.loads(l) for l in nd.stdout.splitlines()
            if '"class":"TPV"' in l and '"mode":3' in l}
    common = [t for t in tpvs if t.get("time") in ntpv and "lat" in t]
    assert len(common) >= 5, f"{len(common)} epochs in both logs"
    for t in common:
        n = ntpv[t["time"]]
        assert abs(n["lat"] - t["lat"]) * 111e3 < 0.05 and abs(n["lon"] - t["lon"]) * 73e3 < 0.05, (t, n)
    sats = [json.loads(l) for l in dec.stdout.splitlines() if '"class":"SKY"' in l]
    assert sats and any(s.get("uSat", 0) >= 4 or len(s.get("satellites", [])) >= 4 for s in sats), "no SKY"
    print(f"  gpsdecode: {matched} UBX fixes equal the daemon's (worst {worst * 100:.1f} cm), "
          f"{len(common)} epochs agree with the NMEA log")


def case_nav5(rig):
    path, out = pty_output(rig, extra='ubx_messages = ["NAV-PVT"]\nprotocols_out = ["ubx"]')
    rig.start_daemon(out)
    fd = rig.open_tty(path)
    s = Stream(fd)
    fix = lambda k, m: k == "ubx" and m[2:4] == b"\x01\x07" and m[6 + 21] & 1
    gspeed = lambda m: struct.unpack_from("<i", m, 6 + 60)[0] / 1000.0

    def speeds(n):
        return [gspeed(s.wait_for(fix, 3.0, "NAV-PVT with gnssFixOK")[1]) for _ in range(n)]

    def set_dyn(model):
        nav5 = bytearray(poll_cfg(s, fd, 0x24))
        struct.pack_into("<HB", nav5, 0, 0x0001, model)
        set_cfg(s, fd, 0x24, bytes(nav5))
        assert poll_cfg(s, fd, 0x24)[2] == model
        s.msgs.clear()
        s.wait_for(fix, 3.0, "NAV-PVT after CFG-NAV5")  # the epoch under way when it changed

    before = speeds(3)
    assert all(3.0 < v < 7.0 for v in before), f"demo circle at 5 m/s, NAV-PVT gSpeed {before}"
    set_dyn(2)  # stationary
    still = speeds(3)
    assert still == [0.0, 0.0, 0.0], f"stationary model: gSpeed {still}, want 0"
    set_dyn(4)  # automotive
    again = speeds(3)
    assert all(3.0 < v < 7.0 for v in again), f"automotive model: gSpeed {again}"
    assert "CFG-NAV5 dynModel 2" in rig.daemon_log_text()
    print(f"  nav5: gSpeed {before[0]:.2f} m/s portable, {still[0]:.2f} stationary, {again[0]:.2f} automotive")


def case_cold_start(rig):
    path, out = pty_output(rig, extra='sentences = ["RMC", "GGA", "GSA"]')
    rig.start_daemon(out)
    pipe = gpsd_rig(rig, path, readonly=True)
    read_json(pipe, 20, lambda m: m.get("class") == "TPV" and m.get("mode") == 3, "TPV mode 3 after power-on")
    # The host writes to the receiver on the same pty; gpsd keeps reading it.
    fd = os.open(path, os.O_WRONLY | os.O_NOCTTY)
    rig.fds.append(fd)
    t_rst = time.monotonic()
    send(fd, frame(0x06, 0x04, bytes([0xFF, 0xFF, 0x02, 0x00])))  # cold start, GNSS only
    read_json(pipe, 5, lambda m: m.get("class") == "TPV" and m.get("mode", 0) <= 1, "TPV mode 1 after CFG-RST")
    t_lost = time.monotonic() - t_rst
    read_json(pipe, 60, lambda m: m.get("class") == "TPV" and m.get("mode") == 3, "TPV mode 3 after the cold start")
    t_back = time.monotonic() - t_rst
    # M8 data sheet, GPS: cold start 29 s; ours: 17-31 s of ephemeris download
    # after acquisition and bit synchronisation (docs/validation.md, TTFF).
    assert 15.0 <= t_back <= 45.0, f"fix back {t_back:.1f} s after the cold start (M8: 29 s)"
    assert "CFG-RST cold start (navBbrMask 0xFFFF)" in rig.daemon_log_text(), "no cold start logged"
    print(f"  cold_start: gpsd mode 1 {t_lost:.1f} s after CFG-RST cold, mode 3 again after {t_back:.1f} s "
          f"(M8 data sheet: 29 s)")


def case_power_on_cold(rig):
    # [receiver.acquisition] start = "cold": the daemon powers on knowing
    # nothing (no fix for about the cold TTFF); then a host's CFG-RST hot start
    # keeps everything and the fix is back after about 1 s.
    path, out = pty_output(rig, extra='sentences = ["RMC", "GGA", "GSA"]')
    t_on = time.monotonic()
    rig.start_daemon(out, extra_toml='[receiver.acquisition]\nstart = "cold"\n')
    pipe = gpsd_rig(rig, path, readonly=True)
    read_json(pipe, 20, lambda m: m.get("class") == "TPV" and m.get("mode", 0) <= 1, "TPV mode 1 after power-on")
    read_json(pipe, 60, lambda m: m.get("class") == "TPV" and m.get("mode") == 3, "TPV mode 3 after a cold power-on")
    t_fix = time.monotonic() - t_on
    assert 15.0 <= t_fix <= 45.0, f"first fix {t_fix:.1f} s after a cold power-on (M8: 29 s)"
    assert "receiver: cold start at power-on" in rig.daemon_log_text(), "no cold power-on logged"
    fd = os.open(path, os.O_WRONLY | os.O_NOCTTY)
    rig.fds.append(fd)
    t_rst = time.monotonic()
    send(fd, frame(0x06, 0x04, bytes([0x00, 0x00, 0x02, 0x00])))  # hot start, GNSS only
    read_json(pipe, 5, lambda m: m.get("class") == "TPV" and m.get("mode", 0) <= 1, "TPV mode 1 after CFG-RST hot")
    read_json(pipe, 10, lambda m: m.get("class") == "TPV" and m.get("mode") == 3, "TPV mode 3 after the hot start")
    t_back = time.monotonic() - t_rst
    assert t_back <= 5.0, f"fix back {t_back:.1f} s after a hot start (M8: 1 s)"
    print(f"  power_on_cold: first fix {t_fix:.1f} s after a cold power-on (M8 data sheet: 29 s); "
          f"back {t_back:.1f} s after CFG-RST hot (1 s)")


def set_speed(fd, baud):
    """The host side's line rate (termios), as PX4's setBaudrate does."""
    attrs = termios.tcgetattr(fd)
    speed = getattr(termios, f"B{baud}")
    attrs[4] = attrs[5] = speed
    termios.tcsetattr(fd, termios.TCSANOW, attrs)


def case_serial(rig):
    a = os.path.join(rig.tmp, "ttyA")
    b = os.path.join(rig.tmp, "ttyB")
    socat_argv = ["socat", "-d", "-d", f"pty,raw,echo=0,link={a}", f"pty,raw,echo=0,link={b}"]
    socat_log = open(os.path.join(rig.tmp, "socat.log"), "w")
    socat = rig.spawn(socat_argv, stdout=socat_log, stderr=subprocess.STDOUT)
    deadline = time.monotonic() + 5
    while not (os.path.exists(a) and os.path.exists(b)):
        assert time.monotonic() < deadline, "socat did not create the pty pair"
        time.sleep(0.05)
    rig.start_daemon(f'[[output]]\nname = "uart"\ntype = "serial"\ndevice = "{a}"\nbaud = 9600\n', rate_hz=2.0)
    fd = rig.open_tty(b)
    s = Stream(fd)
    s.wait_for(lambda k, m: k == "nmea" and m.startswith(b"$GPGGA"), 5, "GGA on the serial port")
    assert stty_speed(a) == 9600, stty_speed(a)
    # $PUBX,41 (ArduPilot's probe): UART1, in UBX+NMEA+RTCM, out UBX+NMEA, 38400.
    send(fd, nmea("PUBX,41,1,0007,0003,38400,0"))
    deadline = time.monotonic() + 3
    while stty_speed(a) != 38400:
        assert time.monotonic() < deadline, f"termios still {stty_speed(a)} after $PUBX,41"
        time.sleep(0.05)
    s.wait_for(lambda k, m: k == "nmea" and m.startswith(b"$GPGGA"), 5, "GGA after the switch")
    # CFG-PRT: ACK first (at the old rate), then the line switches to 115200.
    prt = struct.pack("<BBHIIHHHH", 1, 0, 0, 0x08D0, 115200, 0x0003, 0x0003, 0, 0)
    send(fd, frame(0x06, 0x00, prt))
    _, m = s.wait_for(is_ack_for(0x06, 0x00), 1.0, "ACK of CFG-PRT")
    assert m == ack(0x06, 0x00)
    deadline = time.monotonic() + 3
    while stty_speed(a) != 115200:
        assert time.monotonic() < deadline, f"termios still {stty_speed(a)} after CFG-PRT"
        time.sleep(0.05)
    prt_back = poll_cfg(s, fd, 0x00, bytes([1]))
    assert struct.unpack_from("<I", prt_back, 8)[0] == 115200
    # PX4's way (PX4-GPSDrivers ubx.cpp configure): CFG-PRT for UART1 at the
    # current baud (needs the ACK), then CFG-PRT with the target baud (ACK not
    # awaited), the host switches its own side, and CFG-PRT again at the
    # target baud, which must be ACKed at that baud.
    px4_prt = lambda baud: frame(0x06, 0x00, struct.pack("<BBHIIHHHH", 1, 0, 0, 0x08D0, baud, 0x0003, 0x0003, 0, 0))
    send(fd, px4_prt(115200))
    assert s.wait_for(is_ack_for(0x06, 0x00), 1.0, "ACK of CFG-PRT at the current baud")[1] == ack(0x06, 0x00)
    send(fd, px4_prt(230400))
    set_speed(fd, 230400)
    deadline = time.monotonic() + 3
    while stty_speed(a) != 230400:
        assert time.monotonic() < deadline, f"termios still {stty_speed(a)} after PX4's CFG-PRT 230400"
        time.sleep(0.02)
    s.msgs.clear()
    t0 = time.monotonic()
    send(fd, px4_prt(230400))
    t, m = s.wait_for(is_ack_for(0x06, 0x00), 1.0, "ACK of CFG-PRT at the target baud")
    assert m == ack(0x06, 0x00) and t - t0 < 0.25, (m.hex(), t - t0)
    assert stty_speed(a) == 230400 and stty_speed(b) == 230400
    # Unplug: socat goes away with both ptys; the daemon retries and reopens.
    rig.stop(socat)
    rig.fds.remove(fd)
    os.close(fd)
    time.sleep(1.5)
    assert rig.daemon.poll() is None, "gnssemud died when the device vanished"
    socat = rig.spawn(socat_argv, stdout=socat_log, stderr=subprocess.STDOUT)
    deadline = time.monotonic() + 5
    while not (os.path.exists(a) and os.path.exists(b)):
        assert time.monotonic() < deadline, "socat did not come back"
        time.sleep(0.05)
    fd = rig.open_tty(b)
    s = Stream(fd)
    s.wait_for(lambda k, m: k == "nmea" and m.startswith(b"$GPGGA"), 10, "GGA after the device came back")
    log = rig.daemon_log_text()
    assert "open again" in log, "no reopen logged"
    warnings = log.count("retrying every")
    assert 1 <= warnings <= 2, f"{warnings} failure warnings for one unplug: want 1 (rate limited)"
    print(f"  serial: 9600 -> 38400 ($PUBX,41) -> 115200 (CFG-PRT) -> 230400 (PX4's CFG-PRT twice, host switched) "
          f"seen in termios; reopened after unplug "
          f"({warnings} warning(s))")


def case_net(rig):
    uport = free_port(socket.SOCK_DGRAM)
    usock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    usock.bind(("127.0.0.1", uport))
    usock.settimeout(5)
    outs = ('[[output]]\nname = "net"\ntype = "tcp"\nport = 0\nubx_messages = ["NAV-PVT"]\n'
            f'[[output]]\nname = "udp"\ntype = "udp"\naddress = "127.0.0.1"\nport = {uport}\n'
            'ubx_messages = ["NAV-PVT", "NAV-SAT"]\n')
    rig.start_daemon(outs, rate_hz=2.0)
    m = re.search(r"on tcp 127\.0\.0\.1:(\d+)", "\n".join(rig.banner))
    assert m, rig.banner
    c1 = socket.create_connection(("127.0.0.1", int(m.group(1))), timeout=5)
    c2 = socket.create_connection(("127.0.0.1", int(m.group(1))), timeout=5)
    s1, s2 = Stream(c1.fileno()), Stream(c2.fileno())
    for st in (s1, s2):
        st.frame_of(0x01, 0x07, 5)
        st.wait_for(lambda k, mm: k == "nmea" and mm.startswith(b"$GPGGA"), 5, "GGA over tcp")
    c1.sendall(frame(0x0A, 0x04))
    s1.frame_of(0x0A, 0x04, 2)
    s2.msgs.clear()
    end = time.monotonic() + 1.5
    while time.monotonic() < end:
        s2.pump(end - time.monotonic())
    assert not any(k == "ubx" and mm[2:4] == b"\x0a\x04" for _, k, mm in s2.msgs), "MON-VER reply went to client 2"
    got = b""
    kinds = set()
    end = time.monotonic() + 3
    while time.monotonic() < end:
        try:
            d = usock.recv(65536)
        except socket.timeout:
            break
        assert len(d) <= 1400, f"datagram of {len(d)} bytes"
        msgs, rest = split_stream(d)
        assert rest == b"", f"datagram ends inside a message: {rest[:40]!r}"
        kinds |= {(k, mm[2:4] if k == "ubx" else mm[3:6]) for k, mm in msgs}
        got += d
    assert ("ubx", b"\x01\x07") in kinds and ("ubx", b"\x01\x35") in kinds and ("nmea", b"GGA") in kinds, kinds
    c1.close()
    c2.close()
    usock.close()
    print(f"  net: two tcp clients get the stream, MON-VER answered to the asking client only; "
          f"udp datagrams of whole messages ({len(got)} bytes in 3 s)")


def case_budget(rig):
    path, out = pty_output(rig, extra='baud = 9600\nubx_messages = ["NAV-PVT", "NAV-SAT", "NAV-SVINFO", "NAV-SOL"]\n'
                                      'sentences = ["RMC", "VTG", "GGA", "GSA", "GSV", "GLL", "GST", "ZDA"]')
    rig.start_daemon(out, rate_hz=5.0)
    fd = rig.open_tty(path)
    s = Stream(fd)
    t0 = time.monotonic()
    total = 0
    end = t0 + 8
    while time.monotonic() < end:
        s.pump(end - time.monotonic())
    # Everything after the first second (the 4 KiB buffer filling) is bounded by the line.
    first = s.msgs[0][0] if s.msgs else t0
    late = [m for t, _, m in s.msgs if t >= first + 2.0]
    span = max(t for t, _, _ in s.msgs) - (first + 2.0)
    total = sum(len(m) for m in late)
    rate = total / span
    assert rate <= 960 * 1.15, f"{rate:.0f} B/s over a 9600 baud line (max 960)"
    assert rate >= 960 * 0.6, f"only {rate:.0f} B/s: the line is not used"
    log = rig.daemon_log_text()
    assert log.count("the configured messages need") == 1, "drop warning missing or repeated"
    w = re.search(r"need (\d+) bytes per epoch at 5 Hz but 9600 baud carries (\d+)", log)
    assert w and int(w.group(1)) > int(w.group(2)) == 192, w and w.group(0)
    print(f"  budget: {w.group(1)} B/epoch wanted, 192 B/epoch carried; measured {rate:.0f} B/s (line 960 B/s); "
          f"warned once")


def case_wallclock(rig):
    # A u-blox's epochs sit on whole multiples of the measurement period in
    # GPS time, whatever instant the daemon started at.
    path, out = pty_output(rig, extra='protocols_out = ["ubx"]\nubx_messages = ["NAV-PVT"]')
    rig.start_daemon(out, extra_toml="[time]\nuse_wall_clock_date = true\n")
    fd = rig.open_tty(path)
    s = Stream(fd)

    def itows(seconds):
        s.msgs.clear()
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            s.pump(end - time.monotonic())
        return [struct.unpack_from("<I", m, 6)[0] for _, k, m in s.msgs if k == "ubx" and m[2:4] == b"\x01\x07"]

    one_hz = itows(2.5)
    assert len(one_hz) >= 2, f"{len(one_hz)} NAV-PVT in 2.5 s at 1 Hz"
    assert all(t % 1000 == 0 for t in one_hz), f"iTOW not on whole seconds: {one_hz}"
    # Time of output: the first byte of an epoch leaves [time] output_delay_s
    # (default 0.1 s, as a u-blox M8) after the measurement epoch it reports.
    lags = []
    wall_minus_mono = time.time() - time.monotonic()
    for _ in range(3):
        t, m = s.wait_for(lambda k, m: k == "ubx" and m[2:4] == b"\x01\x07", 2.0, "NAV-PVT")
        year, month, day, hour, minute, sec = struct.unpack_from("<HBBBBB", m, 6 + 4)
        nano = struct.unpack_from("<i", m, 6 + 16)[0]
        epoch = datetime.datetime(year, month, day, hour, minute, sec, tzinfo=datetime.timezone.utc).timestamp()
        lags.append(t + wall_minus_mono - (epoch + nano * 1e-9))
    assert all(0.095 <= lag <= 0.2 for lag in lags), f"first byte {lags} s after the epoch, want ~0.1 s"
    set_cfg(s, fd, 0x08, struct.pack("<HHH", 200, 1, 0))
    five_hz = itows(2.0)[1:]
    assert len(five_hz) >= 7, f"{len(five_hz)} NAV-PVT in 2 s at 5 Hz"
    assert all(t % 200 == 0 for t in five_hz), f"iTOW not on 200 ms boundaries: {five_hz}"
    print(f"  wallclock: iTOW {one_hz[-1]} ... at 1 Hz, {five_hz[:3]} ... at 5 Hz; output "
          f"{min(lags) * 1e3:.0f}..{max(lags) * 1e3:.0f} ms after the epoch")


def mon_hw_poll(rig, extra_toml):
    """Start a daemon with extra_toml, wait for an epoch, poll MON-HW; stop it.
    Returns (noisePerMS, agcCnt, jamInd)."""
    path, out = pty_output(rig)
    rig.start_daemon(out, extra_toml=extra_toml)
    fd = rig.open_tty(path)
    s = Stream(fd)
    s.wait_for(lambda k, m: k == "nmea" and m.startswith(b"$GPGGA"), 5, "GGA (an epoch)")
    send(fd, frame(0x0A, 0x09))
    m = s.frame_of(0x0A, 0x09)
    assert len(m) == 8 + 60, f"MON-HW of {len(m)} bytes"
    noise, agc = struct.unpack_from("<HH", m, 6 + 16)
    jam = m[6 + 45]
    rig.fds.remove(fd)
    os.close(fd)
    rig.stop(rig.daemon)
    return noise, agc, jam


def case_jamming(rig):
    # MON-HW follows the world: the receiver's environment noise rise
    # ([signal] noise_rise_db, or environment = "jamming") drives noisePerMS,
    # agcCnt and jamInd (docs/ubx.md MON-HW), through Fix::noise_rise_db.
    quiet = mon_hw_poll(rig, "[signal]\nnoise_rise_db = 1.0\n")
    jammed = mon_hw_poll(rig, "[signal]\nnoise_rise_db = 30.0\n")
    print(f"  jamming: quiet noisePerMS/agcCnt/jamInd {quiet}, 30 dB rise {jammed}")
    assert jammed[0] > quiet[0], f"noisePerMS {jammed[0]} not above quiet {quiet[0]}"
    assert jammed[1] < quiet[1], f"agcCnt {jammed[1]} not below quiet {quiet[1]}"
    assert jammed[2] > quiet[2], f"jamInd {jammed[2]} not above quiet {quiet[2]}"
    # With the documented mapping (82 + 3 rise, 5000 - 110 rise, 7 + 5 rise)
    # a 30 dB rise reads (172, 1700, 157); not asserted exactly, so the
    # receiver may add its own terms to the rise.



# NAV-SAT (0x01 0x35): 8-byte header, 12 bytes per satellite: gnssId, svId, cno, elev, azim, prRes, flags (bit 3 svUsed).
def nav_sat_systems(m):
    n = m[6 + 5]
    sats = [(m[6 + 8 + 12 * i], m[6 + 9 + 12 * i], struct.unpack_from("<I", m, 6 + 16 + 12 * i)[0]) for i in range(n)]
    return {g for g, _, _ in sats}, {g for g, _, f in sats if f & 0x08}


GNSS_NAMES = {0: "GPS", 1: "SBAS", 2: "Galileo", 3: "BeiDou", 5: "QZSS", 6: "GLONASS"}


def names(ids):
    return "+".join(GNSS_NAMES.get(g, str(g)) for g in sorted(ids))


def case_px4_m9_gnss(rig):
    """PX4 with GPS_1_GNSS = GPS + Galileo (mask 5) on an M9N in a four-system
    sky: before, NAV-SAT lists GPS, GLONASS, Galileo and BeiDou; PX4's
    CFG-SIGNAL VALSETs (configureDevice: the five ENA keys, QZSS with GPS, then
    SBAS) are ACKed, the chip restarts tracking, and from then NAV-SAT lists
    GPS, Galileo and QZSS only, with a fix on them."""
    rig.nav = rig.args.nav_mgnss
    path, out = pty_output(rig)
    rig.start_daemon(out, receiver_toml=M9)
    fd = rig.open_tty(path)
    s = Stream(fd)
    px4_startup_m9(s, fd, path)
    s.wait_for(pvt_fix_ok, 6.0, "the first gnssFixOK")
    before = set()
    for _, k, m in s.collect(2.5):
        if k == "ubx" and m[2:4] == b"\x01\x35":
            before |= nav_sat_systems(m)[0]
    assert {0, 2, 3, 6} <= before, f"NAV-SAT before the restriction lists {names(before)}"
    t_acks = []
    for pairs in ([(K_SIGNAL_GPS_ENA, 1), (K_SIGNAL_QZSS_ENA, 1), (K_SIGNAL_GAL_ENA, 1), (K_SIGNAL_BDS_ENA, 0),
                   (K_SIGNAL_GLO_ENA, 0)], [(K_SIGNAL_SBAS_ENA, 0)]):
        send(fd, frame(0x06, 0x8A, valset(pairs)))
        t, m = s.wait_for(is_ack_for(0x06, 0x8A), 1.0, "reply to PX4's CFG-SIGNAL VALSET")
        assert m == ack(0x06, 0x8A), f"CFG-SIGNAL VALSET: got {m.hex()}"
        t_acks.append(t)
    t_fix, _ = s.wait_for(pvt_fix_ok, 8.0, "gnssFixOK after the GNSS restart")
    # The chip restarts its GNSS engine on the change (M8/M9 interface descriptions, CFG-GNSS / CFG-SIGNAL):
    # the fix drops for a moment.
    lost = pvt_lost_after(s, t_acks[0], t_fix)
    assert lost > 0, "no NAV-PVT without gnssFixOK after the GNSS change: the chip did not restart"
    after, used = set(), set()
    pvts = 0
    for _, k, m in s.collect(2.5):
        if k == "ubx" and m[2:4] == b"\x01\x35":
            seen, u = nav_sat_systems(m)
            after |= seen
            used |= u
        pvts += k == "ubx" and m[2:4] == b"\x01\x07" and m[6 + 21] & 1
    assert after and after <= {0, 2, 5}, f"NAV-SAT after GPS_1_GNSS = GPS + Galileo lists {names(after)}"
    assert {0, 2} <= used, f"satellites used after the restriction: {names(used)}"
    assert pvts > 0, "no NAV-PVT with gnssFixOK after the restriction"
    print(f"  px4_m9_gnss: NAV-SAT {names(before)} -> {names(after)} (used {names(used)}) after PX4's "
          f"CFG-SIGNAL VALSETs (ACKed); the restart: {lost} NAV-PVT without a fix, gnssFixOK again "
          f"{t_fix - t_acks[-1]:.1f} s after the last ACK; {pvts} NAV-PVT with gnssFixOK in 2.5 s")


def case_px4_m8_gnss(rig):
    """PX4 on an M8 in a four-system sky (its legacy start-up, then the CFG-GNSS
    of GPS_1_GNSS): the factory M8 tracks GPS, GLONASS (+ QZSS, SBAS); GPS +
    Galileo + BeiDou (mask 13) is ACKed, the chip restarts (a NAV-PVT without
    fix) and NAV-SVINFO then holds GPS, Galileo and BeiDou only, with a fix;
    every system at once (mask 31, four major GNSS) is NAKed, as an M8 runs
    at most three (multi-gnss.md), and the set stays."""
    rig.nav = rig.args.nav_mgnss
    path, out = pty_output(rig)
    rig.start_daemon(out)
    fd = rig.open_tty(path)
    s = Stream(fd)
    px4_startup(s, fd)
    s.wait_for(pvt_fix_ok, 6.0, "the first gnssFixOK")
    before = svinfo_systems(s.wait_for(is_ubx(0x01, 0x30), 3.0, "NAV-SVINFO (PX4 sets rate 5)")[1])[0]
    assert 6 in before and not {2, 3} & before, f"factory M8 NAV-SVINFO lists {names(before)}"
    lost = gnss_change_restarts(s, fd, px4_cfg_gnss(1 | 4 | 8), "M8")
    after, used, dt = systems_used_by_poll(s, fd, 0x30, svinfo_systems, {0, 2, 3, 5}, {0, 2, 3}, "NAV-SVINFO")
    send(fd, frame(0x06, 0x3E, px4_cfg_gnss(31)))
    m = s.wait_for(is_ack_for(0x06, 0x3E), 1.0, "reply to CFG-GNSS with four major systems")[1]
    assert m == ack(0x06, 0x3E, False), f"CFG-GNSS with GPS, Galileo, BeiDou and GLONASS: want NAK, got {m.hex()}"
    still = svinfo_systems(s.wait_for(is_ubx(0x01, 0x30), 3.0, "NAV-SVINFO after the NAK")[1])[0]
    assert still <= {0, 2, 3, 5}, f"after the NAK NAV-SVINFO lists {names(still)}"
    print(f"  px4_m8_gnss: NAV-SVINFO {names(before)} -> {names(after)} after PX4's CFG-GNSS for mask 13 (ACKed; "
          f"the restart: {lost} NAV-PVT without a fix); all used {dt:.0f} s after it; mask 31 "
          f"NAKed, set kept")


def gnss_change_restarts(s, fd, payload, chip):
    """CFG-GNSS payload set (ACKed); the chip restarts its GNSS engine on the
    change: a NAV-PVT without gnssFixOK, then the fix again. The number of
    NAV-PVT without fix."""
    t_set = time.monotonic()
    set_cfg(s, fd, 0x3E, payload)
    t_fix, _ = s.wait_for(pvt_fix_ok, 8.0, "gnssFixOK after the GNSS restart")
    lost = pvt_lost_after(s, t_set, t_fix)
    assert lost > 0, f"no NAV-PVT without gnssFixOK after CFG-GNSS: the {chip} did not restart its GNSS engine"
    return lost


def systems_used_by_poll(s, fd, mid, decode, allowed, wanted, what):
    """Poll NAV-<mid> every second until the wanted systems are used (the
    acquisition model decides when a newly enabled one is), at most 60 s;
    every poll lists only allowed systems. (listed, used, seconds)."""
    t0 = time.monotonic()
    while True:
        time.sleep(1.0)
        send(fd, frame(0x01, mid))
        listed, used = decode(s.wait_for(is_ubx(0x01, mid), 2.0, f"{what} poll")[1])
        assert listed <= allowed, f"{what} after the change lists {names(listed)}"
        if wanted <= used or time.monotonic() - t0 > 60:
            break
    assert wanted <= used, f"satellites used {time.monotonic() - t0:.0f} s after the change: {names(used)}"
    return listed, used, time.monotonic() - t0


def svinfo_systems(m):
    """Systems of a NAV-SVINFO's channels by the M8's svid ranges (docs/ubx.md)."""
    def system(svid):
        if 1 <= svid <= 32: return 0
        if 33 <= svid <= 64 or 159 <= svid <= 163: return 3
        if 65 <= svid <= 96: return 6
        if 120 <= svid <= 158: return 1
        if 193 <= svid <= 202: return 5
        if 211 <= svid <= 246: return 2
        return -1
    n = m[6 + 4]
    chans = [(m[6 + 8 + 12 * i + 1], m[6 + 8 + 12 * i + 2]) for i in range(n)]
    return {system(sv) for sv, _ in chans}, {system(sv) for sv, f in chans if f & 1}


def case_ardupilot_gnss(rig):
    """ArduPilot with GPS_GNSS_MODE = 5 (GPS + Galileo) on the M8 in a
    four-system sky: after its start-up it polls CFG-GNSS and sends it back
    with its channel split (AP_GPS_UBLOX.cpp MSG_CFG_GNSS); ACKed, the chip
    restarts tracking, and NAV-SVINFO then lists GPS and Galileo only (the
    factory GLONASS gone), with a fix."""
    rig.nav = rig.args.nav_mgnss
    path, out = pty_output(rig)
    rig.start_daemon(out)
    fd = rig.open_tty(path)
    s = Stream(fd)
    _, sv = ardupilot_startup(s, fd, path, fix_limit_s=6.0)
    before = svinfo_systems(sv)[0]
    assert 6 in before and 2 not in before, f"factory M8 NAV-SVINFO lists {names(before)}"
    gnss = poll_cfg(s, fd, 0x3E, b"")
    lost = gnss_change_restarts(s, fd, ardupilot_cfg_gnss(gnss, 5), "M8")
    after, used, dt = systems_used_by_poll(s, fd, 0x30, svinfo_systems, {0, 2}, {0, 2}, "NAV-SVINFO")
    print(f"  ardupilot_gnss: NAV-SVINFO {names(before)} -> {names(after)} after ArduPilot's CFG-GNSS for mode 5 "
          f"(ACKed); the restart: {lost} NAV-PVT without a fix; Galileo used {dt:.0f} s after it")


# gpsd's satellite numbers per gnssid (gpsd.h: GPS, SBAS PRN, Galileo, BeiDou, QZSS, GLONASS slot).
SVID_RANGE = {0: range(1, 33), 1: range(120, 159), 2: range(1, 37), 3: range(1, 64), 5: range(1, 11), 6: range(1, 33)}


def gpsd_m9_sky(rig, nmea_only):
    """SKY from gpsd on an M9N in a four-system sky: satellites of GPS,
    Galileo, BeiDou and GLONASS, used ones of each (from NMEA: of GPS and
    GLONASS, as gpsd 3.22 reads NMEA 4.10), each svid in its system's range."""
    rig.nav = rig.args.nav_mgnss
    path, out = pty_output(rig, extra='protocols_out = ["nmea"]' if nmea_only else "")
    # A fixed start: today's sky at some hours holds too few GLONASS
    # satellites above the mask for all four systems to be used.
    rig.start_daemon(out, receiver_toml=M9, extra_toml='[time]\nstart = "2024-01-10T09:00:00"\n')
    pipe = gpsd_rig(rig, path, readonly=nmea_only)
    read_json(pipe, 20, lambda m: m.get("class") == "TPV" and m.get("mode") == 3, "TPV mode 3")
    # gpsd 3.22's NMEA path marks as used only the GSA numbers it can match in
    # its own numbering: GPS and GLONASS; Galileo's and BeiDou's (NMEA 4.10,
    # per-talker numbers) stay unused. It does the same with the real NEO-M9N
    # log (gpsfake on ublox-neo-m9n-nmea.log: 184 SKYs, no Galileo or BeiDou
    # satellite used, BeiDou 33 as SBAS svid 120).
    want = {0, 6} if nmea_only else {0, 2, 3, 6}
    sky = read_json(pipe, 20, lambda m: m.get("class") == "SKY" and
                    want <= {x.get("gnssid") for x in m.get("satellites", []) if x.get("used")} and
                    {0, 2, 3, 6} <= {x.get("gnssid") for x in m.get("satellites", [])},
                    "SKY with GPS, Galileo, BeiDou and GLONASS satellites, " +
                    ("GPS and GLONASS" if nmea_only else "each system's") + " used", last_of="SKY")
    end = time.monotonic() + 8.0  # the first such SKY is early in acquisition: take one 8 s later
    while time.monotonic() < end:
        try:
            sky = read_json(pipe, end - time.monotonic(), lambda m: m.get("class") == "SKY", "SKY")
        except AssertionError:
            break
    sats = sky["satellites"]
    per = {g: (sum(1 for x in sats if x.get("gnssid") == g), sum(1 for x in sats if x.get("gnssid") == g and x.get("used")))
           for g in sorted({x.get("gnssid") for x in sats})}
    # gpsd 3.22 reads a GBGSV number 33-63 (BeiDou-3 MEOs) as an SBAS PRN (the NMEA 2.x range 33-64):
    # from NMEA only GPS, Galileo, BeiDou 1-32 and GLONASS are checked.
    checked = [x for x in sats if not nmea_only or x.get("gnssid") in (0, 2, 3, 6)]
    bad = [(x.get("gnssid"), x.get("svid")) for x in checked if x.get("svid") not in SVID_RANGE.get(x.get("gnssid"), ())]
    assert not bad, f"SKY satellites outside their system's svid range: {bad}"
    print(f"  gpsd_m9_sky{'_nmea' if nmea_only else ''}: SKY " +
          ", ".join(f"{GNSS_NAMES.get(g, g)} {n} seen/{u} used" for g, (n, u) in per.items()) + "; every svid in range")


def case_ardupilot_m9_gnss(rig):
    """ArduPilot with GPS_GNSS_MODE = 5 (GPS + Galileo) on a NEO-M9N in a
    four-system sky: ArduPilot configures an M9 with the legacy messages
    (docs/ubx.md "ArduPilot"), so it polls CFG-GNSS and sends it back with its
    channel split; ACKed, the chip restarts (a NAV-PVT without fix), and
    NAV-SAT then lists GPS and Galileo only (the factory GLONASS, BeiDou and
    QZSS gone), both used."""
    rig.nav = rig.args.nav_mgnss
    path, out = pty_output(rig)
    rig.start_daemon(out, receiver_toml=M9)
    fd = rig.open_tty(path)
    s = Stream(fd)
    ardupilot_startup_m9(s, fd, path, fix_limit_s=6.0)
    send(fd, frame(0x01, 0x35))
    before = nav_sat_systems(s.wait_for(is_ubx(0x01, 0x35), 2.0, "NAV-SAT poll")[1])[0]
    assert {0, 2, 3, 6} <= before, f"factory M9 NAV-SAT lists {names(before)}"
    gnss = poll_cfg(s, fd, 0x3E, b"")
    lost = gnss_change_restarts(s, fd, ardupilot_cfg_gnss(gnss, 5), "M9")
    after, used, dt = systems_used_by_poll(s, fd, 0x35, nav_sat_systems, {0, 2}, {0, 2}, "NAV-SAT")
    print(f"  ardupilot_m9_gnss: NAV-SAT {names(before)} -> {names(after)} after ArduPilot's CFG-GNSS for mode 5 "
          f"(ACKed; the restart: {lost} NAV-PVT without a fix); GPS and Galileo used {dt:.0f} s after it")


def case_gpsd_m9_sky(rig):
    """gpsd 3.22 (configuring the chip, UBX) on an M9N in a four-system sky:
    SKY lists gnssid 0 (GPS), 2 (Galileo), 3 (BeiDou) and 6 (GLONASS) with
    used satellites of each and svids in range, and TPV mode 3."""
    gpsd_m9_sky(rig, nmea_only=False)


def case_gpsd_m9_sky_nmea(rig):
    """The same from an NMEA-only port, gpsd read-only: gpsd takes the
    systems from the talkers of the M9's factory NMEA 4.10."""
    gpsd_m9_sky(rig, nmea_only=True)

def case_state_file(rig):
    """A configuration saved by a host survives a gnssemud restart, as a real
    module's flash/BBR does ([receiver] state_file, docs/ubx.md "Saved
    configuration"): the host sets 5 Hz (CFG-RATE), NAV-PVT on (CFG-MSG) and
    UBX-only output (CFG-PRT), saves (CFG-CFG); the daemon is stopped and
    started again, and with no host input the chip talks NAV-PVT at 5 Hz and
    no NMEA. CFG-CFG clear, one more restart: factory-fresh (NMEA at 1 Hz)."""
    state = os.path.join(rig.tmp, "chip.state")
    path, out = pty_output(rig)
    receiver = f'state_file = "{state}"'

    def start():
        rig.start_daemon(out, receiver_toml=receiver)
        fd = rig.open_tty(path)
        return fd, Stream(fd)

    def what_it_says(s):
        msgs = s.collect(3.0)
        itows = [struct.unpack_from("<I", m, 6)[0] for _, k, m in msgs if k == "ubx" and m[2:4] == b"\x01\x07"]
        steps = sorted({b - a for a, b in zip(itows, itows[1:])})
        return itows, steps, sum(1 for _, k, _m in msgs if k == "nmea")

    fd, s = start()
    s.wait_for(lambda k, m: k == "nmea", 5.0, "factory NMEA")
    set_cfg(s, fd, 0x08, struct.pack("<HHH", 200, 1, 1))               # CFG-RATE 200 ms
    set_cfg(s, fd, 0x01, bytes([0x01, 0x07, 1]))                       # CFG-MSG NAV-PVT every epoch
    set_cfg(s, fd, 0x00, struct.pack("<BBHIIHHHH", 1, 0, 0, 0x08C0, 9600, 0x03, 0x01, 0, 0))  # UART1: UBX out
    set_cfg(s, fd, 0x09, struct.pack("<IIIB", 0, 0x0000061F, 0, 0x17))  # CFG-CFG save
    # The daemon writes the file in the same handler that queued the ACK, a moment after the ACK may arrive.
    deadline = time.monotonic() + 1.0
    while not os.path.exists(state) and time.monotonic() < deadline:
        time.sleep(0.01)
    assert os.path.exists(state), "no state file 1 s after CFG-CFG save's ACK"
    rig.stop(rig.daemon)
    os.close(fd)
    rig.fds.remove(fd)

    fd, s = start()
    itows, steps, nmea_n = what_it_says(s)
    assert len(itows) >= 10 and steps == [200] and nmea_n == 0, \
        f"after the restart: {len(itows)} NAV-PVT in 3 s, iTOW steps {steps} ms, {nmea_n} NMEA sentences"
    print(f"  state_file: restarted with the saved configuration: {len(itows)} NAV-PVT in 3 s (iTOW step 200 ms), "
          f"no NMEA, no host input")
    set_cfg(s, fd, 0x09, struct.pack("<IIIB", 0x0000061F, 0, 0, 0x17))  # CFG-CFG clear
    rig.stop(rig.daemon)
    os.close(fd)
    rig.fds.remove(fd)

    fd, s = start()
    itows, steps, nmea_n = what_it_says(s)
    assert not itows and nmea_n >= 6, f"after CFG-CFG clear and a restart: {len(itows)} NAV-PVT, {nmea_n} NMEA"
    print(f"  state_file: after CFG-CFG clear and a restart factory-fresh: {nmea_n} NMEA sentences in 3 s, no NAV-PVT")


CASES = {"px4": case_px4, "ardupilot": case_ardupilot, "gpsd_ubx": case_gpsd_ubx, "gpsd_nmea": case_gpsd_nmea,
         "gpsdecode": case_gpsdecode, "serial": case_serial, "net": case_net, "budget": case_budget,
         "jamming": case_jamming, "wallclock": case_wallclock, "cold_start": case_cold_start,
         "power_on_cold": case_power_on_cold, "nav5": case_nav5, "px4_faults": case_px4_faults,
         "ardupilot_faults": case_ardupilot_faults, "px4_m9": case_px4_m9,
         "px4_f9p": case_px4_f9p, "px4_f9p_heading": case_px4_f9p_heading,
         "gpsd_f9p": case_gpsd_f9p, "gpsd_m9": case_gpsd_m9,
         "ardupilot_m9": case_ardupilot_m9, "ardupilot_f9p": case_ardupilot_f9p,
         "ardupilot_f9p_mb_rover": case_ardupilot_f9p_mb_rover,
         "ardupilot_f9p_mb_rover_uart2": case_ardupilot_f9p_mb_rover_uart2,
         "ardupilot_f9p_mb_base": case_ardupilot_f9p_mb_base, "ardupilot_f9p_heading": case_ardupilot_f9p_heading, "px4_m9_gnss": case_px4_m9_gnss, "px4_m8_gnss": case_px4_m8_gnss, "ardupilot_gnss": case_ardupilot_gnss, "ardupilot_m9_gnss": case_ardupilot_m9_gnss,
         "gpsd_m9_sky": case_gpsd_m9_sky,
         "gpsd_m9_sky_nmea": case_gpsd_m9_sky_nmea, "state_file": case_state_file}
NEEDS = {"gpsd_ubx": ["gpsd", "gpspipe"], "gpsd_m9_sky": ["gpsd", "gpspipe"], "gpsd_m9_sky_nmea": ["gpsd", "gpspipe"], "gpsd_m9": ["gpsd", "gpspipe", "socat"], "gpsd_f9p": ["gpsd", "gpspipe", "socat"], "gpsd_nmea": ["gpsd", "gpspipe"],
         "gpsdecode": ["gpsdecode"],
         "serial": ["socat", "stty"], "cold_start": ["gpsd", "gpspipe"],
         "power_on_cold": ["gpsd", "gpspipe"]}


def on_alarm(*_):
    raise AssertionError("case exceeded its time limit")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemud", required=True)
    ap.add_argument("--nav", required=True)
    ap.add_argument("--nav-mgnss", help="a multi-GNSS nav file (the *_gnss and *_sky cases)")
    ap.add_argument("--gnssemu", help="the CLI, for `gnssemu ctl` (the *_faults cases)")
    ap.add_argument("case", choices=sorted(CASES) + ["all"])
    args = ap.parse_args()
    failed = False
    for name in (sorted(CASES) if args.case == "all" else [args.case]):
        missing = [t for t in NEEDS.get(name, []) if shutil.which(t) is None]
        if missing:
            print(f"SKIP {name}: {', '.join(missing)} not installed")
            if args.case != "all":
                return 77
            continue
        rig = Rig(args)
        signal.signal(signal.SIGALRM, on_alarm)
        signal.alarm(CASE_LIMITS_S.get(name, CASE_LIMIT_S))
        ok = False
        try:
            print(f"case {name}:")
            CASES[name](rig)
            ok = True
        except AssertionError as e:
            print(f"FAIL {name}: {e}")
        finally:
            signal.alarm(0)
            rc = rig.close(failed=not ok)
        if ok and rc not in (0, None):
            print(f"FAIL {name}: gnssemud exited {rc} on SIGTERM (want 0)")
            ok = False
        print(f"{'PASS' if ok else 'FAIL'} {name}")
        failed |= not ok
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
