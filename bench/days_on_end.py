#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Days on end from the data that ship (issue 12): `gnssemu batch` with a
config (default: config/default.toml, whose nav file is from 2022) over a
static antenna at its origin for --hours at 1 Hz, starting now (or --start),
and what a user would check:

  - epochs with a fix (want >= 99.9 %);
  - the epoch-to-epoch step of the fix: its distribution, the largest step,
    and the largest within +-60 s of every day boundary (00:00 GPST and
    UTC), of the week boundary and of the end of the nav data (where each
    satellite goes on along its last orbit);
  - satellites in view (above the horizon; and above the 5 deg mask), with
    satellites rising and setting; and every hour, per system (G R E C J S),
    the satellites above the mask and those used in the fix (`batch --sats`).

Prints figures and a Markdown table (docs/models.md); no pass/fail.

usage: days_on_end.py --gnssemu build/tools/gnssemu/gnssemu [--config FILE] [--systems G,R,E,C,J]
                      [--start now|YYYY-MM-DDTHH:MM:SS] [--hours 72] [--table-step-h 3]
"""
import argparse
import csv
import datetime
import math
import os
import re
import subprocess
import sys
import tempfile

GPS_EPOCH = datetime.datetime(1980, 1, 6, tzinfo=datetime.timezone.utc)
LEAP_S = 18  # GPS - UTC since 2017-01-01 (no leap second announced since)
MASK_DEG = 5.0
SYSTEMS = "GRECJS"  # RINEX letters, in the order of the sat column's systems


def gps_of(dt):
    """(week, tow) of a GPST calendar time."""
    s = (dt - GPS_EPOCH).total_seconds()
    return int(s // 604800), s - 604800 * int(s // 604800)


def gpst_text(week, tow):
    return (GPS_EPOCH + datetime.timedelta(seconds=week * 604800 + tow)).strftime("%Y-%m-%d %H:%M:%S")


def read_origin(config):
    text = open(config).read()
    sec = text[text.index("[origin]"):]
    val = lambda k: float(re.search(rf"^{k}\s*=\s*([-0-9.eE+]+)", sec, re.M).group(1))
    return val("lat_deg"), val("lon_deg"), val("height_m")


def pct(v, p):
    return v[min(len(v) - 1, int(p * len(v)))] if v else float("nan")


def run(args, start_week, start_tow):
    lat, lon, h = read_origin(args.config)
    n = int(args.hours * 3600) + 1
    tmp = tempfile.mkdtemp(prefix="gnssemu-days-")
    truth = os.path.join(tmp, "truth.csv")
    errors = os.path.join(tmp, "errors.csv")
    with open(truth, "w") as f:
        f.write("gps_week,tow_s,lat_deg,lon_deg,height_m\n")
        for k in range(n):
            w, tow = divmod(start_week * 604800 + start_tow + k, 604800)
            f.write(f"{int(w)},{tow:.3f},{lat},{lon},{h}\n")
    cmd = [args.gnssemu, "batch", "--config", args.config, "--truth", truth, "--errors", errors, "--sats", "-"]
    if args.systems:
        cmd += ["--systems", args.systems]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    # Per epoch: satellites above the horizon (count, set), above the mask, and
    # per system (SYSTEMS order) above the mask and used.
    in_view, above_mask, sets, per_system = [], [], [], []
    header = proc.stdout.readline().strip().split(",")
    c_tow, c_sat, c_el, c_used = (header.index(k) for k in ("tow_s", "sat", "el_deg", "used"))
    cur_tow, cur = None, []

    def close_epoch():
        up = [(sat, el, used) for sat, el, used in cur if el >= 0.0]
        in_view.append(len(up))
        above_mask.append(sum(1 for _, el, _ in up if el >= MASK_DEG))
        sets.append(frozenset(sat for sat, _, _ in up))
        per_system.append(tuple((sum(1 for sat, el, _ in up if sat[0] == x and el >= MASK_DEG),
                                 sum(1 for sat, _, used in up if sat[0] == x and used))
                                for x in SYSTEMS))

    for line in proc.stdout:
        f = line.rstrip("\n").split(",")
        if f[c_tow] != cur_tow and cur_tow is not None:
            close_epoch()
            cur = []
        cur_tow = f[c_tow]
        cur.append((f[c_sat], float(f[c_el]), f[c_used] == "1"))
    if cur_tow is not None:
        close_epoch()
    err = proc.stderr.read()
    if proc.wait() != 0:
        sys.exit("gnssemu batch failed: " + err)
    rows = list(csv.DictReader(open(errors)))
    for p in (truth, errors):
        os.remove(p)
    os.rmdir(tmp)
    return rows, err, in_view, above_mask, sets, per_system


def report(args, label, start_week, start_tow):
    rows, err, in_view, above_mask, sets, per_system = run(args, start_week, start_tow)
    print(f"\n## {label}: {args.hours:g} h at 1 Hz from {gpst_text(start_week, start_tow)} GPST "
          f"(week {start_week} tow {start_tow:.0f}), {os.path.relpath(args.config)}")
    sat_line = next((l for l in err.splitlines() if "satellites:" in l), "")
    print(sat_line.replace("gnssemu batch: ", ""))
    n = len(rows)
    fixed = [r for r in rows if r["e_m"] != ""]
    print(f"epochs {n}, with a fix {len(fixed)} ({100.0 * len(fixed) / n:.3f} %), "
          f"3D {sum(1 for r in rows if r['fix_type'] == '3')}")
    t0 = int(rows[0]["gps_week"]) * 604800 + float(rows[0]["tow_s"])
    gaps = [int(r["gps_week"]) * 604800 + float(r["tow_s"]) for r in rows if r["e_m"] == ""]
    if gaps:
        print("epochs without a fix: " + ", ".join(f"{gpst_text(0, g)} ({g - t0:.0f} s in)" for g in gaps[:5]) +
              (" ..." if len(gaps) > 5 else ""))
    steps = []  # (h, 3d, seconds since start)
    prev = None
    for r in rows:
        if r["e_m"] == "":
            prev = None
            continue
        p = (float(r["e_m"]), float(r["n_m"]), float(r["u_m"]))
        t = int(r["gps_week"]) * 604800 + float(r["tow_s"]) - t0
        if prev is not None:
            d = [a - b for a, b in zip(p, prev)]
            steps.append((math.hypot(d[0], d[1]), math.sqrt(sum(x * x for x in d)), t))
        prev = p
    hs = sorted(s[0] for s in steps)
    ds = sorted(s[1] for s in steps)
    worst = max(steps, key=lambda s: s[1])
    print(f"epoch-to-epoch step of the fix: horizontal median {pct(hs, 0.5):.3f} m, 99.99 % {pct(hs, 0.9999):.3f} m, "
          f"max {hs[-1]:.3f} m; 3D median {pct(ds, 0.5):.3f} m, 99.99 % {pct(ds, 0.9999):.3f} m, "
          f"max {ds[-1]:.3f} m at {gpst_text(0, t0 + worst[2])} GPST")
    # Boundaries: 00:00 GPST and 00:00 UTC of every day, the week boundary, the data's end.
    marks = []
    first_day = math.floor(t0 / 86400)
    for d in range(first_day, first_day + int(args.hours // 24) + 2):
        marks.append(("00:00 GPST", d * 86400 - t0))
        marks.append(("00:00 UTC", d * 86400 + LEAP_S - t0))
    for w in range(int(t0 // 604800), int((t0 + args.hours * 3600) // 604800) + 1):
        marks.append(("week boundary", (w + 1) * 604800 - t0))
    m = re.search(r"after (\d{4}-\d\d-\d\d \d\d:\d\d:\d\d) GPST every satellite", sat_line)
    if m:
        end = datetime.datetime.strptime(m.group(1), "%Y-%m-%d %H:%M:%S").replace(tzinfo=datetime.timezone.utc)
        marks.append(("end of the nav data", (end - GPS_EPOCH).total_seconds() - t0))
    for name in ("00:00 GPST", "00:00 UTC", "week boundary", "end of the nav data"):
        near = [s[1] for s in steps for (k, x) in marks if k == name and abs(s[2] - x) <= 60.0]
        if near:
            print(f"  largest 3D step within 60 s of {name} ({sum(1 for k, x in marks if k == name and 0 <= x <= args.hours * 3600)}"
                  f" in the run): {max(near):.3f} m")
    changes = sum(1 for a, b in zip(sets, sets[1:]) if a != b)
    print(f"satellites in view per epoch (above the horizon): min {min(in_view)} max {max(in_view)}; "
          f"above the 5 deg mask: min {min(above_mask)} max {max(above_mask)}; "
          f"{changes} epochs where a satellite rose or set")
    # Table: per table step, satellites in view at its start, range over the step, rises and sets.
    step = int(args.table_step_h * 3600)
    print(f"\n| GPST | in view (>0 deg) | above 5 deg | range of above 5 deg over the next {args.table_step_h:g} h | rose / set |")
    print("|---|---|---|---|---|")
    for k in range(0, len(sets) - 1, step):
        j = min(k + step, len(sets) - 1)
        rose = sum(len(b - a) for a, b in zip(sets[k:j], sets[k + 1:j + 1]))
        fell = sum(len(a - b) for a, b in zip(sets[k:j], sets[k + 1:j + 1]))
        print(f"| {gpst_text(0, t0 + k)} | {in_view[k]} | {above_mask[k]} | {min(above_mask[k:j + 1])}-"
              f"{max(above_mask[k:j + 1])} | {rose} / {fell} |")
    # Per system, every hour: above the mask / used in the fix.
    shown = [i for i, x in enumerate(SYSTEMS) if any(e[i][0] for e in per_system)]
    print("\nper system every hour, above the 5 deg mask / used in the fix:\n")
    print("| GPST | " + " | ".join(SYSTEMS[i] for i in shown) + " | all |")
    print("|---|" + "---|" * (len(shown) + 1))
    for k in range(0, len(per_system), 3600):
        e = per_system[k]
        print(f"| {gpst_text(0, t0 + k)} | " + " | ".join(f"{e[i][0]} / {e[i][1]}" for i in shown) +
              f" | {sum(x[0] for x in e)} / {sum(x[1] for x in e)} |")
    lo = [min(e[i][0] for e in per_system) for i in shown]
    hi = [max(e[i][0] for e in per_system) for i in shown]
    print("\nabove the mask over the run: " + ", ".join(f"{SYSTEMS[i]} {a}-{b}" for i, a, b in zip(shown, lo, hi)) +
          f"; used: {min(sum(x[1] for x in e) for e in per_system)}-{max(sum(x[1] for x in e) for e in per_system)}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--config", default=os.path.join(os.path.dirname(__file__), "..", "config", "default.toml"))
    ap.add_argument("--systems", default="", help="batch --systems (default: the config's [receiver] constellations)")
    ap.add_argument("--start", default="now", help="now, or GPST YYYY-MM-DDTHH:MM:SS")
    ap.add_argument("--hours", type=float, default=72.0)
    ap.add_argument("--table-step-h", type=float, default=3.0)
    ap.add_argument("--week-boundary", action="store_true",
                    help="also run a window that crosses the next GPS week boundary (Saturday/Sunday 00:00 GPST)")
    args = ap.parse_args()
    if args.start == "now":
        now = datetime.datetime.now(datetime.timezone.utc) + datetime.timedelta(seconds=LEAP_S)
        start = now.replace(microsecond=0) + datetime.timedelta(seconds=1)
    else:
        start = datetime.datetime.strptime(args.start, "%Y-%m-%dT%H:%M:%S").replace(tzinfo=datetime.timezone.utc)
    report(args, "from the start", *gps_of(start))
    if args.week_boundary:
        week, _ = gps_of(start)
        # Friday 12:00 GPST of this week: 72 h include Saturday/Sunday midnight, the week rollover.
        report(args, "across the week boundary", week, 5 * 86400 + 43200.0)


if __name__ == "__main__":
    main()
