#!/usr/bin/env python3
"""The Python module's call overhead: uavplan.plan() on the demo against the planning time the
CLI reports for the same scenario and seed (median of N each). Target: within 5 %.

    PYTHONPATH=build/python python3 bench/python_overhead.py [build/uavplan] [--repeat 15]
"""
import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import uavplan

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe", nargs="?", default=str(ROOT / "build/uavplan"))
    ap.add_argument("--repeat", type=int, default=15)
    a = ap.parse_args()
    path = str(ROOT / "scenarios/demo.yaml")
    rows = []
    for algorithm in ("astar", "rrt"):
        sc = uavplan.Scenario.load(path)
        py_ms, cli_ms, inner_ms, verify_ms = [], [], [], []
        with tempfile.TemporaryDirectory() as tmp:
            for _ in range(a.repeat):
                t0 = time.perf_counter()
                plan = uavplan.plan(sc, algorithm=algorithm)
                py_ms.append((time.perf_counter() - t0) * 1000.0)
                inner_ms.append(plan.plan_ms)
                t0 = time.perf_counter()
                uavplan.verify(sc, plan)
                verify_ms.append((time.perf_counter() - t0) * 1000.0)
                subprocess.run([a.exe, "plan", path, "-o", tmp, "--algorithm", algorithm, "--timing"], check=True,
                               stdout=subprocess.DEVNULL)
                cli_ms.append(json.loads(pathlib.Path(tmp, "plan.json").read_text())["timing"]["plan_ms"])
        py, cli = statistics.median(py_ms), statistics.median(cli_ms)
        inner, ver = statistics.median(inner_ms), statistics.median(verify_ms)
        rows.append((algorithm, cli, py, (py - cli) / cli * 100.0, py - inner - ver, plan.status))
    print(f"uavplan.plan() on the demo against the CLI's plan time (median of {a.repeat}); "
          "plan() also verifies, as the CLI does after its plan time")
    print(f"{'planner':<8} {'cli_plan_ms':>12} {'python_ms':>10} {'diff_%':>8} {'call_overhead_ms':>17}  status")
    for alg, cli, py, pct, over, status in rows:
        print(f"{alg:<8} {cli:>12.2f} {py:>10.2f} {pct:>8.1f} {over:>17.3f}  {status}")
    print("call_overhead_ms: plan()'s wall time less the library's planning and verifying (the binding itself).")
    print("target: within 5 % of the CLI's plan time (a sub-millisecond plan is dominated by the verification)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
