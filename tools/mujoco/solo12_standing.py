"""Solo-12 standing on four foot spheres, in MuJoCo's soft contact and in this project's exact contact, measured in one
run (each cost the minimum of five repeats), for docs/contacts.md "Against soft contact": the CPU per simulated second, how far the base moves while the robot
stands, how far the feet slide and how deep they sink.

The scene is scenes/solo12_standing.toml: the ODRI Solo-12 of reference/data/robots dropped 3 cm onto a floor, each
foot a sphere of radius 16 mm at its FOOT link's origin, friction 0.8, a PD stance (kp 20, kd 0.5) with gravity
compensation (MuJoCo's qfrc_bias), run for 10 s. MuJoCo: its URDF import with the meshes dropped and the fixed links
kept, a free joint on the base, Euler at dt = 1e-3 and 2e-3 (its default integrator and cone). Ours: the release
binary on the same file with duration = 10, its stepping CPU; and on the same robot and stance with a fixed base and
no feet, the same system without contact.

Run in a throwaway virtual environment (MuJoCo is never a dependency of this project), after `cargo build --release`:

    python3 -m venv /tmp/mj && /tmp/mj/bin/pip install mujoco
    /tmp/mj/bin/python tools/mujoco/solo12_standing.py
"""

import os
import re
import subprocess
import sys
import tempfile
import time

import mujoco

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
URDF = os.path.join(REPO, "reference/data/robots/solo12.urdf")
SCENE = os.path.join(REPO, "scenes/solo12_standing.toml")
DURATION = 10.0
STANCE = {"HAA": 0.0, "HFE": 0.8, "KFE": -1.6}
LEGS = ("FL", "FR", "HL", "HR")
RADIUS, MU, KP, KD, DROP_HEIGHT = 0.016, 0.8, 20.0, 0.5, 0.269
# Each cost is the minimum over this many runs (the machine is shared; the least disturbed run is the measurement).
REPEATS = 5


def target(leg, joint):
    """The stance angle: the hind legs' HFE and KFE mirrored, as in the scene file."""
    value = STANCE[joint]
    return -value if leg.startswith("H") and joint != "HAA" else value


def model(timestep):
    """MuJoCo's model of the scene: the URDF without meshes, its fixed links kept, a free base, foot spheres, a floor."""
    with open(URDF) as f:
        urdf = f.read()
    urdf = re.sub(r"<visual>.*?</visual>|<collision>.*?</collision>", "", urdf, flags=re.S)
    urdf = urdf.replace("</robot>", '<mujoco><compiler fusestatic="false" discardvisual="true"/></mujoco></robot>')
    spec = mujoco.MjSpec.from_string(urdf)
    spec.option.timestep = timestep
    spec.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_PLANE, size=[10, 10, 0.1], friction=[MU, 0, 0])
    spec.body("base_link").add_freejoint()
    for leg in LEGS:
        spec.body(f"{leg}_FOOT").add_geom(type=mujoco.mjtGeom.mjGEOM_SPHERE, size=[RADIUS, 0, 0], friction=[MU, 0, 0])
    built = spec.compile()
    return built, mujoco.MjData(built)


def mujoco_run(timestep):
    m, d = model(timestep)
    d.qpos[:7] = [0.0, 0.0, DROP_HEIGHT, 1.0, 0.0, 0.0, 0.0]
    address = {}
    for leg in LEGS:
        for joint in STANCE:
            j = m.joint(f"{leg}_{joint}")
            address[(leg, joint)] = (j.qposadr[0], j.dofadr[0])
            d.qpos[j.qposadr[0]] = target(leg, joint)
    mujoco.mj_forward(m, d)
    feet = [m.body(f"{leg}_FOOT").id for leg in LEGS]
    steps = int(round(DURATION / timestep))
    settled, feet_settled, moved, slid, deepest = None, None, 0.0, 0.0, 0.0
    start = time.process_time()
    for k in range(steps):
        for (leg, joint), (q, v) in address.items():
            d.qfrc_applied[v] = KP * (target(leg, joint) - d.qpos[q]) - KD * d.qvel[v] + d.qfrc_bias[v]
        mujoco.mj_step(m, d)
        t = (k + 1) * timestep
        deepest = max(deepest, max(RADIUS - d.xpos[f][2] for f in feet))
        if t >= 2.0:
            base = d.qpos[:3].copy()
            positions = [d.xpos[f][:2].copy() for f in feet]
            if settled is None:
                settled, feet_settled = base, positions
            moved = max(moved, float(sum((base - settled) ** 2) ** 0.5))
            slid = max(slid, max(float(sum((p - s) ** 2) ** 0.5) for p, s in zip(positions, feet_settled)))
    cpu = time.process_time() - start
    resting = max(RADIUS - d.xpos[f][2] for f in feet)
    return cpu / DURATION, moved, slid, deepest, resting


def our_run(without_contact=False):
    """Our binary on the scene file with duration 10 s: the stepping CPU per simulated second of each algebra. Without
    contact: the same robot and stance on a fixed base, no feet (the same system without contact that stands still)."""
    binary = os.path.join(REPO, "target/release/ga-dynamics")
    if not os.path.exists(binary):
        return None
    with open(SCENE) as f:
        text = f.read().replace("duration = 7.0", f"duration = {DURATION}")
    text = text.replace("../reference/data/robots/solo12.urdf", URDF)
    if without_contact:
        text = text[: text.index("[[contact]]")].replace('root = "free"', 'root = "fixed"')
        text = re.sub(r"^base_(position|orientation) = .*$", "", text, flags=re.M)
    with tempfile.TemporaryDirectory() as folder:
        scene = os.path.join(folder, "solo12_standing.toml")
        with open(scene, "w") as f:
            f.write(text)
        done = subprocess.run(
            [binary, "--scene-file", scene, "--output", folder], check=True, capture_output=True, text=True
        )
    # The binary prints "PGA: … CPU 2.95e-2 s per simulated second" per algebra.
    rows = re.findall(r"^(PGA|CGA): .*CPU ([0-9.e+-]+) s per simulated second", done.stdout + done.stderr, flags=re.M)
    return {algebra: float(cpu) for algebra, cpu in rows}


if __name__ == "__main__":
    print(f"MuJoCo {mujoco.__version__}, Solo-12 standing {DURATION} s")
    for timestep in (1e-3, 2e-3):
        runs = [mujoco_run(timestep) for _ in range(REPEATS)]
        cpu = min(run[0] for run in runs)
        _, moved, slid, deepest, resting = runs[0]
        print(
            f"MuJoCo dt = {timestep:g}: CPU {cpu:.3e} s per simulated second; from t = 2 s the base moves {moved:.2e} m, "
            f"a foot slides {slid:.2e} m; deepest {deepest:.2e} m into the floor, {resting:.2e} m at the end"
        )
    for without_contact, what in ((False, "standing on its feet (exact contact)"), (True, "fixed base, no contact")):
        repeats = [our_run(without_contact) for _ in range(REPEATS)]
        if repeats[0] is None:
            print("ours: build the release binary first (cargo build --release)", file=sys.stderr)
            break
        for algebra in repeats[0]:
            cpu = min(r[algebra] for r in repeats)
            print(f"ours {algebra}, {what}, DOP853-body at 1e-10: CPU {cpu:.3e} s per simulated second")
