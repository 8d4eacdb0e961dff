"""MuJoCo's soft contact on the closed-form friction scenes of dynamics/tests/integration/friction.rs, for
docs/contacts.md "Against soft contact": how far a box that should stick creeps, how deep it sinks, how a stack of
three boxes settles, and when a struck ball starts rolling.

Run in a throwaway virtual environment (MuJoCo is never a dependency of this project):

    python3 -m venv /tmp/mj && /tmp/mj/bin/pip install mujoco
    /tmp/mj/bin/python tools/mujoco/contact_creep.py
"""

import math

import mujoco

G = 9.81


def body_on_floor(body_geom, mu, timestep, gravity=(0.0, 0.0, -G)):
    """A model of one free body (its geom's XML) starting with its centre 0.1 m above a floor, friction `mu` on both."""
    xml = f"""
    <mujoco>
      <option timestep="{timestep}" gravity="{gravity[0]} {gravity[1]} {gravity[2]}"/>
      <worldbody>
        <geom type="plane" size="10 10 0.1" friction="{mu} 0 0"/>
        <body pos="0 0 0.1">
          <freejoint/>
          {body_geom.format(mu=mu)}
        </body>
      </worldbody>
    </mujoco>"""
    model = mujoco.MjModel.from_xml_string(xml)
    return model, mujoco.MjData(model)


def box_on_incline(slope, mu, timestep, duration):
    """A 0.2 m cube of 1 kg at rest on an incline of `slope` rad (gravity tilted), friction `mu` (> tan slope: it
    should stick). Returns the distance it moved along the incline and the deepest its bottom went below the plane."""
    gravity = (G * math.sin(slope), 0.0, -G * math.cos(slope))
    box = '<geom type="box" size="0.1 0.1 0.1" mass="1" friction="{mu} 0 0"/>'
    model, data = body_on_floor(box, mu, timestep, gravity)
    deepest = 0.0
    steps = int(round(duration / timestep))
    for _ in range(steps):
        mujoco.mj_step(model, data)
        deepest = max(deepest, 0.1 - data.qpos[2])
    return abs(data.qpos[0]), deepest


def struck_ball(v0, mu, timestep):
    """A ball (2 kg, radius 0.1 m) struck without spin along a floor with friction `mu`: the time its contact point's
    slip first falls below 1e-3 m/s and its speed at 1 s, against 2v0/(7 mu g) and 5v0/7."""
    ball = '<geom type="sphere" size="0.1" mass="2" friction="{mu} 0 0"/>'
    model, data = body_on_floor(ball, mu, timestep)
    data.qvel[0] = v0
    rolling = None
    for step in range(int(round(1.0 / timestep))):
        mujoco.mj_step(model, data)
        slip = data.qvel[0] - data.qvel[4] * 0.1
        if rolling is None and abs(slip) < 1e-3:
            rolling = (step + 1) * timestep
    return rolling, data.qvel[0]


def stack(timestep, duration, mu=0.5):
    """Three boxes stacked on a floor at rest (3 kg 0.6 x 0.6 x 0.3 m, 2 kg 0.4 x 0.4 x 0.2 m, 1 kg 0.2 m cube, friction
    `mu`), as dynamics/tests/integration/bodies_meeting.rs stacks them: the most any box moves from its start in
    `duration`, and the deepest any box sinks into the one below it (or the floor)."""
    boxes = [(3.0, (0.6, 0.6, 0.3)), (2.0, (0.4, 0.4, 0.2)), (1.0, (0.2, 0.2, 0.2))]
    bodies, height, centres = "", 0.0, []
    for k, (mass, (a, b, c)) in enumerate(boxes):
        centre = height + c / 2
        centres.append(centre)
        bodies += f"""
        <body pos="0 0 {centre}">
          <freejoint/>
          <geom type="box" size="{a / 2} {b / 2} {c / 2}" mass="{mass}" friction="{mu} 0 0"/>
        </body>"""
        height += c
    xml = f"""
    <mujoco>
      <option timestep="{timestep}"/>
      <worldbody>
        <geom type="plane" size="10 10 0.1" friction="{mu} 0 0"/>{bodies}
      </worldbody>
    </mujoco>"""
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    moved, sunk = 0.0, 0.0
    for _ in range(int(round(duration / timestep))):
        mujoco.mj_step(model, data)
        for k, centre in enumerate(centres):
            position = data.qpos[7 * k : 7 * k + 3]
            moved = max(moved, math.dist(position, (0.0, 0.0, centre)))
            sunk = max(sunk, centre - position[2])
    return moved, sunk


def main():
    print("MuJoCo", mujoco.__version__)
    for timestep in (1e-3, 2e-3):
        moved, deepest = box_on_incline(0.3, 0.35, timestep, 10.0)
        print(f"box on a 0.3 rad incline, mu 0.35, dt {timestep:g}: crept {moved:.3e} m in 10 s, sank {deepest:.3e} m")
        moved, deepest = box_on_incline(0.0, 0.35, timestep, 10.0)
        print(f"box on a level floor, dt {timestep:g}: moved {moved:.3e} m in 10 s, sank {deepest:.3e} m")
        moved, sunk = stack(timestep, 10.0)
        print(f"stack of three boxes at rest, dt {timestep:g}: a box moved {moved:.3e} m in 10 s, sank {sunk:.3e} m")
        rolling, speed = struck_ball(2.0, 0.3, timestep)
        print(
            f"struck ball, dt {timestep:g}: rolling from {rolling} s (exact {2 * 2.0 / (7 * 0.3 * G):.6f} s), "
            f"speed {speed:.6f} m/s (exact {5 * 2.0 / 7:.6f})"
        )


if __name__ == "__main__":
    main()
