# SPDX-License-Identifier: Apache-2.0
"""PX4's and ArduPilot's UBX start-up while faults run (cases of
ubx_ports_integration.py, docs/ports.md §Tests, docs/faults.md).

The daemon starts with `--scenario` whose events are active from the first
epoch, while the host configures: a CW jammer, a 50 m step on PRN 08 (used
in the fault-free run: 75 deg elevation on the fixed date below) and a
latency on the host's output. One more fault is injected through `gnssemu
ctl` in the middle of the host's sequence. The sequences are ubx_host's,
byte for byte as in the fault-free cases, with every reply within the
host's time-out; then what the host reads shows the faults' physics against
the same daemon after `ctl clear` (fault-free, seconds later, same sky).

  px4_faults       jammer 24 dB, latency 100 ms; a second CW jammer (28 dB:
                   about 29.5 dB together) injected after MON-VER. After the
                   start-up: NAV-PVT at 5 Hz with gnssFixOK arrives 100 ms
                   later (against iTOW) than after clear; NAV-SVINFO C/N0
                   lower and PRN 08 tracked but not used; MON-HW jamInd
                   higher; 200 ms more latency puts a reply past PX4's 250 ms
                   (PX4 would restart its configuration, as behind a real
                   link that slow); an injected outage drops gnssFixOK, `ctl
                   clear` brings it back
  ardupilot_faults jammer 30 dB, latency 50 ms; a drag-off spoofer injected
                   once the message rates are set. Every poll answered within
                   ArduPilot's 300 ms request interval; NAV-STATUS
                   spoofDetState >= 2, the fix leaves the truth while
                   gnssFixOK stays; MON-HW jamInd higher; `ctl clear`: the
                   spoofed loops let go, gnssFixOK drops and comes back
"""
import json
import math
import os
import statistics
import struct
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the rooms' shared helpers (itlib, ubx_host)
from ubx_host import (ARDUPILOT_REQUEST_S, PX4_REPLY_LIMIT_S, Stream, ardupilot_rates, ardupilot_startup, frame,  # noqa: E402
                      is_ubx, mon_hw_jam, nav_status_spoof, px4_rates, px4_startup, send, svinfo_channels)

START = "2022-01-01T01:00:00"  # GPS time: a fixed sky, PRN 08 high and used
BIASED_PRN = 8
FIX_LIMIT_S = 10.0  # first fix under a 30 dB jammer: ~4 s of reacquisition at low C/N0


def event(event_type, **keys):
    """One scenario [[event]] of event_type, active from its start (start_s = 0)."""
    lines = [f'type = "{event_type}"', "start_s = 0"] + [f"{k} = {json.dumps(v)}" for k, v in keys.items()]
    return "[[event]]\n" + "\n".join(lines) + "\n"


class FaultRig:
    """The case's daemon (a pty, a control socket, the scenario) and ctl."""

    def __init__(self, rig, js_db, latency_ms):
        assert rig.args.gnssemu, "the *_faults cases need --gnssemu (for gnssemu ctl)"
        self.rig = rig
        self.sock = os.path.join(rig.tmp, "control.sock")
        self.path = os.path.join(rig.tmp, "gps0")
        scenario = self.write("scenario.toml", event("jammer", kind="cw", js_db=js_db) +
                              event("satellite", prn=BIASED_PRN, bias_m=50) +
                              event("port", fault="latency", output=0, latency_ms=latency_ms))
        extra = f'[time]\nstart = "{START}"\n[status]\nport = 0\n[control]\nsocket = "{self.sock}"\n'
        rig.start_daemon(f'[[output]]\nname = "gps0"\ntype = "pty"\npath = "{self.path}"\n', extra_toml=extra,
                         scenario=scenario)
        deadline = time.monotonic() + 10
        while not os.path.exists(self.sock):
            assert time.monotonic() < deadline, "no control socket"
            time.sleep(0.05)
        self.fd = rig.open_tty(self.path)
        self.s = Stream(self.fd)
        # The receiver is on before the host boots: its port faults act from
        # the first epoch, so the host starts once that epoch went out.
        self.s.wait_for(lambda k, m: k == "nmea", 5.0, "the first epoch (factory NMEA)")

    def write(self, name, text):
        path = os.path.join(self.rig.tmp, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    def ctl(self, *args):
        r = subprocess.run([self.rig.args.gnssemu, "ctl", "--socket", self.sock, *args], capture_output=True,
                           text=True, timeout=10)
        assert r.returncode == 0, f"ctl {' '.join(args)}: exit {r.returncode}: {r.stderr}"
        return json.loads(r.stdout)

    def inject(self, name, toml):
        """Inject a scenario now; returns the monotonic time it was accepted."""
        reply = self.ctl("inject", self.write(name, toml))
        assert reply["ok"] and len(reply["injected"]) == 1, reply
        return time.monotonic()

    def status(self):
        return self.ctl("status")["status"]


def ubx_of(msgs, cls, mid):
    return [(t, m) for t, k, m in msgs if k == "ubx" and m[2] == cls and m[3] == mid]


def output_lag_s(msgs):
    """Median of NAV-PVT arrival (monotonic) minus its iTOW: the same
    constant plus whatever the line adds."""
    return statistics.median(t - struct.unpack_from("<I", m, 6)[0] / 1000.0 for t, m in ubx_of(msgs, 0x01, 0x07))


def cn0_by_prn(svinfo):
    """C/N0 of the tracked channels (cno > 0) by PRN, dB-Hz."""
    return {sv: cno for sv, _, _, cno in svinfo_channels(svinfo) if cno > 0}


def cw_cn0_drop_db(js_db):
    """C/N0 lost under a CW jammer of J/S js_db: the jammer adds I0 =
    J/(Q Rc) to N0 (Kaplan & Hegarty §6.10.1), so every satellite loses
    10 log10(1 + I0/N0). I0 = N0 at J/S 20.6 dB for wideband noise (Q = 2,
    docs/faults.md §1), 3 dB less for CW (Q = 1)."""
    return 10 * math.log10(1 + 10 ** ((js_db - 20.6 + 10 * math.log10(2)) / 10))


def jam_ind(msgs):
    """(agcCnt, jamInd) means of the MON-HW frames."""
    hw = [mon_hw_jam(m) for _, m in ubx_of(msgs, 0x0A, 0x09)]
    assert hw, "no MON-HW"
    return sum(a for a, _ in hw) / len(hw), sum(j for _, j in hw) / len(hw)


def wait_fix_flag(s, ok, limit_s, what):
    return s.wait_for(lambda k, m: k == "ubx" and m[2:4] == b"\x01\x07" and bool(m[6 + 21] & 1) == ok, limit_s, what)[0]


def check_reply_latency(replies, latency_s, limit_s, host):
    """Every reply (but CFG-VALSET's NAK, which PX4 waits 2 s for) came
    through the latency and within the host's limit."""
    early = [(w, round(dt, 3)) for w, dt in replies.times if dt < latency_s - 0.01]
    assert not early, f"replies faster than the line's {latency_s * 1000:.0f} ms latency: {early}"
    late = [(w, round(dt, 3)) for w, dt in replies.times if dt >= limit_s and "VALSET" not in w]
    assert not late, f"replies after {host}'s {limit_s * 1000:.0f} ms: {late}"


CW_STEP = event("jammer", kind="cw", js_db=28)
MORE_LATENCY = event("port", fault="latency", output=0, latency_ms=200)
OUTAGE = event("outage")


def case_px4_faults(rig):
    f = FaultRig(rig, js_db=24, latency_ms=100)
    s = f.s
    # PX4 configures while the scenario's faults run; a second CW jammer comes
    # in once it knows the board.
    t0 = time.monotonic()
    replies = px4_startup(s, f.fd, after_mon_ver=lambda: f.inject("cw_step.toml", CW_STEP))
    t_configured = time.monotonic() - t0
    check_reply_latency(replies, 0.1, PX4_REPLY_LIMIT_S, "PX4")
    jammers = [e for e in f.status()["faults"] if e["type"] == "jammer" and e["active"]]
    assert len(jammers) == 2, f"active jammers {jammers}"
    faulted = px4_rates(s, 3.0, FIX_LIMIT_S)
    print(f"  px4_faults: start-up passed under CW jammer 24 dB (+28 dB injected after MON-VER), PRN {BIASED_PRN:02d} "
          f"+50 m, latency 100 ms, in {t_configured:.2f} s ({replies.summary()}; PX4 waits 250 ms)")

    # 200 ms more latency: a reply past PX4's time-out, as behind any line that slow.
    f.inject("more_latency.toml", MORE_LATENCY)
    time.sleep(0.5)  # the next epoch's fault status sets it on the port
    t1 = time.monotonic()
    send(f.fd, frame(0x0A, 0x04))
    slow_s = s.wait_for(is_ubx(0x0A, 0x04), 2.0, "MON-VER through 300 ms of latency")[0] - t1
    assert slow_s >= 0.29, f"MON-VER after {slow_s:.3f} s through 300 ms of latency"

    # An outage: gnssFixOK goes; ctl clear ends every fault and brings it back.
    t_out = f.inject("outage.toml", OUTAGE)
    t_lost = wait_fix_flag(s, False, 3.0, "NAV-PVT without gnssFixOK after the outage") - t_out
    f.ctl("clear")
    t_clr = time.monotonic()
    t_back = wait_fix_flag(s, True, 10.0, "NAV-PVT with gnssFixOK after ctl clear") - t_clr
    clean = px4_rates(s, 3.0, 1.0)

    # What PX4 read under the faults against the same receiver fault-free.
    sv_f = cn0_by_prn([m for _, m in ubx_of(faulted, 0x01, 0x30)][-1])
    sv_c = cn0_by_prn([m for _, m in ubx_of(clean, 0x01, 0x30)][-1])
    common = sorted(set(sv_f) & set(sv_c))
    assert len(common) >= 4, f"tracked under the jammers {sorted(sv_f)}, after clear {sorted(sv_c)}"
    js_db = 10 * math.log10(10 ** 2.4 + 10 ** 2.8)
    drop = statistics.mean(sv_c[p] - sv_f[p] for p in common)
    model = cw_cn0_drop_db(js_db)
    used_f = {sv: used for sv, used, _, _ in svinfo_channels([m for _, m in ubx_of(faulted, 0x01, 0x30)][-1])}
    used_c = {sv: used for sv, used, _, _ in svinfo_channels([m for _, m in ubx_of(clean, 0x01, 0x30)][-1])}
    agc_f, jam_f = jam_ind(faulted)
    agc_c, jam_c = jam_ind(clean)
    lag_ms = 1000 * (output_lag_s(faulted) - output_lag_s(clean))
    print(f"  px4_faults: NAV-SVINFO C/N0 {drop:.1f} dB lower on the {len(common)} satellites tracked in both "
          f"(J/S {js_db:.1f} dB CW: {model:.1f} dB by the interference relation); tracked {len(sv_f)} vs {len(sv_c)} "
          f"after clear; MON-HW jamInd {jam_f:.0f} vs {jam_c:.0f}, agcCnt {agc_f:.0f} vs {agc_c:.0f}; PRN "
          f"{BIASED_PRN:02d} tracked at {sv_f.get(BIASED_PRN)} dB-Hz, used {used_f.get(BIASED_PRN)} -> "
          f"{used_c.get(BIASED_PRN)}")
    print(f"  px4_faults: NAV-PVT {lag_ms:.0f} ms later against iTOW under 100 ms latency; MON-VER after "
          f"{slow_s * 1000:.0f} ms through 300 ms (PX4 gives up at 250); outage: gnssFixOK 0 after {t_lost:.2f} s, "
          f"back {t_back:.2f} s after clear")
    assert abs(drop - model) <= 1.5, f"C/N0 {drop:.1f} dB lower, the interference relation says {model:.1f}"
    assert jam_f >= jam_c + 20, f"jamInd {jam_f:.0f} under the jammers vs {jam_c:.0f} after clear"
    assert BIASED_PRN in sv_f and used_f[BIASED_PRN] is False, \
        f"PRN {BIASED_PRN:02d} (50 m step) tracked at {sv_f.get(BIASED_PRN)} dB-Hz, used {used_f.get(BIASED_PRN)}"
    assert used_c.get(BIASED_PRN), f"PRN {BIASED_PRN:02d} not used after clear"
    assert 70 <= lag_ms <= 150, f"NAV-PVT {lag_ms:.0f} ms later under 100 ms latency"
    assert t_lost <= 2.0, f"gnssFixOK still set {t_lost:.2f} s after the outage"


SPOOFER = event("spoofer", mode="drag", power_advantage_db=6, drag_speed_m_s=5, drag_heading_deg=0)


def case_ardupilot_faults(rig):
    f = FaultRig(rig, js_db=30, latency_ms=50)
    s = f.s
    t0 = time.monotonic()
    injected = []
    replies, sv = ardupilot_startup(s, f.fd, f.path, fix_limit_s=FIX_LIMIT_S,
                                    after_msg_rates=lambda: injected.append(f.inject("spoofer.toml", SPOOFER)))
    t_configured = time.monotonic() - t0
    check_reply_latency(replies, 0.05, ARDUPILOT_REQUEST_S, "ArduPilot")
    faulted = ardupilot_rates(s, 2.0)
    spoof_cn0 = [c for _, _, _, c in svinfo_channels(sv) if c > 0]
    agc_f, jam_f = jam_ind(faulted)
    spoof = [nav_status_spoof(m) for t, m in ubx_of(s.seen, 0x01, 0x03) if t > injected[0]]
    err_f = f.status()["error"]["h_m"]
    print(f"  ardupilot_faults: start-up passed under jammer 30 dB, PRN {BIASED_PRN:02d} +50 m, latency 50 ms and a "
          f"drag-off spoofer injected after CFG-MSG, in {t_configured:.2f} s ({replies.summary()}; ArduPilot asks "
          f"again after 300 ms)")
    f.ctl("clear")
    t_clr = time.monotonic()
    t_lost = wait_fix_flag(s, False, 3.0, "NAV-PVT without gnssFixOK as the spoofer lets go") - t_clr
    t_back = wait_fix_flag(s, True, 10.0, "NAV-PVT with gnssFixOK after ctl clear") - t_clr
    clean = s.collect(2.0)
    agc_c, jam_c = jam_ind(clean)
    send(f.fd, frame(0x01, 0x30))
    sv_c = s.frame_of(0x01, 0x30)
    clean_cn0 = [c for _, _, _, c in svinfo_channels(sv_c) if c > 0]
    err_c = f.status()["error"]["h_m"]
    print(f"  ardupilot_faults: NAV-STATUS spoofDetState {max(spoof)} after the spoofer (1: none); horizontal error "
          f"{err_f:.1f} m with gnssFixOK, {err_c:.1f} m after clear; NAV-SVINFO C/N0 "
          f"{min(spoof_cn0)}..{max(spoof_cn0)} dB-Hz spoofed, {min(clean_cn0)}..{max(clean_cn0)} after clear; "
          f"MON-HW jamInd {jam_f:.0f} vs {jam_c:.0f}, agcCnt {agc_f:.0f} vs {agc_c:.0f}; clear: gnssFixOK 0 after "
          f"{t_lost:.2f} s, back after {t_back:.2f} s")
    assert max(spoof) >= 2, f"spoofDetState {spoof}"
    assert max(spoof_cn0) - min(spoof_cn0) <= 1, f"spoofed C/N0 not uniform: {spoof_cn0}"
    assert err_f >= 10.0, f"horizontal error {err_f} m under a 5 m/s drag"
    assert err_c < 10.0, f"horizontal error {err_c} m after clear"
    assert jam_f >= jam_c + 20, f"jamInd {jam_f:.0f} under the jammer vs {jam_c:.0f} after clear"
