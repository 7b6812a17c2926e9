#!/usr/bin/python3
"""Teaches one part of a recorded log and localizes another, for many seeds and map modes, and
prints the per-mode figures docs/RESULTS.md quotes for real logs (the Intel and ACES studies).

    scripts/log_study.py --retrace build/retrace --log intel-corrected.log.gz \
        --teach-to 351.09 --localize-from 351.09 --seeds 1-40 --out /tmp/intel

Per mode: the median [min, max] of the on-route RMS over the seeds, how many seeds stay under
1 m, the largest single-update jump of the estimate beyond the odometry's motion
(localizer.max_jump_m), the largest single-update increase of the error in one alignment
(localizer.max_error_increase_m), the re-acquisitions and how many were wrong (the error more
than 0.5 m larger after) or closer, the time lost by the localizer's own account, and, for
comparison with earlier studies, the largest jump of est.tum against reference.tum (whose
alignment moves with the teaching sample the reference matches: far off the route it moves by
metres, and counts as a jump). A second table says whether the localizer knew when it was wrong:
the silent failure time (error above 1 m while neither lost nor off map) as a share of the run,
the false alarms (lost with the error below 0.3 m), the time off map and the wrong map switches.
`--reuse` summarizes the folders already in --out without running anything again. Every log command runs with --synthetic-odometry (the logs
are corrected ones: their poses are the reference). Runs two commands at a time.
"""
import argparse
import concurrent.futures
import json
import math
import os
import statistics
import subprocess
import sys


def seeds_of(text):
    out = []
    for part in text.split(","):
        if "-" in part:
            a, b = part.split("-")
            out.extend(range(int(a), int(b) + 1))
        elif part:
            out.append(int(part))
    return out


def run(cmd):
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode not in (0, 1):
        sys.exit("failed: " + " ".join(cmd) + "\n" + proc.stderr)
    return proc


def read_tum(path):
    rows = {}
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            v = [float(x) for x in line.split()]
            rows[v[0]] = (v[1], v[2])
    return rows


def jumps(folder):
    """Largest |move of est.tum - move of reference.tum| between consecutive scans (m)."""
    est = read_tum(os.path.join(folder, "est.tum"))
    ref = read_tum(os.path.join(folder, "reference.tum"))
    times = sorted(t for t in est if t in ref)
    jump = 0.0
    for a, b in zip(times, times[1:]):
        de = (est[b][0] - est[a][0], est[b][1] - est[a][1])
        dr = (ref[b][0] - ref[a][0], ref[b][1] - ref[a][1])
        jump = max(jump, math.hypot(de[0] - dr[0], de[1] - dr[1]))
    return jump


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--retrace", required=True)
    p.add_argument("--log", required=True)
    p.add_argument("--teach-from", default=None)
    p.add_argument("--teach-to", required=True)
    p.add_argument("--localize-from", required=True)
    p.add_argument("--seeds", default="1-40")
    p.add_argument("--modes", default="partial,scan_matched,consistent")
    p.add_argument("--out", required=True)
    p.add_argument("--set", action="append", default=[], help="passed to both commands")
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--reuse", action="store_true",
                   help="keep the teach and localize folders already in --out (only summarize)")
    a = p.parse_args()
    seeds = seeds_of(a.seeds)
    modes = a.modes.split(",")
    sets = [x for s in a.set for x in ("--set", s)]
    os.makedirs(a.out, exist_ok=True)

    def teach(seed):
        out = os.path.join(a.out, f"teach_{seed}")
        if a.reuse and os.path.isdir(out):
            return
        cmd = [a.retrace, "log-teach", a.log, "--to", a.teach_to, "--synthetic-odometry",
               "--seed", str(seed), "--out", out, "--mode", ",".join(modes), "--no-figures"]
        if a.teach_from:
            cmd += ["--from", a.teach_from]
        run(cmd + sets)

    def localize(seed, mode):
        out = os.path.join(a.out, f"{mode}_{seed}")
        if not (a.reuse and os.path.exists(os.path.join(out, "metrics.json"))):
            run([a.retrace, "log-localize", a.log, "--teach",
                 os.path.join(a.out, f"teach_{seed}", mode, "teach"), "--from", a.localize_from,
                 "--synthetic-odometry", "--seed", str(seed), "--out", out, "--no-figures"] + sets)
        with open(os.path.join(out, "metrics.json")) as f:
            m = json.load(f)
        h = m["localizer"]
        return seed, mode, m, (h["max_jump_m"], h["max_error_increase_m"], h["reacquisitions"],
                               h["reacquisitions_wrong"], h["reacquisitions_closer"], jumps(out))

    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        list(pool.map(teach, seeds))
        results = list(pool.map(lambda sm: localize(*sm), [(s, m) for s in seeds for m in modes]))

    print(f"{a.log}: seeds {a.seeds}, {len(seeds)} seeds")
    print("| mode | on-route RMS (m), median [min, max] | seeds < 1 m | largest jump, median [max] "
          "| seeds with a jump > 1 m | largest error increase, median [max] "
          "| seeds with an increase > 1 m | re-acquisitions (wrong, closer) "
          "| lost by its own account (s) | maps | est.tum jump > 1 m |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for mode in modes:
        rows = [r for r in results if r[1] == mode]
        rms = [r[2]["localization_error_on_route_m"]["rms"] for r in rows]
        jump = [r[3][0] for r in rows]
        away = [r[3][1] for r in rows]
        reacq = sum(r[3][2] for r in rows)
        wrong = sum(r[3][3] for r in rows)
        closer = sum(r[3][4] for r in rows)
        lost = sum(r[2]["localizer"]["lost_time_s"] for r in rows)
        maps = sorted({r[2]["maps"] for r in rows})
        away = [0.0 if x is None else x for x in away]
        tum = [r[3][5] for r in rows]
        print(f"| {mode} | {statistics.median(rms):.3f} [{min(rms):.2f}, {max(rms):.2f}] "
              f"| {sum(x < 1.0 for x in rms)} / {len(rows)} "
              f"| {statistics.median(jump):.2f} [{max(jump):.1f}] | {sum(x > 1.0 for x in jump)} "
              f"| {statistics.median(away):.2f} [{max(away):.1f}] | {sum(x > 1.0 for x in away)} "
              f"| {reacq} ({wrong}, {closer}) | {lost:.0f} "
              f"| {','.join(map(str, sorted(maps)))} | {sum(x > 1.0 for x in tum)} |")
    # Whether the stack knew when it was wrong (docs/FORMATS.md, metrics.json's localizer).
    print()
    print("| mode | silent failure, % of the run: median [max] | longest silent stretch, max (s) "
          "| false alarm (s), total | off map (s), total | map switches (wrong) |")
    print("|---|---|---|---|---|---|")
    for mode in modes:
        rows = [r for r in results if r[1] == mode]
        h = [r[2]["localizer"] for r in rows]
        silent = [100.0 * x["silent_failure_time_s"] / r[2]["duration_s"] for x, r in zip(h, rows)]
        print(f"| {mode} | {statistics.median(silent):.2f} [{max(silent):.1f}] "
              f"| {max(x['longest_silent_failure_s'] for x in h):.0f} "
              f"| {sum(x['false_alarm_time_s'] for x in h):.0f} "
              f"| {sum(x['off_map_time_s'] for x in h):.0f} "
              f"| {sum(r[2]['switches'] for r in rows)} ({sum(x['wrong_switches'] for x in h)}) |")
    with open(os.path.join(a.out, "study.json"), "w") as f:
        json.dump([{"seed": r[0], "mode": r[1], "on_route_rms": r[2]["localization_error_on_route_m"]["rms"],
                    "jump": r[3][0], "error_increase": r[3][1], "reacquisitions": r[3][2],
                    "wrong": r[3][3], "closer": r[3][4], "tum_jump": r[3][5]}
                   for r in results], f, indent=1)


if __name__ == "__main__":
    main()
