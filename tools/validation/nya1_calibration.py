#!/usr/bin/env python3
"""Reproduce the NYA1 calibration table of docs/validation.md
("Calibration against a real receiver") from a clean build.

1. gnssemu calibrate on the full NYA1 day (GPS L1, 2880 epochs) at the IGS
   station's header coordinates -> a fitted config. With --span holdout the
   fit sees only 00:00-12:00 and everything is compared on 12:00-24:00.
2. The real single-point errors: gnssemu spp --station on the same data
   (the hour 00:00-01:30 of the 90-minute file, the whole day, or the
   held-out half day).
3. The simulation: gnssemu batch with the fitted config and static truth at
   the station over the same span, for --seeds seeds (errors sampled every
   30 s like the data).
4. sigma E/N/U, CEP50, CEP95 and the error correlation time of both, and
   their relative differences (simulated ensemble mean vs real).

Usage: tools/validation/nya1_calibration.py --gnssemu build/tools/gnssemu/gnssemu [--seeds 20] [--span hour|day|holdout]
Only the Python standard library is used.
"""
import argparse
import gzip
import math
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "tests", "data")
OBS_DAY = os.path.join(DATA, "obs", "NYA100NOR_S_20241240000_01D_30S_GO_L1.rnx.gz")
OBS_HOUR = os.path.join(DATA, "obs", "NYA100NOR_S_20241240000_90M_30S_MO.rnx")
NAV = os.path.join(DATA, "nav", "NYA100NOR_S_20241240000_01D_GN.rnx")
STATION = "1202434.1303,252632.2212,6237772.4351"  # NYA1 header APPROX POSITION XYZ
STEP_S = 30.0
MASK_DEG = "10"


def run(args):
    return subprocess.run(args, check=True, capture_output=True, text=True).stdout


def read_csv(text):
    lines = [l for l in text.strip().splitlines() if l]
    head = lines[0].split(",")
    return [dict(zip(head, l.split(","))) for l in lines[1:]]


def quantile(v, q):
    v = sorted(v)
    pos = q * (len(v) - 1)
    i = int(pos)
    f = pos - i
    return v[i] * (1 - f) + v[i + 1] * f if i + 1 < len(v) else v[i]


def split_day(path, tmp):
    """Write the first and the second half of a RINEX 3 observation day (cut at
    12:00) as plain files; returns their paths."""
    with gzip.open(path, "rt") as f:
        lines = f.read().splitlines(keepends=True)
    end = next(i for i, l in enumerate(lines) if "END OF HEADER" in l) + 1
    head, first, second = lines[:end], [], []
    target = first
    for l in lines[end:]:
        if l.startswith(">") and int(l.split()[4]) >= 12:
            target = second
        target.append(l)
    out = []
    for name, body in (("first.rnx", first), ("second.rnx", second)):
        p = os.path.join(tmp, name)
        with open(p, "w") as f:
            f.writelines(head + body)
        out.append(p)
    return out


def stats(series):
    """series: dict grid index -> (e, n, u). Same definitions as statistics::position_error_stats."""
    keys = sorted(series)
    vals = [series[k] for k in keys]
    n = len(vals)
    mean = [sum(v[c] for v in vals) / n for c in range(3)]
    var = [sum((v[c] - mean[c]) ** 2 for v in vals) / n for c in range(3)]
    h = [math.hypot(v[0], v[1]) for v in vals]
    out = {"sigma_e": math.sqrt(var[0]), "sigma_n": math.sqrt(var[1]), "sigma_u": math.sqrt(var[2]),
           "cep50": quantile(h, 0.5), "cep95": quantile(h, 0.95),
           "mean_e": mean[0], "mean_n": mean[1], "mean_u": mean[2],
           # horizontal precision: CEP about the mean position (without the bias)
           "cep50_about_mean": quantile([math.hypot(v[0] - mean[0], v[1] - mean[1]) for v in vals], 0.5),
           "cep95_about_mean": quantile([math.hypot(v[0] - mean[0], v[1] - mean[1]) for v in vals], 0.95)}
    lo, hi = keys[0], keys[-1]
    prev, tau = 1.0, (hi - lo + 1) * STEP_S
    for k in range(1, hi - lo + 1):
        rho = 0.0
        for c in range(3):
            acc, cnt = 0.0, 0
            for g in keys:
                b = series.get(g + k)
                if b is None:
                    continue
                acc += (series[g][c] - mean[c]) * (b[c] - mean[c])
                cnt += 1
            rho += acc / cnt / var[c] / 3.0 if cnt and var[c] > 0 else 0.0
        if rho < math.exp(-1):
            tau = (k - 1 + (prev - math.exp(-1)) / (prev - rho)) * STEP_S
            break
        prev = rho
    out["corr_time"] = tau
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gnssemu", required=True)
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--span", choices=["hour", "day", "holdout"], default="day")
    a = ap.parse_args()
    gnssemu = os.path.abspath(a.gnssemu)

    with tempfile.TemporaryDirectory() as tmp:
        cfg = os.path.join(tmp, "nya1.toml")
        fit_obs, obs = OBS_DAY, OBS_HOUR if a.span == "hour" else OBS_DAY
        if a.span == "holdout":
            fit_obs, obs = split_day(OBS_DAY, tmp)
        report = read_csv(run([gnssemu, "calibrate", "--obs", fit_obs, "--nav", NAV, "--station", STATION,
                               "--mask", MASK_DEG, "--out", cfg]))
        fit = {r["parameter"]: float(r["value"]) for r in report}

        rows = read_csv(run([gnssemu, "spp", "--obs", obs, "--nav", NAV, "--mask", MASK_DEG, "--station", STATION,
                             "--config", cfg]))
        week = int(rows[0]["gps_week"])
        t0 = float(rows[0]["tow_s"])
        t1 = float(rows[-1]["tow_s"])
        real = {round((float(r["tow_s"]) - t0) / STEP_S): (float(r["e_m"]), float(r["n_m"]), float(r["u_m"]))
                for r in rows}
        real_stats = stats(real)

        x, y, z = STATION.split(",")
        truth = os.path.join(tmp, "truth.csv")
        with open(truth, "w") as f:
            f.write(f"gps_week,tow_s,x_m,y_m,z_m\n{week},{t0},{x},{y},{z}\n{week},{t1},{x},{y},{z}\n")
        text = open(cfg).read()
        sims = []
        for seed in range(1, a.seeds + 1):
            c = os.path.join(tmp, f"seed{seed}.toml")
            with open(c, "w") as f:
                f.write(re.sub(r"(?m)^seed = \d+", f"seed = {seed}", text))
            errs = read_csv(run([gnssemu, "batch", "--config", c, "--truth", truth, "--errors", "-"]))
            series = {}
            for r in errs:
                g = (float(r["tow_s"]) - t0) / STEP_S
                if abs(g - round(g)) < 1e-6 and r["fix_type"] != "0":
                    series[round(g)] = (float(r["e_m"]), float(r["n_m"]), float(r["u_m"]))
            sims.append(stats(series))

    print(f"# calibration ({'00:00-12:00' if a.span == 'holdout' else 'full day'}): residual RMS "
          f"{fit['residual_rms']:.3f} m; iono {fit['klobuchar_scale']:.3f} x Klobuchar, ZWD {fit['zwd_residual']:+.3f} m; "
          f"gradient N {fit['gradient_north']:+.3f} E {fit['gradient_east']:+.3f} m, daily cycle N "
          f"{fit['gradient_north_diurnal']:.3f} m peak {fit['gradient_north_peak']:.1f} h E {fit['gradient_east_diurnal']:.3f} m "
          f"peak {fit['gradient_east_peak']:.1f} h, GM {fit['gradient_sigma']:.3f} m "
          f"{fit['gradient_tau']:.0f} s; DLL B_L {fit['dll_bandwidth']:.3f} Hz; multipath {fit['multipath_sigma_zenith']:.3f} m"
          f"/sin(el) {fit['multipath_tau']:.0f} s; orbit/clock {fit['orbit_clock_sigma']:.3f} m {fit['orbit_clock_tau']:.0f} s; "
          f"iono GM {fit['iono_sigma']:.2f} TECU {fit['iono_tau']:.0f} s; C/N0 RMS {fit['cn0_rms']:.2f} dB-Hz")
    print(f"# span: {a.span} ({len(real)} real epochs), simulation: {a.seeds} seeds")
    print("metric,real,simulated_mean,simulated_sd,relative_difference_pct")
    for k, unit in (("sigma_e", "m"), ("sigma_n", "m"), ("sigma_u", "m"), ("cep50", "m"), ("cep95", "m"),
                    ("corr_time", "s"), ("cep50_about_mean", "m"), ("cep95_about_mean", "m"), ("mean_e", "m"),
                    ("mean_n", "m"), ("mean_u", "m")):
        v = [s[k] for s in sims]
        m = sum(v) / len(v)
        sd = math.sqrt(sum((x - m) ** 2 for x in v) / max(len(v) - 1, 1))
        rel = 100.0 * (m - real_stats[k]) / abs(real_stats[k]) if real_stats[k] else float("nan")
        if k.startswith("mean_"):
            rel = float("nan")  # a relative difference of a near-zero mean says nothing
        print(f"{k}_{unit},{real_stats[k]:.3f},{m:.3f},{sd:.3f},{rel:+.1f}")
    print(f"cn0_rms_dbhz,{fit['cn0_rms']:.2f},,,")
    return 0


if __name__ == "__main__":
    sys.exit(main())
