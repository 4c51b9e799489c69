"""The Python module against the command line: same plans, same bytes, same messages."""
import json
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import uavplan
import ompl_log


@pytest.fixture(scope="module")
def demo(root):
    return uavplan.Scenario.load(str(root / "scenarios/demo.yaml"))


@pytest.fixture(scope="module")
def demo_plan(demo):
    return uavplan.plan(demo)


def test_plan_is_the_clis_plan_byte_for_byte(root, exe, tmp_path, demo, demo_plan):
    subprocess.run([exe, "plan", str(root / "scenarios/demo.yaml"), "-o", str(tmp_path)], check=True,
                   stdout=subprocess.DEVNULL)
    assert demo_plan.status == "solved"
    assert demo_plan.to_json() == (tmp_path / "plan.json").read_text()
    demo_plan.save(str(tmp_path / "again.json"))
    assert (tmp_path / "again.json").read_bytes() == (tmp_path / "plan.json").read_bytes()
    loaded = uavplan.Plan.load(str(tmp_path / "plan.json"))
    assert loaded.to_json() == demo_plan.to_json()


def test_trajectory_is_a_read_only_view_with_t_x_y_z(root, demo_plan):
    u = demo_plan.uavs[0]
    t = u.trajectory
    assert t.shape[1] == 4 and t.shape[0] > 10 and t.dtype == np.float64
    assert not t.flags["OWNDATA"] and not t.flags["WRITEABLE"]
    assert np.all(np.diff(t[:, 0]) >= 0)
    row = json.loads(demo_plan.to_json())["uavs"][0]["trajectory"][-1]
    assert list(t[-1]) == pytest.approx([row["t"], *row["p"]] if isinstance(row, dict) else row)
    # The view keeps the plan alive.
    p = uavplan.plan(uavplan.Scenario.load(str(root / "scenarios/demo.yaml")))
    view = p.uavs[1].trajectory
    first = view.copy()
    del p
    assert np.array_equal(view, first)
    assert u.metrics["length_m"] == pytest.approx(u.length_m)
    assert demo_plan.uav(u.id).id == u.id
    with pytest.raises(KeyError):
        demo_plan.uav("nobody")


def test_seed_algorithm_and_params_as_on_the_command_line(root, exe, tmp_path, demo):
    p = uavplan.plan(demo, algorithm="rrt", seed=5, params={"goal_bias": 0.2})
    subprocess.run([exe, "plan", str(root / "scenarios/demo.yaml"), "-o", str(tmp_path), "--algorithm", "rrt",
                    "--seed", "5", "--set", "goal_bias=0.2"], stdout=subprocess.DEVNULL)
    assert p.algorithm == "rrt" and p.seed == 5
    assert p.to_json() == (tmp_path / "plan.json").read_text()


def test_verify_finds_a_route_through_a_building(root, tmp_path, demo, demo_plan):
    assert uavplan.verify(demo, demo_plan).ok
    d = json.loads(demo_plan.to_json())
    traj = d["uavs"][0]["trajectory"]
    mid = traj[len(traj) // 2]
    if isinstance(mid, dict):
        mid["p"] = [230.0, 230.0, 30.0]
    else:
        mid[1:4] = [230.0, 230.0, 30.0]  # inside tower_a
    (tmp_path / "bad.json").write_text(json.dumps(d))
    verdict = uavplan.verify(demo, uavplan.Plan.load(str(tmp_path / "bad.json")))
    assert not verdict.ok and not verdict
    kinds = {v["kind"] for v in verdict.violations}
    assert "obstacle" in kinds
    assert all(v["text"] for v in verdict.violations)


def test_from_dict_plans_a_scenario_written_in_python():
    sc = uavplan.Scenario.from_dict({
        "version": 1, "name": "py",
        "world": {"bounds": {"min": [0, 0, 0], "max": [200, 200, 50]},
                  "obstacles": [{"type": "box", "min": [80, 0, 0], "max": [120, 150, 50]}]},
        "uavs": [{"id": "a", "start": [20, 20, 10], "goal": [180, 20, 10], "speed": 5}],
        "planner": {"algorithm": "astar"}})
    p = uavplan.plan(sc, seed=3)
    assert p.status == "solved" and uavplan.verify(sc, p).ok
    t = p.uavs[0].trajectory
    assert t[:, 3].max() <= 50
    assert t[:, 2].max() > 150  # around the wall's end (it stands to the ceiling)
    assert sc.obstacles == [{"type": "box", "min": [80.0, 0.0, 0.0], "max": [120.0, 150.0, 50.0]}]
    assert sc.bounds == [[0, 0, 0], [200, 200, 50]]
    assert p.reason == "none" and p.uavs[0].reason == "none"
    # Walled in on every side: failed, and the plan says why as the UAV does.
    walled = uavplan.Scenario.from_dict({
        "version": 1, "name": "walled",
        "world": {"bounds": {"min": [0, 0, 0], "max": [200, 200, 50]},
                  "obstacles": [{"type": "box", "min": [80, 0, 0], "max": [120, 200, 50]}]},
        "uavs": [{"id": "a", "start": [20, 20, 10], "goal": [180, 20, 10], "speed": 5}],
        "planner": {"algorithm": "astar"}})
    f = uavplan.plan(walled, seed=3)
    assert f.status == "failed" and f.reason == f.uavs[0].reason == "no_route", (f.reason, f.message)
    # A dict's error names the key path, not a line of text the user never wrote.
    with pytest.raises(uavplan.InputError) as e:
        uavplan.Scenario.from_dict({"version": 1, "world": {"bounds": {"min": [0, 0, 0], "max": [9, 9, 9]}},
                                    "uavs": [{"id": "a", "start": [1, 1, 1], "goal": [2, 2, "x"]}]})
    assert str(e.value).startswith("Scenario.from_dict: uavs[0].goal[2]: expected a number"), str(e.value)


def test_errors_carry_the_clis_one_line_message(root, exe, tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text((root / "scenarios/demo.yaml").read_text().replace("speed:", "speeed:", 1))
    cli = subprocess.run([exe, "plan", str(bad), "-o", str(tmp_path / "o")], capture_output=True, text=True)
    assert cli.returncode == 2
    with pytest.raises(uavplan.InputError) as e:
        uavplan.Scenario.load(str(bad))
    assert str(e.value) == cli.stderr.strip()
    assert isinstance(e.value, ValueError)
    with pytest.raises(ValueError, match="planner.params.cell_m"):
        uavplan.plan(uavplan.Scenario.load(str(root / "scenarios/demo.yaml")), params={"cell_m": "wide"})
    with pytest.raises(ValueError, match="unknown planner"):
        uavplan.plan(uavplan.Scenario.load(str(root / "scenarios/demo.yaml")), algorithm="nosuch")


def expect_the_clis_files(exe, scenario, formats, written, tmp_path):
    """The files Python wrote under tmp_path/py are byte for byte those of `plan --export`."""
    subprocess.run([exe, "plan", str(scenario), "-o", str(tmp_path / "cli"), "--export", formats],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    for path in written:
        name = path.rsplit("/", 1)[1]
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name


def test_export_writes_the_clis_files(root, exe, tmp_path, demo, demo_plan):
    written = uavplan.export(demo, demo_plan, ["qgc", "csv"], str(tmp_path / "py"))
    assert len(written) == 7  # three .plan, three .csv and schedule.json, as the command line writes them
    expect_the_clis_files(exe, root / "scenarios/demo.yaml", "qgc,csv", written, tmp_path)
    qgc = json.loads((tmp_path / "py" / "u1.plan").read_text())
    assert qgc["fileType"] == "Plan" and len(qgc["mission"]["items"]) > 2
    with pytest.raises(ValueError):
        uavplan.export(demo, demo_plan, ["shapefile"], str(tmp_path / "x"))


def test_a_formation_mission_exports_as_the_cli_does(root, exe, tmp_path):
    # Fixed wing by default (it flies from a runway), the same bytes as the command line.
    sc = uavplan.Scenario.load(str(root / "scenarios/p5_mission.yaml"))
    plan = uavplan.plan(sc)
    written = uavplan.export(sc, plan, ["qgc"], str(tmp_path / "py"))
    assert len(written) == 5
    expect_the_clis_files(exe, root / "scenarios/p5_mission.yaml", "qgc", written, tmp_path)
    assert json.loads((tmp_path / "py" / "u1.plan").read_text())["mission"]["vehicleType"] == 1


def test_planners_lists_names_and_parameters(root, exe):
    names = [p["name"] for p in uavplan.planners()]
    info = subprocess.run([exe, "info", str(root / "scenarios/demo.yaml")], capture_output=True, text=True).stdout
    assert info.split("planners for this mission:")[1].split() == names  # an independent mission takes any
    group = subprocess.run([exe, "info", str(root / "scenarios/p3_group9.yaml")], capture_output=True, text=True).stdout
    assert group.split("planners for this mission:")[1].split() == ["apf", "apf_traditional"]
    rrt = next(p for p in uavplan.planners() if p["name"] == "rrt")
    assert "goal_bias" in rrt["params"] and rrt["description"]
    assert rrt["params"]["goal_bias"] == "0.5" and "goal" in rrt["param_docs"]["goal_bias"]
    # The same declarations as the command line's table.
    listed = subprocess.run([exe, "info", "--planners"], capture_output=True, text=True, check=True).stdout
    assert "    goal_bias (number [0, 1]; 0.5): " + rrt["param_docs"]["goal_bias"] in listed


def test_the_gil_is_released_while_planning(demo):
    ticks = 0
    stop = False

    def count():
        nonlocal ticks
        while not stop:
            ticks += 1
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    time.sleep(0.01)
    before = ticks
    t0 = time.perf_counter()
    uavplan.plan(demo, algorithm="astar")
    elapsed = time.perf_counter() - t0
    during = ticks - before
    stop = True
    t.join()
    # With the GIL held the counter would stand still for the whole plan.
    assert elapsed > 0.05 and during > 5, (elapsed, during)


def test_batch_ompl_log_reads_back_with_a_parser_from_the_format(root, exe, tmp_path):
    sweep = tmp_path / "sweep.yaml"
    sweep.write_text(f"name: py ompl\nscenarios: [{root}/scenarios/demo.yaml]\n"
                     "planners: [astar, {name: rrt, params: {goal_bias: [0.05, 0.3]}}]\nseeds: 4\n")
    subprocess.run([exe, "batch", str(sweep), "-o", str(tmp_path / "out"), "--ompl-log", str(tmp_path / "b.log")],
                   check=True, stdout=subprocess.DEVNULL)
    log = ompl_log.parse((tmp_path / "b.log").read_text())
    assert log["experiment"] == "py_ompl" and log["runs_per_planner"] == 4
    assert [p["name"] for p in log["planners"]] == ["astar", "rrt[goal_bias=0.05]", "rrt[goal_bias=0.3]"]
    rows = (tmp_path / "out/results.csv").read_text().splitlines()[1:]
    assert sum(len(p["runs"]) for p in log["planners"]) == len(rows) == 12
    for p in log["planners"]:
        assert ("time", "REAL") in p["properties"] and ("solved", "BOOLEAN") in p["properties"]
        for run in p["runs"]:
            assert run["time"] >= 0 and isinstance(run["solved"], bool)
            if run["solved"]:
                assert run["solution length"] > 0 and run["correct solution"] is True
    assert log["planners"][1]["common"] == {"goal_bias": "0.05"}
    # The parser is strict: a count that does not match is an error.
    broken = (tmp_path / "b.log").read_text().replace("4 runs\n", "5 runs\n", 1)
    with pytest.raises(ompl_log.LogError):
        ompl_log.parse(broken)


def test_the_example_plans_verifies_and_plots(root, tmp_path):
    import os
    env = dict(os.environ)
    out = subprocess.run([os.sys.executable, str(root / "examples/plan_and_plot.py"), str(root / "scenarios/demo.yaml"),
                          str(tmp_path / "routes.png")], capture_output=True, text=True, env=env)
    assert out.returncode == 0, out.stderr
    assert "demo: solved with astar" in out.stdout and "holds" in out.stdout
    png = (tmp_path / "routes.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 20000


def test_ctrl_c_inside_plan_raises_keyboard_interrupt_at_once(root):
    """Ctrl-C while uavplan.plan() runs stops the plan and raises within half a second."""
    import signal
    import sys
    code = (
        "import time, uavplan\n"
        f"sc = uavplan.Scenario.load({str(root / 'scenarios/p2_city.yaml')!r})\n"
        "print('ready', flush=True)\n"
        "try:\n"
        "    uavplan.plan(sc, algorithm='cellular_aco', params={'iterations': 100000})\n"
        "    print('finished', flush=True)\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', flush=True)\n")
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "ready"
    time.sleep(1.0)
    sent = time.monotonic()
    proc.send_signal(signal.SIGINT)
    line = proc.stdout.readline().strip()
    took = time.monotonic() - sent
    proc.wait(timeout=30)
    assert line == "interrupted"
    assert took < 0.5, f"KeyboardInterrupt after {took:.2f} s"


def test_hostile_elevation_models_are_input_errors(tmp_path):
    # The module reads through the same locked-down GDAL: a VRT source pointing into the process
    # (MEM:::, once a SIGSEGV) or a raw band on /proc/self/environ is a clear error, not a crash.
    (tmp_path / "src.asc").write_text("ncols 1\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n5\n")
    sources = {
        "mem": '<SimpleSource><SourceFilename relativeToVRT="1">MEM:::DATAPOINTER=0x1000,PIXELS=4,LINES=4'
               '</SourceFilename></SimpleSource>',
        "raw": '</VRTRasterBand><VRTRasterBand dataType="Byte" band="2" subClass="VRTRawRasterBand">'
               '<SourceFilename relativetoVRT="0">/proc/self/environ</SourceFilename>',
    }
    for name, inside in sources.items():
        (tmp_path / f"{name}.vrt").write_text(
            '<VRTDataset rasterXSize="4" rasterYSize="4"><SRS>EPSG:21781</SRS>'
            '<GeoTransform>780000, 100, 0, 186400, 0, -100</GeoTransform>'
            f'<VRTRasterBand dataType="Float32" band="1">{inside}</VRTRasterBand></VRTDataset>')
        (tmp_path / f"{name}.yaml").write_text(
            "version: 1\norigin: {lat: 46.80256, lon: 9.79959, alt: 0}\n"
            f"world:\n  bounds: {{min: [-100, -100, 0], max: [100, 100, 300]}}\n  terrain: {{file: {name}.vrt}}\n"
            "uavs:\n  - {id: a, start: [-50, -50, 200], goal: [50, 50, 200]}\n")
        with pytest.raises(uavplan.InputError, match=f"{name}.vrt"):
            uavplan.Scenario.load(str(tmp_path / f"{name}.yaml"))


def test_plan_and_export_follow_the_command_lines_rules(root, exe, tmp_path, demo):
    # One entry point: the same memory cap gives the same refusal, word for word.
    cli = subprocess.run([exe, "plan", str(root / "scenarios/demo.yaml"), "-o", str(tmp_path / "cli"),
                          "--max-memory", "1K"], capture_output=True, text=True)
    assert cli.returncode == 2
    with pytest.raises(ValueError) as e:
        uavplan.plan(demo, max_memory_bytes=1024)
    assert str(e.value) in cli.stderr, (str(e.value), cli.stderr)
    # The export rules are the library's: a runway mission is not exported as a multirotor.
    p5 = uavplan.Scenario.load(str(root / "scenarios/p5_mission.yaml"))
    cli = subprocess.run([exe, "plan", str(root / "scenarios/p5_mission.yaml"), "-o", str(tmp_path / "p5"),
                          "--export", "qgc", "--vehicle", "multirotor"], capture_output=True, text=True)
    assert cli.returncode == 2
    with pytest.raises(uavplan.ExportError) as e:
        uavplan.export(p5, uavplan.plan(p5), ["qgc"], str(tmp_path / "py"), vehicle="multirotor")
    assert str(e.value) in cli.stderr, (str(e.value), cli.stderr)
    assert not (tmp_path / "py").exists() or not any((tmp_path / "py").iterdir())


def test_without_numpy_the_import_says_which_python_it_needs():
    # numpy made unimportable, as under a python3 that is not Debian's
    code = "import sys; sys.modules['numpy'] = None; import uavplan"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode != 0
    assert "uavplan's Python module needs numpy, and " + sys.executable + " has none" in r.stderr
    assert "Debian's python3 " in r.stderr and "python3-numpy" in r.stderr


def test_from_dict_names_every_typo_and_hints_are_kept():
    scenario = {
        "version": 1, "name": "py",
        "world": {"bounds": {"min": [0, 0, 0], "max": [200, 200, 50]}},
        "uavs": [{"id": "a", "start": [20, 20, 10], "goal": [180, 20, 10], "sped": 5, "max_turn_deg": 1.57}],
        "mission": {"type": "independent", "seperation": 5}}
    with pytest.raises(ValueError) as e:
        uavplan.Scenario.from_dict(scenario)
    lines = str(e.value).splitlines()
    assert lines == ["Scenario.from_dict: uavs[0].sped: unknown key 'sped' (did you mean 'speed'?)",
                     "Scenario.from_dict: mission.seperation: unknown key 'seperation' (did you mean 'separation'?)"]
    del scenario["uavs"][0]["sped"], scenario["mission"]["seperation"]
    sc = uavplan.Scenario.from_dict(scenario)
    assert len(sc.hints) == 1 and "uavs[0].max_turn_deg: hint: a turn limit of 1.57 degrees" in sc.hints[0]
