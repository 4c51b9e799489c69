#!/usr/bin/env python3
"""uavplan batch at scale: 10,000 runs of small scenarios (a P3 group of 9, a P4 Table-3 search,
the demo with RRT) on 1 and 2 cores; the speed-up and the batch's cost per run beyond planning
(loading, verifying, writing the plan and the journal, process start and sweep check spread
over the runs). The results must be the same bytes on 1 and 2 cores.

    python3 bench/batch_scaling.py [build/uavplan] [--runs 10000]
"""
import argparse
import csv
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe", nargs="?", default=str(ROOT / "build/uavplan"))
    ap.add_argument("--runs", type=int, default=10000)
    a = ap.parse_args()
    n = a.runs
    # Shares of the runs: P3 group 45 %, the demo with RRT 45 %, P4 Table 3 10 % (it plans 50x longer).
    p3, demo = int(n * 0.45), int(n * 0.45)
    p4 = n - p3 - demo
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="uavplan-batch-bench-"))
    try:
        sweeps = {
            "p3": f"scenarios: [{ROOT}/scenarios/p3_group9.yaml]\nseeds: {p3}\n",
            "demo": f"scenarios: [{ROOT}/scenarios/demo.yaml]\nplanners: [rrt]\nseeds: {demo}\n",
            "p4": f"scenarios: [{ROOT}/scenarios/p4_table3.yaml]\nseeds: {p4}\n",
        }
        rows = []
        results = {}
        for jobs in (1, 2):
            wall = 0.0
            plan_ms = 0.0
            wall_ms = 0.0
            runs = 0
            for name, text in sweeps.items():
                (tmp / f"{name}.yaml").write_text(text)
                out = tmp / f"{name}-j{jobs}"
                t0 = time.perf_counter()
                subprocess.run([a.exe, "batch", str(tmp / f"{name}.yaml"), "-o", str(out), "--jobs", str(jobs)],
                               check=True, stdout=subprocess.DEVNULL)
                wall += time.perf_counter() - t0
                with open(out / "timings.csv") as f:
                    for r in csv.DictReader(f):
                        plan_ms += float(r["plan_ms"])
                        wall_ms += float(r["wall_ms"])
                        runs += 1
                results[(name, jobs)] = (out / "results.csv").read_bytes()
            rows.append((jobs, runs, wall, plan_ms / 1000.0, wall_ms / 1000.0))
        same = all(results[(k, 1)] == results[(k, 2)] for k in sweeps)
        print(f"uavplan batch: {n} runs ({p3} P3 group of 9 with apf, {demo} demo with rrt, {p4} P4 Table 3 with "
              "directional_astar), planned and verified, plans and journal written")
        print(f"{'jobs':>4} {'runs':>6} {'wall_s':>8} {'plan_s':>8} {'runs/s':>8} {'speed-up':>9} "
              f"{'overhead_ms/run':>16} {'verify+json':>12} {'batch':>8}")
        base = rows[0][2]
        for jobs, runs, wall, plan_s, run_s in rows:
            # The cost per run beyond planning: wall time x cores busy, less the planning itself;
            # of it, verifying the plan and writing its JSON (inside the run), and the rest (the
            # plan file, the journal, three process starts and sweep checks spread over the runs).
            overhead = (wall * jobs - plan_s) / runs * 1000.0
            verify_json = (run_s - plan_s) / runs * 1000.0
            print(f"{jobs:>4} {runs:>6} {wall:>8.2f} {plan_s:>8.2f} {runs / wall:>8.1f} {base / wall:>9.2f} "
                  f"{overhead:>16.3f} {verify_json:>12.3f} {overhead - verify_json:>8.3f}")
        print(f"results.csv on 1 and 2 jobs: {'the same bytes' if same else 'DIFFER'}; target: speed-up near 2, "
              "overhead under 1 ms per run")
        return 0 if same else 1
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
