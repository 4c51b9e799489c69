#!/usr/bin/env python3
"""Monte Carlo tables the papers imply, each from one `uavplan batch` (mean and spread over
seeds, not one run):
  - P2 Table 1: the cellular ant colony on p2_city over 20 seeds per ant count (25-100 ants):
    finish time, route length, planning time, solved and verified, beside the paper's finish;
  - P3 scaling: the improved potential field and the traditional one on random obstacle fields
    (P3's block-to-block group, as `uavplan bench p3` builds them) of 9 to 400 UAVs, 10 fields
    (seeds) per size: solved UAVs, planning time, the least separation, the group score SC;
  - P4 Table 5: directional A* for uav3 of p4_rendezvous over the L x M grid (step 1.0-3.0
    cells, 3-6 directions), route length beside the paper's (one run per cell: the search is
    deterministic, so a seed changes nothing).

    python3 bench/monte_carlo.py [build/uavplan] [--seeds 20] [--jobs 0]
"""
import argparse
import csv
import json
import math
import pathlib
import random
import statistics
import subprocess
import sys
import tempfile

import yaml

ROOT = pathlib.Path(__file__).resolve().parents[1]
P2_PAPER_FINISH_S = {25: 869, 50: 778, 75: 683, 100: 591}
P4_PAPER_TABLE5_KM = [[55.5, 51.2, 51.2, 51.2], [54.9, 51.2, 51.2, 51.2], [51.2, 51.2, 51.2, 51.2],
                      [51.2, 50.4, 51.2, 49.5], [55.0, 49.2, 50.3, 49.2], [55.4, 54.9, 55.2, 55.5],
                      [52.8, 53.0, 51.1, 51.2], [54.7, 53.0, 52.8, 53.0], [54.7, 53.0, 53.0, 52.9],
                      [51.9, 53.1, 52.8, 52.7], [55.8, 52.9, 54.0, 50.1]]


def batch(exe, sweep_text, tmp, name, jobs):
    (tmp / f"{name}.yaml").write_text(sweep_text)
    out = tmp / name
    subprocess.run([exe, "batch", str(tmp / f"{name}.yaml"), "-o", str(out), "--jobs", str(jobs)], check=True,
                   stdout=subprocess.DEVNULL)
    with open(out / "results.csv") as f:
        rows = list(csv.DictReader(f))
    with open(out / "timings.csv") as f:
        ms = {r["run"]: float(r["plan_ms"]) for r in csv.DictReader(f)}
    for r in rows:
        r["plan_ms"] = ms[r["run"]]
    return rows


def mean_sd(values):
    if not values:
        return "-"
    if len(values) == 1:
        return f"{values[0]:.1f}"
    return f"{statistics.mean(values):.1f} ± {statistics.stdev(values):.1f}"


def p2_table(exe, tmp, seeds, jobs):
    rows = batch(exe, f"scenarios: [{ROOT}/scenarios/p2_city.yaml]\nplanners: [cellular_aco]\n"
                      f"params: {{ants: [25, 50, 75, 100]}}\nseeds: {seeds}\n", tmp, "p2", jobs)
    print(f"P2 Table 1 over {seeds} seeds per ant count (cellular_aco on p2_city; mean ± sd over the solved runs)")
    print(f"| ants | paper finish s | ours finish s | length m | plan ms | solved | verified |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    for ants, paper in P2_PAPER_FINISH_S.items():
        mine = [r for r in rows if r["params"] == f"ants={ants}"]
        ok = [r for r in mine if r["status"] == "solved"]
        print(f"| {ants} | {paper} | {mean_sd([float(r['flight_time_s']) for r in ok])} | "
              f"{mean_sd([float(r['length_m']) for r in ok])} | {mean_sd([r['plan_ms'] for r in mine])} | "
              f"{len(ok)}/{len(mine)} | {sum(r['verified'] == '1' for r in ok)}/{len(ok)} |")
    print("(the paper's finish times are one run each and include its hover at the task points)\n")


def p3_group(n, seed):
    """P3's scaling scene (bench/p3_runner.cpp, 2-D): n UAVs in a square block 1.5 m apart, goals
    in the same block at the upper right, random spheres of 0.1-0.4 m in between (none within the
    separation of a goal); separation 0.5 m, radius 0.1 m, 1 m/s."""
    rng = random.Random(seed)
    side_n = math.ceil(math.sqrt(n))
    spacing, separation, radius = 1.5, 0.5, 0.1
    side = spacing * side_n
    span = 3.0 * side + 10.0
    uavs = []
    for i in range(n):
        start = [spacing * (i % side_n), spacing * (i // side_n), 0.0]
        uavs.append({"id": f"u{i + 1}", "start": start, "goal": [start[0] + span - side, start[1] + span - side, 0.0],
                     "radius": radius, "speed": 1})
    spheres = []
    while len(spheres) < int(2 * side * side / 3) + 5:
        c = [rng.uniform(side + 2.0, span - 2.0), rng.uniform(side + 2.0, span - 2.0), 0.0]
        r = rng.uniform(0.1, 0.4)
        if all(math.dist(u["goal"], c) >= r + radius + separation for u in uavs):
            spheres.append({"type": "sphere", "center": c, "radius": r})
    return {"version": 1, "name": f"p3_field_{n}_{seed}",
            "world": {"bounds": {"min": [-2, -2, 0], "max": [span + side + 2, span + side + 2, 0]}, "obstacles": spheres},
            "uavs": uavs, "mission": {"type": "group", "separation": separation}, "planner": {"algorithm": "apf"}}


def p3_scaling(exe, tmp, seeds, jobs, sizes):
    fields = tmp / "p3_fields"
    fields.mkdir()
    for n in sizes:
        for seed in range(1, seeds + 1):
            (fields / f"n{n:04d}_s{seed:02d}.json").write_text(json.dumps(p3_group(n, seed)))
    rows = batch(exe, f"scenarios: [\"{fields}/*.json\"]\nplanners: [apf, apf_traditional]\n", tmp, "p3", jobs)
    print(f"P3 scaling over {seeds} random fields per size (2-D, block to block, separation 0.5 m; mean ± sd)")
    print("| uavs | planner | UAVs solved | plan ms | least separation m | group SC |")
    print("|---:|---|---:|---:|---:|---:|")
    for n in sizes:
        for planner in ("apf", "apf_traditional"):
            mine = [r for r in rows if r["planner"] == planner and f"/n{n:04d}_" in r["scenario"]]
            scores = []
            for r in mine:
                if r["plan_file"]:
                    plan = json.loads((tmp / "p3" / r["plan_file"]).read_text())
                    if plan["metrics"].get("p3_group_score") is not None:
                        scores.append(plan["metrics"]["p3_group_score"])
            seps = [float(r["min_separation_m"]) for r in mine if r["min_separation_m"]]
            solved = sum(int(r["uavs_solved"]) for r in mine)
            print(f"| {n} | {planner} | {solved}/{n * len(mine)} | {mean_sd([r['plan_ms'] for r in mine])} | "
                  f"{mean_sd(seps) if seps else '-'} | {mean_sd(scores) if scores else '-'} |")
    print("(the paper times one group of 9; a solved UAV's route is verified, separation included)\n")


def p4_table5(exe, tmp, jobs):
    sc = yaml.safe_load((ROOT / "scenarios/p4_rendezvous.yaml").read_text())
    sc["name"] = "p4_uav3"
    sc["uavs"] = [sc["uavs"][2]]
    sc["mission"] = {"type": "independent"}
    (tmp / "p4_uav3.yaml").write_text(yaml.safe_dump(sc, sort_keys=False))
    steps = [round(1.0 + 0.2 * i, 1) for i in range(11)]
    rows = batch(exe, f"scenarios: [{tmp}/p4_uav3.yaml]\nplanners: [directional_astar]\n"
                      f"params: {{step_cells: {steps}, directions: [3, 4, 5, 6]}}\n", tmp, "p4", jobs)
    print("P4 Table 5 for uav3 of p4_rendezvous: route length (km) by step L (cells) and directions M, ours | paper")
    print(f"{'L':>5} " + " ".join(f"{'M=' + str(m):>13}" for m in range(3, 7)))
    for li, step in enumerate(steps):
        cells = []
        for m in range(3, 7):
            r = next(x for x in rows if x["params"] == f"step_cells={step};directions={m}")
            ours = f"{float(r['length_m']) / 1000:6.1f}" if r["status"] == "solved" else f"{'-':>6}"
            cells.append(f"{ours}|{P4_PAPER_TABLE5_KM[li][m - 3]:5.1f}")
        print(f"{step:5.1f} " + " ".join(f"{c:>13}" for c in cells))
    failed = [r for r in rows if r["status"] != "solved"]
    if failed:
        print(f"-: not solved; the planner says (step {failed[0]['params']}): {failed[0]['message']}")
    solved = sum(r["status"] == "solved" for r in rows)
    print(f"{solved}/{len(rows)} cells solved and verified: {sum(r['verified'] == '1' for r in rows)}; "
          f"median plan {statistics.median(r['plan_ms'] for r in rows):.1f} ms\n")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe", nargs="?", default=str(ROOT / "build/uavplan"))
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--jobs", type=int, default=0)
    ap.add_argument("--p3-sizes", default="9,25,100,400")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="uavplan-mc-") as tmp:
        p2_table(a.exe, pathlib.Path(tmp), a.seeds, a.jobs)
        p3_scaling(a.exe, pathlib.Path(tmp), 10, a.jobs, [int(x) for x in a.p3_sizes.split(",")])
        p4_table5(a.exe, pathlib.Path(tmp), a.jobs)
    return 0


if __name__ == "__main__":
    sys.exit(main())
