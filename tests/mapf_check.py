#!/usr/bin/env python3
"""An independent check of MAPF solution files in libMultiRobotPlanning's output format against
their instances: every agent starts at its start, ends at its goal, steps to a free 4-neighbour or
waits, no two agents share a cell at one time or swap cells in one step (an agent stays at its
goal after its schedule ends), and statistics.cost is the sum of the schedules' lengths.
Usage: mapf_check.py INSTANCE_DIR SOLUTION_DIR  (every solution file is checked)"""
import os
import sys

import yaml


def check(instance, solution):
    dims = instance["map"]["dimensions"]
    blocked = {tuple(c) for c in instance["map"].get("obstacles") or []}
    agents = instance["agents"]
    sched = solution["schedule"]
    paths = []
    for a in agents:
        steps = sched.get(a["name"])
        if not steps:
            return f"{a['name']}: no schedule"
        if [s["t"] for s in steps] != list(range(len(steps))):
            return f"{a['name']}: times are not 0, 1, 2, ..."
        cells = [(s["x"], s["y"]) for s in steps]
        if cells[0] != tuple(a["start"]) or cells[-1] != tuple(a["goal"]):
            return f"{a['name']}: does not go from its start to its goal"
        for t, c in enumerate(cells):
            if c in blocked or not (0 <= c[0] < dims[0] and 0 <= c[1] < dims[1]):
                return f"{a['name']}: on an obstacle or off the map at t={t}"
            if t and abs(c[0] - cells[t - 1][0]) + abs(c[1] - cells[t - 1][1]) > 1:
                return f"{a['name']}: jumps at t={t}"
        paths.append(cells)
    cost = sum(len(p) - 1 for p in paths)
    if solution["statistics"]["cost"] != cost:
        return f"statistics.cost {solution['statistics']['cost']} but the schedules sum to {cost}"
    end = max(len(p) for p in paths)
    at = lambda p, t: p[min(t, len(p) - 1)]
    for t in range(end):
        seen = {}
        for i, p in enumerate(paths):
            c = at(p, t)
            if c in seen:
                return f"{agents[seen[c]]['name']} and {agents[i]['name']} meet at {c} at t={t}"
            seen[c] = i
        for i, p in enumerate(paths):
            for j in range(i + 1, len(paths)):
                q = paths[j]
                if at(p, t) != at(p, t + 1) and at(p, t) == at(q, t + 1) and at(q, t) == at(p, t + 1):
                    return f"{agents[i]['name']} and {agents[j]['name']} swap at t={t}"
    return None


def main():
    instances, solutions = sys.argv[1], sys.argv[2]
    files = sorted(f for f in os.listdir(solutions) if f.endswith(".yaml"))
    if not files:
        print("mapf_check: no solution files")
        return 1
    bad = 0
    for f in files:
        with open(os.path.join(instances, f)) as a, open(os.path.join(solutions, f)) as b:
            why = check(yaml.safe_load(a), yaml.safe_load(b))
        if why:
            print(f"mapf_check: {f}: {why}")
            bad += 1
    print(f"mapf_check: {len(files) - bad}/{len(files)} solutions hold")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
