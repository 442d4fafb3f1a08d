#!/usr/bin/env python3
"""Simo and Vu-Quoc's right-angle cantilever as a MuJoCo hinge chain: the independent check of
examples/right_angle_cantilever.toml (issue 37, item 2).

The structure (Simo and Vu-Quoc 1988, CMAME 66:125-161): two legs of L = 10 at a right angle, the
first along y clamped at the origin, the second along x from the elbow (0, 10, 0); EI = GJ = 1e3,
rho A = 1, rotary inertia per length rho J = diag(20, 10, 10) (twist first); EA = GA = 1e6 is
taken as rigid. A force along z at the elbow rises from 0 to 50 over 0 <= t <= 1 and falls back to
0 at t = 2; the run goes to t = 30.

The chain: each leg cut into N equal segments; at the middle of each segment three hinges at one
point, twist about the leg and bending about the two axes across it, with the segment's
stiffnesses GJ/h and EI/h (h = L/N, the midpoint rule of the elastic energy: a Hencky chain). Each
rigid link between two hinge points carries exactly the mass and inertia of the rod it spans
(rho A h, rho A h^3/12 + rho J h across, rho J_x h about the leg), the link over the elbow both legs'
halves. The elbow force is applied at the elbow point (mj_applyFT at the step's mid-time), no
gravity, no contacts, RK4 at a fixed step. The chain converges to the rod as N grows; run a few N
to see it.

Usage (MuJoCo's Python package; run from a scratch directory so MUJOCO_LOG.TXT stays out of the tree):

    python3 scripts/right_angle_mujoco.py --links 40 --step 1e-3 --out scripts/right_angle_cantilever_mujoco.csv
    python3 scripts/right_angle_mujoco.py --links 20 --compare flexure.csv   # flexure simulate --out's CSV
    python3 scripts/right_angle_mujoco.py --links 40 --step 0.025 --flexure target/release/flexure

It writes t, the elbow's z and the tip's z every 0.05 s, prints the extremes (Exudyn's figures
for the same benchmark: tip 8.24 at t = 7.40 and -9.75 at 15.85, elbow -4.07 at 10.85) and, with
--compare, the largest differences from a flexure run. With --flexure (the `flexure` command) it
runs examples/right_angle_cantilever.toml itself (30 s at tolerance 1e-4, from rest), times it (CPU
of the child process, including the error estimate `simulate` adds: a second run at 1e-5) and
compares. It reports and does not judge.
"""

import argparse
import csv
import pathlib
import resource
import subprocess
import tempfile
import time

import mujoco
import numpy as np

L, EI, GJ, MU, ROTARY = 10.0, 1e3, 1e3, 1.0, (20.0, 10.0, 10.0)
EVERY, END = 0.05, 30.0


def force(t):
    """The elbow force along z: 0 to 50 over [0, 1], back to 0 at t = 2."""
    return 50.0 * t if t < 1.0 else (50.0 * (2.0 - t) if t < 2.0 else 0.0)


def piece(a, b):
    """A straight piece of the rod from a to b: its mass, centre and inertia about it (world axes)."""
    d = b - a
    length = np.linalg.norm(d)
    e = d / length
    across = MU * length**3 / 12.0 + ROTARY[1] * length
    inertia = across * (np.eye(3) - np.outer(e, e)) + ROTARY[0] * length * np.outer(e, e)
    return MU * length, (a + b) / 2.0, inertia


def combined(pieces):
    """Pieces as one rigid body: mass, centre, inertia about the centre (parallel axes)."""
    mass = sum(p[0] for p in pieces)
    centre = sum(p[0] * p[1] for p in pieces) / mass
    inertia = np.zeros((3, 3))
    for m, c, i in pieces:
        r = c - centre
        inertia += i + m * (r @ r * np.eye(3) - np.outer(r, r))
    return mass, centre, inertia


def chain(n, step):
    h = L / n
    leg1 = [np.array([0.0, (k + 0.5) * h, 0.0]) for k in range(n)]
    leg2 = [np.array([(k + 0.5) * h, L, 0.0]) for k in range(n)]
    elbow, tip = np.array([0.0, L, 0.0]), np.array([L, L, 0.0])
    hinges = [(p, np.array([0.0, 1.0, 0.0])) for p in leg1] + [(p, np.array([1.0, 0.0, 0.0])) for p in leg2]
    links = [combined([piece(leg1[k], leg1[k + 1])]) for k in range(n - 1)]
    links.append(combined([piece(leg1[-1], elbow), piece(elbow, leg2[0])]))
    links += [combined([piece(leg2[k], leg2[k + 1] if k < n - 1 else tip)]) for k in range(n)]
    xml = [
        f'<mujoco><option timestep="{step}" integrator="RK4" gravity="0 0 0">'
        '<flag contact="disable"/></option><worldbody>'
    ]
    previous = np.zeros(3)
    for j, ((p, axis), (m, c, i)) in enumerate(zip(hinges, links)):
        x = p - previous
        xml.append(f'<body name="link{j}" pos="{x[0]} {x[1]} {x[2]}">')
        xml.append(f'<joint type="hinge" axis="{axis[0]} {axis[1]} {axis[2]}" stiffness="{GJ / h}"/>')
        for across in (np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0])):
            if abs(across @ axis) < 0.5:
                xml.append(f'<joint type="hinge" axis="{across[0]} {across[1]} {across[2]}" stiffness="{EI / h}"/>')
        c = c - p
        xml.append(
            f'<inertial pos="{c[0]} {c[1]} {c[2]}" mass="{m}" '
            f'fullinertia="{i[0, 0]} {i[1, 1]} {i[2, 2]} {i[0, 1]} {i[0, 2]} {i[1, 2]}"/>'
        )
        for name, point, last in (("elbow", elbow, n - 1), ("tip", tip, 2 * n - 1)):
            if j == last:
                s = point - p
                xml.append(f'<site name="{name}" pos="{s[0]} {s[1]} {s[2]}"/>')
        previous = p
    xml.append("</body>" * (2 * n) + "</worldbody></mujoco>")
    return mujoco.MjModel.from_xml_string("".join(xml))


def run(n, step):
    model = chain(n, step)
    data = mujoco.MjData(model)
    elbow, tip = model.site("elbow").id, model.site("tip").id
    body = model.site_bodyid[elbow]
    per_sample = int(round(EVERY / step))
    if abs(per_sample * step - EVERY) > 1e-12:
        raise SystemExit(f"--step must divide {EVERY}")
    rows = [(0.0, 0.0, 0.0)]
    f, zero = np.zeros(3), np.zeros(3)
    start = time.process_time()
    for _ in range(int(round(END / EVERY))):
        for _ in range(per_sample):
            f[2] = force(data.time + 0.5 * step)
            data.qfrc_applied[:] = 0.0
            mujoco.mj_kinematics(model, data)
            mujoco.mj_applyFT(model, data, f, zero, data.site_xpos[elbow].copy(), body, data.qfrc_applied)
            mujoco.mj_step(model, data)
        rows.append((data.time, data.site_xpos[elbow][2], data.site_xpos[tip][2]))
    return np.array(rows), time.process_time() - start


def extremes(a, label):
    e, t1, t2 = a[:, 1].argmin(), a[:, 2].argmax(), a[:, 2].argmin()
    print(
        f"{label}: elbow min {a[e, 1]:.4f} at t = {a[e, 0]:.2f}; tip max {a[t1, 2]:.4f} at {a[t1, 0]:.2f}, "
        f"min {a[t2, 2]:.4f} at {a[t2, 0]:.2f}"
    )


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--links", type=int, default=40, help="links per leg [40]")
    p.add_argument("--step", type=float, default=1e-3, help="RK4 step (s), dividing 0.05 [1e-3]")
    p.add_argument("--out", help="write t, elbow z, tip z here (CSV)")
    p.add_argument("--compare", help="a CSV of `flexure simulate --out` to compare with")
    p.add_argument("--flexure", help="the flexure command: run and time examples/right_angle_cantilever.toml")
    args = p.parse_args()
    if args.flexure:
        example = pathlib.Path(__file__).resolve().parent.parent / "examples" / "right_angle_cantilever.toml"
        args.compare = str(pathlib.Path(tempfile.mkdtemp()) / "flexure.csv")
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        command = [args.flexure, "simulate", str(example), "--duration", "30", "--every", "0.05"]
        command += ["--tolerance", "1e-4", "--start", "rest", "--out", args.compare]
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        spent = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
        print(f"flexure simulate, order 4 at 1e-4 with its error estimate: {spent:.1f} s CPU")
    a, cpu = run(args.links, args.step)
    extremes(a, f"MuJoCo {mujoco.__version__}, {args.links} links per leg, step {args.step}: {cpu:.1f} s CPU")
    if args.out:
        with open(args.out, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["time", "elbow_z", "tip_z"])
            w.writerows([[f"{t:.2f}", f"{e:.6f}", f"{tip:.6f}"] for t, e, tip in a])
    if args.compare:
        rows = list(csv.reader(open(args.compare)))
        head, values = rows[0], np.array([[float(x) for x in r] for r in rows[1:]])
        t, e, tip = values[:, 0], values[:, head.index("elbow.z")], values[:, head.index("tip.z")]
        de = np.abs(np.interp(a[:, 0], t, e) - a[:, 1])
        dt = np.abs(np.interp(a[:, 0], t, tip) - a[:, 2])
        extremes(np.column_stack([t, e, tip]), "flexure")
        print(f"largest difference: elbow {de.max():.4f} at t = {a[de.argmax(), 0]:.2f}, tip {dt.max():.4f} at {a[dt.argmax(), 0]:.2f}")


if __name__ == "__main__":
    main()
