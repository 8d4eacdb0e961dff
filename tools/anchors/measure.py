"""Times MuJoCo and Pinocchio on the reference scenes now, with the reference set's own scripts, and writes the
figures the report compares our costs with (docs/benchmarks.md, "Anchors measured in the same run").

Each script runs REPEATS times in a fresh process; a figure keeps every repeat, the minimum (the run least
disturbed by other work on the machine) and the spread max/min - 1. Errors are the script's (deterministic).
Usage: python measure.py --reference-set DIR --output FILE [--repeats N] [--only KEY_PREFIX,...]
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
# MULTIBODY.md's parameters of M1 (m1 a1 b1 c1 m2 a2 b2 c2 q1 q2 w1 w2 T) and M2 (L0 L1 L2 L3 w m1 m2 m3 phi0
# omega0 T).
M1_ARGUMENTS = "1.0 0.1 0.1 1.0 0.5 0.08 0.08 0.8 1.0 0.6 1.0 -0.5 10".split()
M2_ARGUMENTS = "1.0 0.3 1.0 0.8 0.05 0.5 1.0 0.8 1.0 6.0 5".split()


def load_average():
    with open("/proc/loadavg") as f:
        return [float(x) for x in f.read().split()[:3]]


def run(command, workdir):
    # The scripts print progress; only their files are read, so their output goes to a log beside them.
    with open(os.path.join(workdir, "log.txt"), "a") as log:
        subprocess.run(command, cwd=workdir, stdout=log, stderr=log, check=True)


def json_in(path):
    with open(path) as f:
        return json.load(f)


def m1(reference_set, python, workdir):
    """M1: MuJoCo RK4 s per step at dt = 1e-3; its end orientation errors (rad) at dt = 1e-2, 1e-3, 1e-4."""
    script = os.path.join(reference_set, "scenes/multibody/mujoco/double_pendulum.py")
    command = [python, script, workdir, "m1", *M1_ARGUMENTS]
    run(command, workdir)
    rk4 = json_in(os.path.join(workdir, "m1.json"))["mujoco_rk4"]
    errors = [{"dt": float(dt), "error": rk4[dt]["rot_err_rad"]} for dt in ("0.01", "0.001", "0.0001")]
    yield command, "m1", "MuJoCo 4.0 RK4 step at dt = 1e-3", 1e-3, rk4["0.001"]["us_per_step"] * 1e-6, errors


def m2(reference_set, python, workdir):
    """M2: MuJoCo RK4 s per step at dt = 1e-3; its coupler centre-of-mass error at T (m)."""
    script = os.path.join(reference_set, "scenes/multibody/mujoco/four_bar.py")
    command = [python, script, workdir, "m2", *M2_ARGUMENTS]
    run(command, workdir)
    at = json_in(os.path.join(workdir, "m2.json"))["mujoco_rk4_equality"]["0.001"]
    errors = [{"dt": 1e-3, "error": at["coupler_com_err_end_m"]}]
    yield command, "m2", "MuJoCo 4.0 RK4 step at dt = 1e-3, loop by a soft equality", 1e-3, at["us_per_step"] * 1e-6, errors


def chain_script(reference_set, python, workdir, simulator, output_name):
    """Runs the reference set's `<simulator>/chain.py` into `output_name`: its command and the JSON it wrote."""
    output = os.path.join(workdir, output_name)
    command = [python, os.path.join(reference_set, "scenes/multibody", simulator, "chain.py"), output]
    run(command, workdir)
    return command, json_in(output)


def m3(reference_set, python, workdir):
    """M3: MuJoCo RK4 s per step at dt = 1e-3 for the ball and the hinge chains of N links."""
    command, chains = chain_script(reference_set, python, workdir, "mujoco", "chain.json")
    for joint in ("ball", "hinge"):
        for n in CHAIN_LINKS:
            seconds = chains[f"{joint}_{n}"]["us_per_step"] * 1e-6
            yield command, f"m3-{joint}-{n}", f"MuJoCo 4.0 RK4 step at dt = 1e-3, {joint} joints", 1e-3, seconds, None


def m3_pinocchio(reference_set, python, workdir):
    """M3: Pinocchio's ABA on the ball chain, s per dynamics evaluation (no step size)."""
    command, chains = chain_script(reference_set, python, workdir, "pinocchio", "pinocchio_chain.json")
    for n in CHAIN_LINKS:
        seconds = chains[str(n)]["pinocchio_aba_us"] * 1e-6
        yield command, f"m3-pinocchio-{n}", "Pinocchio 4.1 ABA evaluation, ball joints", None, seconds, None


def robots(reference_set, python, workdir):
    """UR5 and Solo-12: MuJoCo RK4 s per step at dt = 1e-3 and 1e-4; the largest joint error (rad) at each."""
    script = os.path.join(reference_set, "robots/tools/reference.py")
    for robot in ROBOTS:
        command = [python, script, robot, workdir]
        run(command, workdir)
        rk4 = json_in(os.path.join(workdir, f"{robot}.json"))["mujoco"]["rk4"]
        # The script's keys for the steps, and the report's (Rust's `{:.0e}`, not Python's "1e-03").
        for dt, step in (("0.001", "1e-3"), ("0.0001", "1e-4")):
            errors = [{"dt": float(dt), "error": rk4[dt]["max_joint_pos_err"]}]
            key = f"{robot}-dt{step}"
            yield command, key, f"MuJoCo 4.0 RK4 step at dt = {step}", float(dt), rk4[dt]["us_per_step"] * 1e-6, errors


MEASUREMENTS = (m1, m2, m3, m3_pinocchio, robots)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--reference-set", required=True)
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
                for command, key, what, dt, seconds, errors in measurement(args.reference_set, sys.executable, workdir):
                    figure = figures.setdefault(key, {"key": key, "what": what, "dt": dt, "repeats": []})
                    # The command with its scratch folder named, so it can be run again by hand.
                    figure["command"] = shlex.join(c.replace(workdir, "OUTDIR") for c in command)
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
