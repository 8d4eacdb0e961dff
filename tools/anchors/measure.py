"""Times MuJoCo and Pinocchio on the reference scenes now, with scenes.py beside this file, and writes the figures
the report compares our costs with (docs/benchmarks.md, "Anchors measured in the same run").

Each measurement runs REPEATS times in a fresh process; a figure keeps every repeat, the minimum (the run least
disturbed by other work on the machine) and the spread max/min - 1. Errors are MuJoCo's (deterministic).
Usage: python measure.py --output FILE [--repeats N] [--only NAME,...]
"""
import argparse
import datetime
import json
import os
import shlex
import subprocess
import sys
import tempfile

CHAIN_LINKS = (1, 2, 4, 8, 16, 32, 64)
ROBOTS = ("ur5", "solo12")
REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(REPO, "tools", "anchors", "scenes.py")


def load_average():
    with open("/proc/loadavg") as f:
        return [float(x) for x in f.read().split()[:3]]


def measured(name, python, workdir):
    """Runs `scenes.py name` in a fresh process: its command and the figures it wrote."""
    output = os.path.join(workdir, f"{name}.json")
    command = [python, SCENES, name, output]
    subprocess.run(command, cwd=workdir, check=True)
    with open(output) as f:
        return command, json.load(f)


SINGLE_BODIES = ("scene1", "scene2", "scene3a", "scene4-circle")


def single_bodies(python, workdir):
    """Scenes 1, 2, 3a and 4 (circle): MuJoCo RK4 s per step at dt = 1e-3; its errors at T at dt = 1e-2, 1e-3, 1e-4
    (rad; scene 4, m)."""
    command, runs = measured("single_bodies", python, workdir)
    for key in SINGLE_BODIES:
        errors = [{"dt": dt, "error": runs[f"{key}_{dt:g}"]["error"]} for dt in (1e-2, 1e-3, 1e-4)]
        seconds = runs[f"{key}_0.001"]["seconds_per_step"]
        yield command, key, "MuJoCo 4.0 RK4 step at dt = 1e-3", 1e-3, seconds, errors


def m1(python, workdir):
    """M1: MuJoCo RK4 s per step at dt = 1e-3; its end orientation errors (rad) at dt = 1e-2, 1e-3, 1e-4."""
    command, steps = measured("m1", python, workdir)
    errors = [{"dt": float(dt), "error": steps[dt]["orientation_error_rad"]} for dt in ("0.01", "0.001", "0.0001")]
    yield command, "m1", "MuJoCo 4.0 RK4 step at dt = 1e-3", 1e-3, steps["0.001"]["seconds_per_step"], errors


def m2(python, workdir):
    """M2: MuJoCo RK4 s per step at dt = 1e-3; its coupler centre-of-mass error at T (m)."""
    command, steps = measured("m2", python, workdir)
    at = steps["0.001"]
    errors = [{"dt": 1e-3, "error": at["coupler_centre_error_m"]}]
    yield command, "m2", "MuJoCo 4.0 RK4 step at dt = 1e-3, loop by a soft equality", 1e-3, at["seconds_per_step"], errors


def m3(python, workdir):
    """M3: MuJoCo RK4 s per step at dt = 1e-3 for the ball and the hinge chains of N links."""
    command, chains = measured("m3", python, workdir)
    for joint in ("ball", "hinge"):
        for n in CHAIN_LINKS:
            seconds = chains[f"{joint}_{n}"]["seconds_per_step"]
            yield command, f"m3-{joint}-{n}", f"MuJoCo 4.0 RK4 step at dt = 1e-3, {joint} joints", 1e-3, seconds, None


def m3_pinocchio(python, workdir):
    """M3: Pinocchio's ABA on the ball chain, s per dynamics evaluation (no step size)."""
    command, chains = measured("m3_pinocchio", python, workdir)
    for n in CHAIN_LINKS:
        seconds = chains[str(n)]["seconds_per_evaluation"]
        yield command, f"m3-pinocchio-{n}", "Pinocchio 4.1 ABA evaluation, ball joints", None, seconds, None


def robots(python, workdir):
    """UR5 and Solo-12: MuJoCo RK4 s per step at dt = 1e-3 and 1e-4; the largest joint error (rad) at each."""
    command, runs = measured("robots", python, workdir)
    for robot in ROBOTS:
        # The scripts' keys for the steps, and the report's (Rust's `{:.0e}`, not Python's "1e-03").
        for dt, step in (("0.001", "1e-3"), ("0.0001", "1e-4")):
            run = runs[f"{robot}_{dt}"]
            errors = [{"dt": float(dt), "error": run["joint_position_error"]}]
            key = f"{robot}-dt{step}"
            yield command, key, f"MuJoCo 4.0 RK4 step at dt = {step}", float(dt), run["seconds_per_step"], errors


MEASUREMENTS = (single_bodies, m1, m2, m3, m3_pinocchio, robots)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", required=True)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--only", default="", help="comma-separated measurement names (m1, m2, m3, ...)")
    args = parser.parse_args()
    chosen = [m for m in MEASUREMENTS if not args.only or m.__name__ in args.only.split(",")]
    started = datetime.datetime.now(datetime.timezone.utc)
    load_before = load_average()
    figures = {}
    for measurement in chosen:
        for repeat in range(args.repeats):
            print(f"{measurement.__name__}: repeat {repeat + 1} of {args.repeats}", file=sys.stderr, flush=True)
            with tempfile.TemporaryDirectory() as workdir:
                for command, key, what, dt, seconds, errors in measurement(sys.executable, workdir):
                    figure = figures.setdefault(key, {"key": key, "what": what, "dt": dt, "repeats": []})
                    # The command as run from the repository with its scratch folder named, to be run again by hand.
                    shown = ["python", *(c.replace(workdir, "OUTDIR").replace(REPO + os.sep, "") for c in command[1:])]
                    figure["command"] = shlex.join(shown)
                    figure["repeats"].append(seconds)
                    if errors is not None:
                        figure["errors"] = errors
    for figure in figures.values():
        figure["min"] = min(figure["repeats"])
        figure["spread"] = max(figure["repeats"]) / figure["min"] - 1
    document = {
        "format": 1,
        "measured_at": started.strftime("%Y-%m-%dT%H:%M:%SZ"),
        "machine": {"nproc": os.cpu_count(), "load_before": load_before, "load_after": load_average()},
        "figures": list(figures.values()),
    }
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    with open(args.output, "w") as f:
        json.dump(document, f, indent=1)
    for figure in figures.values():
        print(f"{figure['key']}: {figure['min']:.3e} s (spread {100 * figure['spread']:.0f} %)")


main()
