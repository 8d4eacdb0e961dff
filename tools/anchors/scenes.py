"""MuJoCo's and Pinocchio's costs (and MuJoCo's errors) on this repository's reference scenes, one measurement per
call, written as JSON for measure.py. Everything it reads is in the repository: the scene parameters of
docs/scenes.md, the reference trajectories and robots of reference/data. Every model is written here from those
parameters.

Usage: python scenes.py {single_bodies,m1,m2,m3,m3_pinocchio,robots} OUTFILE

Times are thread CPU seconds per step (MuJoCo) or per evaluation (Pinocchio) of one run in this process; measure.py
runs each measurement in several fresh processes and keeps the fastest. Errors compare MuJoCo's state with the
reference trajectory at the reference's sample times.
"""
import csv
import json
import math
import os
import re
import sys
import time

import mujoco
import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(REPO, "reference", "data")
GRAVITY = 9.81
SAMPLE_INTERVAL = 0.01  # the reference trajectories' sample interval
CHAIN_LINKS = (1, 2, 4, 8, 16, 32, 64)
ROBOT_STEPS = (1e-3, 1e-4)


def reference_rows(path):
    """A reference CSV as a list of {column: float} rows."""
    with open(path, newline="") as f:
        return [{key: float(value) for key, value in row.items()} for row in csv.DictReader(f)]


def cuboid_inertia(mass, x, y, z):
    """Principal moments of a solid cuboid of extents (x, y, z) about its centre."""
    return (mass * (y * y + z * z) / 12, mass * (x * x + z * z) / 12, mass * (x * x + y * y) / 12)


def inertial(mass, extents, centre):
    """An MJCF <inertial> for a cuboid link whose centre of mass is at `centre` in its body frame."""
    moments = " ".join(repr(m) for m in cuboid_inertia(mass, *extents))
    return f'<inertial pos="{" ".join(repr(c) for c in centre)}" mass="{mass!r}" diaginertia="{moments}"/>'


def rk4_model(worldbody, dt, extra="", gravity=GRAVITY):
    """A model stepped by MuJoCo's RK4 at `dt`, `gravity` along −z, no contact."""
    return mujoco.MjModel.from_xml_string(
        f'<mujoco><option gravity="0 0 {-gravity!r}" integrator="RK4" timestep="{dt!r}">'
        f'<flag contact="disable"/></option><worldbody>{worldbody}</worldbody>{extra}</mujoco>')


def stepping_cpu(model, data, steps):
    """Thread CPU seconds of `steps` steps of MuJoCo in one call."""
    start = time.thread_time()
    mujoco.mj_step(model, data, nstep=steps)
    return time.thread_time() - start


def rotation_angle(q, r):
    """The angle (rad) of the rotation between unit quaternions q and r (w, x, y, z), accurate near zero: with
    s = sign(q·r), |q − s r| = 2 sin(θ/4) and |q + s r| = 2 cos(θ/4)."""
    q, r = np.asarray(q, float), np.asarray(r, float)
    r = math.copysign(1.0, float(np.dot(q, r))) * r
    return 4 * math.atan2(float(np.linalg.norm(q - r)), float(np.linalg.norm(q + r)))


def m1():
    """M1, the double pendulum (docs/scenes.md): RK4 at dt = 1e-2, 1e-3, 1e-4 over T = 10 s; per step its cost,
    and the largest orientation error of the two links at T against reference/data/ref_m1_double_pendulum.csv."""
    rows = reference_rows(os.path.join(DATA, "ref_m1_double_pendulum.csv"))
    end = rows[-1]
    duration = end["t"]
    # Link 1 hangs from the world origin on a hinge about x; link 2 from link 1's lower end on a hinge about
    # link 1's y. Body frames sit at the hinges with z along the link, so each centre of mass is half a link down.
    worldbody = (
        '<body name="link1"><joint type="hinge" axis="1 0 0"/>'
        + inertial(1.0, (0.1, 0.1, 1.0), (0, 0, -0.5))
        + '<body name="link2" pos="0 0 -1"><joint type="hinge" axis="0 1 0"/>'
        + inertial(0.5, (0.08, 0.08, 0.8), (0, 0, -0.4))
        + "</body></body>")
    figures = {}
    for dt in (1e-2, 1e-3, 1e-4):
        model = rk4_model(worldbody, dt)
        data = mujoco.MjData(model)
        data.qpos[:] = (1.0, 0.6)
        data.qvel[:] = (1.0, -0.5)
        steps = round(duration / dt)
        cpu = stepping_cpu(model, data, steps)
        mujoco.mj_kinematics(model, data)
        errors = [rotation_angle(data.xquat[model.body(f"link{k}").id],
                                 [end[f"q{c}{k}"] for c in "wxyz"]) for k in (1, 2)]
        figures[f"{dt:g}"] = {"seconds_per_step": cpu / steps, "orientation_error_rad": max(errors)}
    return figures


def single_body_run(reference, worldbody, gravity, start, dt):
    """One single-body scene at dt from `start` (qpos, qvel), over its reference's span: the CPU per step, the model,
    its data at the end and the reference's last row."""
    rows = reference_rows(os.path.join(DATA, reference))
    model = rk4_model(worldbody, dt, gravity=gravity)
    data = mujoco.MjData(model)
    data.qpos[:], data.qvel[:] = start
    steps = round(rows[-1]["t"] / dt)
    cpu = stepping_cpu(model, data, steps)
    mujoco.mj_kinematics(model, data)
    return cpu / steps, model, data, rows[-1]


def single_bodies():
    """The single-body scenes of docs/scenes.md that have a MuJoCo anchor, RK4 at dt = 1e-2, 1e-3, 1e-4: per step its
    cost, and its error at T against reference/data (the end orientation; scene 4, the centre of mass)."""
    # The rod of scenes 2 and 4: 1 kg, 1 m, its centre of mass half a metre from the end its frame sits at.
    rod = f'<inertial pos="0 0 -0.5" mass="1" diaginertia="{1 / 12!r} {1 / 12!r} 0.001"/>'
    half_tilt = math.pi / 12  # scene 3 starts turned by π/6 about world x
    scenes = {
        # Scene 1: the free cuboid (1, 2, 3), no gravity; a free joint's angular velocity is in the body's axes.
        "scene1": ("ref_scene1_cuboid.csv", '<body name="body"><freejoint/>'
                   + inertial(1.0, (1.0, 2.0, 3.0), (0, 0, 0)) + "</body>", 0.0,
                   ([0, 0, 0, 1, 0, 0, 0], [1.0, 0.5, 0.0, 0.1, 10.0, 0.0])),
        # Scene 2: the rod hinged at its end about world y, from horizontal (+π/2 puts its centre at −x).
        "scene2": ("ref_scene2_pendulum.csv", '<body name="body"><joint type="hinge" axis="0 1 0"/>' + rod + "</body>",
                   GRAVITY, ([math.pi / 2], [0.0])),
        # Scene 3a: the cone on its tip (its centre of mass 0.75 up the axis), spinning at 20 rad/s about the axis.
        "scene3a": ("ref_scene3a_top_cusp.csv", '<body name="body"><joint type="ball"/><inertial pos="0 0 0.75" mass="1" '
                    'diaginertia="0.1875 0.1875 0.3"/></body>', GRAVITY,
                    ([math.cos(half_tilt), math.sin(half_tilt), 0, 0], [0.0, 0.0, 20.0])),
        # Scene 4: the rod's end on the horizontal circle of radius 0.5 about the origin, in reduced coordinates: an
        # arm of negligible mass (1e-14 kg; 1e-9 kg moves the end state by 8e-9 m) turning about world z carries a
        # ball joint round the circle. The start: the end at (0.5, 0, 0) at rest, the rod spinning at 1 rad/s about x.
        "scene4-circle": ("ref_scene4_rod_end_on_circle.csv",
                          '<body name="arm"><joint type="hinge" axis="0 0 1"/><inertial pos="0 0 0" mass="1e-14" '
                          'diaginertia="1e-14 1e-14 1e-14"/><body name="body" pos="0.5 0 0"><joint type="ball"/>'
                          + rod + "</body></body>", GRAVITY, ([0.0, 1, 0, 0, 0], [0.0, 1.0, 0.0, 0.0])),
    }
    figures = {}
    for key, (reference, worldbody, gravity, start) in scenes.items():
        for dt in (1e-2, 1e-3, 1e-4):
            seconds, model, data, end = single_body_run(reference, worldbody, gravity, start, dt)
            body = model.body("body").id
            if key == "scene4-circle":
                error = float(np.linalg.norm(data.xipos[body] - [end["px"], end["py"], end["pz"]]))
            else:
                error = rotation_angle(data.xquat[body], [end[f"q{c}"] for c in "wxyz"])
            figures[f"{key}_{dt:g}"] = {"seconds_per_step": seconds, "error": error}
    return figures


def four_bar_rates(alpha, lengths, crank_rate):
    """The coupler's and rocker's angular rates the loop implies. The loop B + L2 e(α2) = D + L3 e(α3), with
    B = L1 e(α1), differentiated: L2 α̇2 e⊥(α2) − L3 α̇3 e⊥(α3) = −L1 α̇1 e⊥(α1), e⊥(α) = (−sin α, cos α)."""
    l1, l2, l3 = lengths
    perp = lambda a: np.array([-math.sin(a), math.cos(a)])
    matrix = np.column_stack([l2 * perp(alpha[1]), -l3 * perp(alpha[2])])
    return np.linalg.solve(matrix, -l1 * crank_rate * perp(alpha[0]))


def m2():
    """M2, the four-bar linkage (docs/scenes.md), its loop closed by MuJoCo's (soft) connect equality: RK4 at
    dt = 1e-3 over T = 5 s; per step its cost, and the coupler's centre-of-mass error at T against
    reference/data/ref_m2_four_bar.csv."""
    rows = reference_rows(os.path.join(DATA, "ref_m2_four_bar.csv"))
    start, end = rows[0], rows[-1]
    ground, width = 1.0, 0.05
    links = {"crank": (0.3, 0.5), "coupler": (1.0, 1.0), "rocker": (0.8, 0.8)}  # length, mass

    def link(name, position):
        length, mass = links[name]
        # A hinge about −y turns body z, which starts along world +z, to the direction angle α = q + π/2
        # (measured from +x towards +z).
        return (f'<body name="{name}" pos="{position}"><joint type="hinge" axis="0 -1 0"/>'
                + inertial(mass, (width, width, length), (0, 0, length / 2)))

    # One open chain A → B → C → D (the rocker's body runs from C to D), its end held at D: the model the
    # recorded figure (report/src/recorded_anchors.rs) was measured on.
    lengths = [links[n][0] for n in ("crank", "coupler", "rocker")]
    worldbody = (link("crank", "0 0 0") + link("coupler", f"0 0 {lengths[0]!r}") + link("rocker", f"0 0 {lengths[1]!r}")
                 + f'<site name="rocker_end" pos="0 0 {lengths[2]!r}"/></body></body></body>'
                 + f'<site name="D" pos="{ground!r} 0 0"/>')
    equality = '<equality><connect site1="rocker_end" site2="D"/></equality>'
    alpha = [start["alpha1"], start["alpha2"], start["alpha3"]]
    coupler_rate, rocker_rate = four_bar_rates(alpha, lengths, 6.0)
    dt = 1e-3
    model = rk4_model(worldbody, dt, equality)
    data = mujoco.MjData(model)
    # Relative angles: the rocker's body points along C → D, at α3 + π.
    data.qpos[:] = (alpha[0] - math.pi / 2, alpha[1] - alpha[0], alpha[2] + math.pi - alpha[1])
    data.qvel[:] = (6.0, coupler_rate - 6.0, rocker_rate - coupler_rate)
    steps = round(end["t"] / dt)
    cpu = stepping_cpu(model, data, steps)
    mujoco.mj_kinematics(model, data)
    centre = data.xipos[model.body("coupler").id]
    error = math.hypot(centre[0] - end["x2"], centre[2] - end["z2"])
    return {f"{dt:g}": {"seconds_per_step": cpu / steps, "coupler_centre_error_m": error}}


# M3 (docs/scenes.md): N links of mass 0.5 and extents (0.05, 0.05, 0.5), end to end, the first hung from the
# world origin, started horizontal (turned +90° about x) at rest.
CHAIN_MASS, CHAIN_WIDTH, CHAIN_LENGTH = 0.5, 0.05, 0.5


def m3():
    """M3 in MuJoCo: RK4 at dt = 1e-3, the cost per step of 2000 steps for N ball joints and for N hinges."""
    figures = {}
    for kind in ("ball", "hinge"):
        axis = ' axis="1 0 0"' if kind == "hinge" else ""
        for n in CHAIN_LINKS:
            worldbody = "".join(
                f'<body pos="0 0 {0.0 if k == 0 else -CHAIN_LENGTH!r}"><joint type="{kind}"{axis}/>'
                + inertial(CHAIN_MASS, (CHAIN_WIDTH, CHAIN_WIDTH, CHAIN_LENGTH), (0, 0, -CHAIN_LENGTH / 2))
                for k in range(n)) + "</body>" * n
            model = rk4_model(worldbody, 1e-3)
            data = mujoco.MjData(model)
            if kind == "ball":
                data.qpos[0:4] = (math.cos(math.pi / 4), math.sin(math.pi / 4), 0, 0)
            else:
                data.qpos[0] = math.pi / 2
            steps = 2000
            figures[f"{kind}_{n}"] = {"seconds_per_step": stepping_cpu(model, data, steps) / steps}
    return figures


def m3_pinocchio():
    """M3's ball chain in Pinocchio: one ABA evaluation at a random state, the mean over a batch of calls (Python's
    call overhead included)."""
    import pinocchio as pin

    figures = {}
    moments = np.diag(cuboid_inertia(CHAIN_MASS, CHAIN_WIDTH, CHAIN_WIDTH, CHAIN_LENGTH))
    for n in CHAIN_LINKS:
        model, parent = pin.Model(), 0
        for k in range(n):
            placement = pin.SE3(np.eye(3), np.array([0.0, 0.0, 0.0 if k == 0 else -CHAIN_LENGTH]))
            parent = model.addJoint(parent, pin.JointModelSpherical(), placement, f"ball{k}")
            model.appendBodyToJoint(parent, pin.Inertia(CHAIN_MASS, np.array([0, 0, -CHAIN_LENGTH / 2]), moments),
                                    pin.SE3.Identity())
        data = model.createData()
        rng = np.random.default_rng(n)
        q = pin.randomConfiguration(model)
        v, tau = rng.standard_normal(model.nv), np.zeros(model.nv)
        calls = 20000 if n < 32 else 4000
        start = time.thread_time()
        for _ in range(calls):
            pin.aba(model, data, q, v, tau)
        figures[str(n)] = {"seconds_per_evaluation": (time.thread_time() - start) / calls}
    return figures


def robot_model(urdf_path, free_root, dt):
    """A URDF robot as MuJoCo loads it, reduced to what the reference models: its inertias on the tree (fixed
    joints fused), gravity, no geometry, no contact, limits, damping, friction, springs or actuators; RK4 at dt."""
    with open(urdf_path) as f:
        urdf = f.read()
    # The meshes are not in the repository and play no part in the dynamics.
    urdf = re.sub(r"<visual>.*?</visual>|<collision>.*?</collision>", "", urdf, flags=re.S)
    compiler = ('<mujoco><compiler fusestatic="true" discardvisual="true" inertiafromgeom="false" '
                'balanceinertia="false" angle="radian"/></mujoco>')
    urdf = urdf.replace("</robot>", compiler + "</robot>")
    spec = mujoco.MjSpec.from_string(urdf)
    if free_root:
        spec.worldbody.first_body().add_freejoint()
    model = spec.compile()
    model.opt.timestep = dt
    model.opt.integrator = mujoco.mjtIntegrator.mjINT_RK4
    model.opt.gravity[:] = (0.0, 0.0, -GRAVITY)
    off = mujoco.mjtDisableBit
    model.opt.disableflags |= (off.mjDSBL_CONTACT | off.mjDSBL_LIMIT | off.mjDSBL_EQUALITY | off.mjDSBL_FRICTIONLOSS
                               | off.mjDSBL_SPRING | off.mjDSBL_DAMPER | off.mjDSBL_ACTUATION)
    model.dof_armature[:] = 0.0
    return model


def robots():
    """UR5 and Solo-12 (reference/data/robots): RK4 at dt = 1e-3 and 1e-4 over the reference's 1 s from its start;
    per step its cost, and the largest joint-position error over the reference's samples."""
    figures = {}
    for robot, urdf in (("ur5", "ur5_robot.urdf"), ("solo12", "solo12.urdf")):
        with open(os.path.join(DATA, "robots", f"{robot}.json")) as f:
            facts = json.load(f)
        rows = reference_rows(os.path.join(DATA, "robots", f"{robot}.csv"))
        free_root = facts["root"] == "free-flyer"
        for dt in ROBOT_STEPS:
            model = robot_model(os.path.join(DATA, "robots", urdf), free_root, dt)
            data = mujoco.MjData(model)
            if free_root:
                base = facts["base_initial"]
                # MuJoCo's free joint: position, quaternion (w, x, y, z); linear velocity in world axes, angular in
                # the body's, which coincide at the identity start.
                data.qpos[0:7] = [*base["position"], *base["quaternion_wxyz"]]
                data.qvel[0:6] = [*base["linear_velocity"], *base["angular_velocity"]]
            joints = facts["joints"]
            for name in joints:
                data.qpos[model.joint(name).qposadr[0]] = facts["q0"][name]
                data.qvel[model.joint(name).dofadr[0]] = facts["v0"][name]
            steps_per_sample = round(SAMPLE_INTERVAL / dt)
            cpu, error = 0.0, 0.0
            for row in rows[1:]:
                cpu += stepping_cpu(model, data, steps_per_sample)
                error = max(error, max(abs(data.qpos[model.joint(n).qposadr[0]] - row[n]) for n in joints))
            steps = steps_per_sample * (len(rows) - 1)
            figures[f"{robot}_{dt:g}"] = {"seconds_per_step": cpu / steps, "joint_position_error": error}
    return figures


MEASUREMENTS = {
    "single_bodies": single_bodies,
    "m1": m1,
    "m2": m2,
    "m3": m3,
    "m3_pinocchio": m3_pinocchio,
    "robots": robots,
}

if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in MEASUREMENTS:
        sys.exit(f"usage: python scenes.py {{{','.join(MEASUREMENTS)}}} OUTFILE")
    result = MEASUREMENTS[sys.argv[1]]()
    with open(sys.argv[2], "w") as f:
        json.dump(result, f, indent=1)
