#!/usr/bin/env python3
"""Plan a scenario from Python, verify it, and plot the routes (top view and height over time).

    PYTHONPATH=build/python python3 examples/plan_and_plot.py scenarios/demo.yaml out/routes.png
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import uavplan  # noqa: E402


def main(scenario_path, png_path, algorithm=None):
    sc = uavplan.Scenario.load(scenario_path)
    plan = uavplan.plan(sc, algorithm=algorithm)
    verdict = uavplan.verify(sc, plan)
    print(f"{sc.name}: {plan.status} with {plan.algorithm} in {plan.plan_ms:.1f} ms, "
          f"{'holds' if verdict.ok else f'{len(verdict.violations)} violations'}")
    for v in verdict.violations[:5]:
        print("  ", v["text"])

    fig, (top, side) = plt.subplots(1, 2, figsize=(12, 5))
    grey = dict(facecolor="0.8", edgecolor="0.5")
    for o in sc.obstacles:  # the top view of each obstacle
        if o["type"] in ("sphere", "cylinder"):
            top.add_patch(plt.Circle(o["center"][:2], o["radius"], **grey))
        elif o["type"] == "box":
            (x0, y0, _), (x1, y1, _) = o["min"], o["max"]
            top.add_patch(plt.Rectangle((x0, y0), x1 - x0, y1 - y0, **grey))
        else:
            top.add_patch(plt.Polygon(o["polygon"], **grey))
    (bx0, by0, _), (bx1, by1, _) = sc.bounds
    top.set_xlim(bx0, bx1)
    top.set_ylim(by0, by1)
    for u in plan.uavs:
        t = u.trajectory  # N x 4: t_s, x, y, z (a view of the plan, no copy)
        if len(t) == 0:
            continue
        line, = top.plot(t[:, 1], t[:, 2], label=f"{u.id} ({u.status}, {u.length_m:.0f} m)")
        top.plot(t[0, 1], t[0, 2], "o", color=line.get_color())
        top.plot(t[-1, 1], t[-1, 2], "s", color=line.get_color())
        side.plot(t[:, 0], t[:, 3], color=line.get_color(), label=u.id)
    top.set_aspect("equal")
    top.set_xlabel("x (m, east)")
    top.set_ylabel("y (m, north)")
    top.set_title(f"{sc.name}: {plan.algorithm}, {plan.status}")
    top.legend(fontsize=8)
    side.set_xlabel("t (s)")
    side.set_ylabel("z (m)")
    side.set_title("height over time")
    fig.tight_layout()
    fig.savefig(png_path, dpi=100)
    print(f"wrote {png_path}")
    return 0 if verdict.ok and plan.status == "solved" else 1


if __name__ == "__main__":
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2], sys.argv[3] if len(sys.argv) > 3 else None))
