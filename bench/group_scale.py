#!/usr/bin/env python3
"""A large group end to end: the whole `uavplan plan` command (load, plan, verify every pair's
separation, metrics, write) for N-UAV groups, against the 2 s target for 1024 UAVs.

The group is P3's scaled up: a square block of UAVs 1.5 m apart (0.1 m radius, 1 m/s), every
goal 65 m further along x and 4 m higher, two spheres of 2 m between the block and the goals
(which every UAV crosses), separation 0.5 m,
planner `apf`. Each size is run several times in turn; the table gives the median and the
95th percentile of the command's wall time and of its planning part (`--timing`), and the plan
file's size.

    python3 bench/group_scale.py [build/uavplan] [--sizes 64,256,1024] [--runs 7]
"""
import argparse
import json
import math
import pathlib
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
TARGET_1024_S = 2.0


def scenario(n):
    side = math.isqrt(n)
    if side * side != n:
        sys.exit(f"group_scale: {n} is not a square number of UAVs")
    spacing = 1.5
    span = (side - 1) * spacing
    gap_mid = 0.5 * (span + 65)
    lines = [
        "version: 1",
        f"name: group_{n}",
        "world:",
        f"  bounds: {{min: [-5, -5, 0], max: [{span + 75:.1f}, {span + 5:.1f}, 12]}}",
        "  obstacles:",
        # in the gap between the block's last column and the first goals, which every UAV crosses
        f"    - {{type: sphere, center: [{gap_mid - 3:.1f}, {span * 0.3:.1f}, 3], radius: 2}}",
        f"    - {{type: sphere, center: [{gap_mid + 3:.1f}, {span * 0.7:.1f}, 4], radius: 2}}",
        "uavs:",
    ]
    for j in range(side):
        for i in range(side):
            x, y = i * spacing, j * spacing
            lines.append(
                f"  - {{id: u{j * side + i}, start: [{x:.1f}, {y:.1f}, 1], goal: [{x + 65:.1f}, {y:.1f}, 5], "
                "radius: 0.1, speed: 1}")
    lines += ["mission: {type: group, separation: 0.5}", "planner: {algorithm: apf}", ""]
    return "\n".join(lines)


def pct(values, q):
    v = sorted(values)
    pos = q * (len(v) - 1)
    lo = math.floor(pos)
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (pos - lo) * (v[hi] - v[lo])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe", nargs="?", default=str(ROOT / "build/uavplan"))
    ap.add_argument("--sizes", default="64,256,1024")
    ap.add_argument("--runs", type=int, default=7)
    a = ap.parse_args()
    sizes = [int(s) for s in a.sizes.split(",")]
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="uavplan-group-scale-"))
    try:
        wall = {n: [] for n in sizes}
        plan = {n: [] for n in sizes}
        size_mb = {}
        status = {}
        for n in sizes:
            (tmp / f"g{n}.yaml").write_text(scenario(n))
        for _ in range(a.runs):  # sizes in turn, so a slow moment of the machine is shared
            for n in sizes:
                out = tmp / f"out{n}"
                t0 = time.perf_counter()
                r = subprocess.run([a.exe, "plan", str(tmp / f"g{n}.yaml"), "-o", str(out), "--timing"],
                                   stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
                wall[n].append(time.perf_counter() - t0)
                if r.returncode not in (0, 1):
                    sys.exit(f"group_scale: {n} UAVs: exit {r.returncode}: {r.stderr.strip()}")
                doc = json.loads((out / "plan.json").read_text())
                status[n] = doc["status"]
                plan[n].append(float(doc["timing"].get("plan_ms", 0.0)) / 1000.0)
                size_mb[n] = (out / "plan.json").stat().st_size / 1e6
                shutil.rmtree(out)
        print(f"whole `uavplan plan` command, {a.runs} runs per size (seconds)")
        print(f"{'uavs':>6} {'status':>8} {'median':>8} {'p95':>8} {'plan med':>9} {'plan p95':>9} "
              f"{'plan.json MB':>13} {'target':>8}")
        for n in sizes:
            target = f"{TARGET_1024_S:.1f}" if n == 1024 else "-"
            print(f"{n:>6} {status[n]:>8} {statistics.median(wall[n]):8.3f} {pct(wall[n], 0.95):8.3f} "
                  f"{statistics.median(plan[n]):9.3f} {pct(plan[n], 0.95):9.3f} {size_mb[n]:13.1f} {target:>8}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
