#!/usr/bin/python3
"""Drives a taught route in ways the teaching never did, and localizes each drive in the taught
maps: the route driven backwards, joined mid-way, and (with --out-and-back) a route whose legs
go along a street and come back along it. The map server's study (docs/RESULTS.md, "Drives the
teaching never made"): none of these drives tuned anything.

    scripts/route_study.py --retrace build/retrace --tours 1-20 --seeds 1,2 --out /tmp/routes
    scripts/route_study.py --retrace build/retrace --scenario scenarios/campus.yaml \
        --seeds 1,2 --out /tmp/campus_routes
    scripts/route_study.py --retrace build/retrace --tours 1-5 --tour-set out_and_back=3 \
        --seeds 1,2 --out /tmp/out_and_back
    scripts/route_study.py --retrace build/retrace --scenario scenarios/office.yaml --starts 0 \
        --teach-set sim.lidar.rate_hz=1 --teach-set 'route.switch_points=[60,75]' \
        --seeds 1-5 --out /tmp/sparse   # a sparse teaching drive, its short map re-entered

Per route (a generated tour, or --scenario) and seed: one teaching drive builds the partial,
scan-matched and consistent maps (`retrace teach`); then each drive is recorded by the teacher
(`retrace teach <drive scenario> --record-log`, the route's points reversed, or cut to start at a
random point) and localized in each mode's maps (`retrace log-localize`). Per drive and mode it
reads metrics.json: the on-route RMS, the largest single-update error increase, the switches
and the wrong ones, the time off every map's coverage, and compares the RMS with the consistent
map's on the same drive. Prints one table row per drive and a verdict line per criterion;
writes study.json. Runs --jobs commands at a time.
"""
import argparse
import concurrent.futures
import json
import math
import os
import random
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from log_study import run, seeds_of  # noqa: E402  (the seed lists and commands as there)

MODES = ["partial", "scan_matched", "consistent"]


def read_route(path):
    pts = []
    with open(path) as f:
        for line in f:
            line = line.split("#")[0].strip()
            if line:
                x, y = line.split()[:2]
                pts.append((float(x), float(y)))
    return pts


def write_route(path, pts, comment):
    with open(path, "w") as f:
        f.write(f"# {comment}\n")
        for x, y in pts:
            f.write(f"{x:.3f} {y:.3f}\n")


def cut(pts, s0):
    """The route from arc length s0 on."""
    acc = 0.0
    for i in range(len(pts) - 1):
        (ax, ay), (bx, by) = pts[i], pts[i + 1]
        d = math.hypot(bx - ax, by - ay)
        if d > 0 and acc + d > s0:
            f = (s0 - acc) / d
            return [(ax + f * (bx - ax), ay + f * (by - ay))] + pts[i + 1:]
        acc += d
    return pts[-2:]


def length(pts):
    return sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(pts, pts[1:]))


def route_file_of(scenario):
    """The scenario's route as points: its `route.file` or `route.points`."""
    import yaml  # Debian's python3-yaml, a dependency of python3-rosbag
    with open(scenario) as f:
        s = yaml.safe_load(f)
    r = s["route"]
    if "file" in r:
        return read_route(os.path.join(os.path.dirname(scenario), r["file"])), s
    return [tuple(p) for p in r["points"]], s


def drive_scenario(base, pts, folder, name, comment):
    """A scenario like `base` that drives `pts` (the teacher only: its maps are not used)."""
    import yaml
    routes, s = route_file_of(base)
    os.makedirs(folder, exist_ok=True)
    write_route(os.path.join(folder, "route.txt"), pts, comment)
    s["name"] = name
    s["world"] = os.path.relpath(os.path.join(os.path.dirname(os.path.abspath(base)), s["world"]),
                                 folder)
    s["route"] = {"file": "route.txt", "switch_points": []}
    s["modes"] = ["consistent"]
    s.pop("events", None)  # playback's scripted events, placed along the taught route
    path = os.path.join(folder, "scenario.yaml")
    with open(path, "w") as f:
        yaml.safe_dump(s, f, sort_keys=False)
    return path


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--retrace", required=True)
    p.add_argument("--tours", default="", help="generate-tour seeds, e.g. 1-20")
    p.add_argument("--scenario", action="append", default=[], help="a scenario file (repeatable)")
    p.add_argument("--tour-set", action="append", default=[],
                   help="generate-tour --set, e.g. length=700 or out_and_back=3")
    p.add_argument("--teach-set", action="append", default=[],
                   help="a scenario key for the teaching drive only, e.g. sim.lidar.rate_hz=1 "
                        "(a sparse teaching drive) or route.switch_points=[60,75]")
    p.add_argument("--seeds", default="1,2")
    p.add_argument("--starts", type=int, default=5, help="mid-route starts per route")
    p.add_argument("--no-reverse", action="store_true")
    p.add_argument("--out", required=True)
    p.add_argument("--jobs", type=int, default=2)
    a = p.parse_args()
    seeds = seeds_of(a.seeds)
    os.makedirs(a.out, exist_ok=True)
    routes = []  # (name, scenario)
    for t in seeds_of(a.tours):
        folder = os.path.join(a.out, f"tour_{t}")
        if not os.path.exists(os.path.join(folder, "scenario.yaml")):
            sets = [x for s in a.tour_set for x in ("--set", s)]
            run([a.retrace, "generate-tour", "--seed", str(t), "--out", folder] + sets)
        routes.append((f"tour_{t}", os.path.join(folder, "scenario.yaml")))
    for sc in a.scenario:
        routes.append((os.path.splitext(os.path.basename(sc))[0], sc))

    # The drives of every route: reversed, and --starts cut at random points (seeded by name).
    drives = []  # (route, drive name, drive scenario)
    for name, sc in routes:
        pts, _ = route_file_of(sc)
        folder = os.path.join(a.out, name)
        if not a.no_reverse:
            drives.append((name, "reversed", drive_scenario(
                sc, pts[::-1], os.path.join(folder, "reversed"), name + "_reversed",
                "the route driven backwards")))
        rng = random.Random(name)
        total = length(pts)
        for i in range(a.starts):
            s0 = rng.uniform(0.1, 0.8) * total
            drives.append((name, f"start_{s0:.0f}", drive_scenario(
                sc, cut(pts, s0), os.path.join(folder, f"start_{s0:.0f}"),
                f"{name}_start_{s0:.0f}", f"the route joined at {s0:.0f} m")))

    def teach(job):
        name, sc, seed = job
        out = os.path.join(a.out, name, f"teach_{seed}")
        if not os.path.exists(os.path.join(out, "consistent", "teach")):
            run([a.retrace, "teach", sc, "--mode", ",".join(MODES), "--seed", str(seed),
                 "--out", out] + [x for t in a.teach_set for x in ("--set", t)])

    def record(job):
        name, drive, sc, seed = job
        logs = os.path.join(os.path.dirname(sc), f"log_{seed}")
        if not os.path.exists(os.path.join(logs, "teach.mcap")):
            run([a.retrace, "teach", sc, "--seed", str(100 + seed), "--record-log", logs,
                 "--out", os.path.join(os.path.dirname(sc), f"drive_{seed}")])

    def localize(job):
        name, drive, sc, seed, mode = job
        folder = os.path.dirname(sc)
        out = os.path.join(folder, f"{mode}_{seed}")
        if not os.path.exists(os.path.join(out, "metrics.json")):
            run([a.retrace, "log-localize", os.path.join(folder, f"log_{seed}", "teach.mcap"),
                 "--teach", os.path.join(a.out, name, f"teach_{seed}", mode, "teach"),
                 "--seed", str(seed), "--out", out, "--no-figures"])
        with open(os.path.join(out, "metrics.json")) as f:
            return job, json.load(f)

    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        list(pool.map(teach, [(n, sc, s) for n, sc in routes for s in seeds]))
        list(pool.map(record, [(n, d, sc, s) for n, d, sc in drives for s in seeds]))
        results = list(pool.map(localize, [(n, d, sc, s, m) for n, d, sc in drives
                                           for s in seeds for m in MODES]))

    table = {}
    for (name, drive, _, seed, mode), m in results:
        h = m["localizer"]
        table[(name, drive, seed, mode)] = {
            "rms": m["localization_error_on_route_m"]["rms"],
            "max": m["localization_error_on_route_m"]["max"],
            "increase": h["max_error_increase_m"] or 0.0,
            "switches": m["switches"],
            "wrong_switches": h.get("wrong_switches", 0),
            "off_map_s": h.get("off_map_time_s", 0.0),
            "silent_s": h.get("silent_failure_time_s", float("nan")),
        }
    print("| route | drive | seed | mode | on-route RMS (m) | × consistent | max (m) "
          "| largest error increase (m) | switches (wrong) | off map (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    fails = {"ratio": [], "increase": [], "wrong": []}
    limit = {"partial": 3.0, "scan_matched": 1.5}
    for (name, drive, seed, mode), r in sorted(table.items()):
        ref = table[(name, drive, seed, "consistent")]["rms"]
        ratio = r["rms"] / ref if ref and r["rms"] is not None else float("nan")
        print(f"| {name} | {drive} | {seed} | {mode} | {r['rms']:.3f} | {ratio:.2f} "
              f"| {r['max']:.2f} | {r['increase']:.2f} | {r['switches']} ({r['wrong_switches']}) "
              f"| {r['off_map_s']:.0f} |")
        key = f"{name} {drive} seed {seed} {mode}"
        # The ratio's floor: a consistent map under 5 cm leaves no room for a ratio to mean much.
        if mode in limit and r["rms"] > limit[mode] * max(ref, 0.05):
            fails["ratio"].append(f"{key}: {ratio:.2f}")
        if r["increase"] > 1.0:
            fails["increase"].append(f"{key}: {r['increase']:.2f} m")
        if r["wrong_switches"]:
            fails["wrong"].append(f"{key}: {r['wrong_switches']}")
    n = len(table)
    print(f"\n{len(drives)} drives x {len(seeds)} seeds x {len(MODES)} modes = {n} runs")
    print(f"on-route RMS within 3x (partial) / 1.5x (scan-matched) of consistent: "
          f"{len(fails['ratio'])} failures {fails['ratio']}")
    print(f"single-update error increase over 1 m: {len(fails['increase'])} {fails['increase']}")
    print(f"wrong switches: {len(fails['wrong'])} {fails['wrong']}")
    with open(os.path.join(a.out, "study.json"), "w") as f:
        json.dump([dict(route=k[0], drive=k[1], seed=k[2], mode=k[3], **v)
                   for k, v in sorted(table.items())], f, indent=1)


if __name__ == "__main__":
    main()
