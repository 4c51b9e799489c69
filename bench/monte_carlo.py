#!/usr/bin/env python3
"""Monte Carlo tables the papers imply, each from one `uavplan batch` (mean and spread over
seeds, not one run):
  - P2 Table 1: the cellular ant colony on p2_city over 20 seeds per ant count (25-100 ants):
    finish time, route length, planning time, solved and verified, beside the paper's finish;
  - P4 Table 5: directional A* for uav3 of p4_rendezvous over the L x M grid (step 1.0-3.0
    cells, 3-6 directions), route length beside the paper's (one run per cell: the search is
    deterministic, so a seed changes nothing).

    python3 bench/monte_carlo.py [build/uavplan] [--seeds 20] [--jobs 0]
"""
import argparse
import csv
import pathlib
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
    a = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="uavplan-mc-") as tmp:
        p2_table(a.exe, pathlib.Path(tmp), a.seeds, a.jobs)
        p4_table5(a.exe, pathlib.Path(tmp), a.jobs)
    return 0


if __name__ == "__main__":
    sys.exit(main())
