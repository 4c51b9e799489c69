"""A reader of OMPL's benchmark log format, written from the grammar in OMPL's documentation
("The benchmark logfile format"), to check that `uavplan batch --ompl-log` writes what
ompl_benchmark_statistics.py and Planner Arena read."""


class LogError(ValueError):
    pass


class _Lines:
    def __init__(self, text):
        if not text.endswith("\n"):
            raise LogError("the log does not end with a newline")
        self.lines = text[:-1].split("\n")
        self.i = 0

    def next(self):
        if self.i >= len(self.lines):
            raise LogError("the log ends early")
        self.i += 1
        return self.lines[self.i - 1]

    def peek(self):
        return self.lines[self.i] if self.i < len(self.lines) else None

    def count(self, suffix):
        line = self.next()
        if not line.endswith(suffix):
            raise LogError(f"line {self.i}: expected '<int>{suffix}', got {line!r}")
        return int(line[: -len(suffix)])


def _num(s):
    if s in ("", "inf", "nan"):
        return None if s == "" else float(s)
    return float(s)


def parse(text):
    r = _Lines(text)
    log = {}
    line = r.next()
    if " version " in line:  # optional: library_name " version " version_number
        log["library"], log["version"] = line.split(" version ", 1)
        line = r.next()
    if not line.startswith("Experiment "):
        raise LogError(f"line {r.i}: expected 'Experiment <name>'")
    log["experiment"] = line[len("Experiment "):]
    if any(c.isspace() for c in log["experiment"]):
        raise LogError("the experiment name has whitespace")
    log["experiment_properties"] = {}
    if r.peek().endswith(" experiment properties"):
        for _ in range(r.count(" experiment properties")):
            name_type, value = r.next().split("=", 1)
            log["experiment_properties"][name_type.strip()] = _num(value.strip())
    line = r.next()
    if not line.startswith("Running on "):
        raise LogError(f"line {r.i}: expected 'Running on <host>'")
    log["host"] = line[len("Running on "):]
    line = r.next()
    if not line.startswith("Starting at "):
        raise LogError(f"line {r.i}: expected 'Starting at <date>'")
    log["date"] = line[len("Starting at "):]

    def multi_line():
        if r.next() != "<<<|":
            raise LogError(f"line {r.i}: expected '<<<|'")
        out = []
        while (s := r.next()) != "|>>>":
            out.append(s)
        return "\n".join(out)

    log["setup"] = multi_line()
    if r.peek() == "<<<|":
        log["cpuinfo"] = multi_line()
    log["seed"] = r.count(" is the random seed")
    line = r.next()
    if not line.endswith(" seconds per run"):
        raise LogError(f"line {r.i}: expected '<float> seconds per run'")
    log["time_limit"] = float(line[: -len(" seconds per run")])
    line = r.next()
    if not line.endswith(" MB per run"):
        raise LogError(f"line {r.i}: expected '<float> MB per run'")
    log["memory_limit"] = float(line[: -len(" MB per run")])
    if r.peek().endswith(" runs per planner"):
        log["runs_per_planner"] = r.count(" runs per planner")
    line = r.next()
    if not line.endswith(" seconds spent to collect the data"):
        raise LogError(f"line {r.i}: expected '<float> seconds spent to collect the data'")
    log["total_time"] = float(line[: -len(" seconds spent to collect the data")])
    if r.peek().endswith(" enum types") or r.peek().endswith(" enum type"):
        for _ in range(int(r.next().split()[0])):
            r.next()
    planners = []
    for _ in range(r.count(" planners")):
        p = {"name": r.next(), "common": {}, "properties": [], "runs": []}
        if not p["name"] or any(c.isspace() for c in p["name"]):
            raise LogError(f"line {r.i}: a planner name without whitespace expected")
        for _ in range(r.count(" common properties")):
            name, value = r.next().split(" = ", 1)
            p["common"][name] = value
        for _ in range(r.count(" properties for each run")):
            name, _, ptype = r.next().rpartition(" ")
            if ptype not in ("BOOLEAN", "INTEGER", "REAL"):
                raise LogError(f"line {r.i}: property type {ptype!r}")
            p["properties"].append((name, ptype))
        for _ in range(r.count(" runs")):
            line = r.next()
            if not line.endswith("; "):
                raise LogError(f"line {r.i}: a run measurement ends with '; '")
            values = line[:-2].split("; ")
            if len(values) != len(p["properties"]):
                raise LogError(f"line {r.i}: {len(values)} values for {len(p['properties'])} properties")
            run = {}
            for (name, ptype), v in zip(p["properties"], values):
                if v == "":
                    run[name] = None
                elif ptype == "INTEGER":
                    run[name] = int(v)
                elif ptype == "BOOLEAN":
                    if v not in ("0", "1"):
                        raise LogError(f"line {r.i}: boolean {v!r}")
                    run[name] = v == "1"
                else:
                    run[name] = float(v)
            p["runs"].append(run)
        if r.next() != ".":
            raise LogError(f"line {r.i}: expected '.' after the planner's runs")
        planners.append(p)
    if r.peek() is not None:
        raise LogError(f"line {r.i + 1}: text after the last planner")
    log["planners"] = planners
    return log
