#!/usr/bin/python3
"""The Flores-Leine-Glocker slider-crank in Siconos (rigid bodies, Moreau-Jean time-stepping, Newton
impacts at the slider's corners), written for this project's comparison with `mechanism simulate`.

Usage: flg_siconos.py OUT.tsv [--restitution 0.4] [--friction 0.0] [--step 1e-5] [--duration 0.2] [--driven]
       [--crank-speed 150]

The model (our own derivation; the parameters are those of Flores, Leine & Glocker, Multibody Syst.
Dyn. 23, 165 (2010), as mechanism/scenes/flores_leine_glocker_free.toml carries them):
generalised coordinates q = (theta1, theta2, theta3): crank angle, coupler angle, slider angle. The
slider's centre is the coupler's end, (l1 cos theta1 + l2 cos theta2, l1 sin theta1 + l2 sin theta2),
links' mass centres at their middles. Mass matrix
    M11 = m1 l1^2 / 4 + (m2 + m3) l1^2 + J1,  M12 = c cos(theta1 - theta2),  c = (m2 / 2 + m3) l1 l2,
    M22 = m2 l2^2 / 4 + m3 l2^2 + J2,  M33 = J3,
gyroscopic and gravity terms (Siconos's FGyr: M q'' + FGyr = p)
    FGyr1 = c sin(theta1 - theta2) theta2'^2 + g l1 (m1 / 2 + m2 + m3) cos theta1,
    FGyr2 = -c sin(theta1 - theta2) theta1'^2 + g l2 (m2 / 2 + m3) cos theta2,  FGyr3 = 0.
Four unilateral contacts: the top corners (xi, +b) against the upper guide y = b + c and the bottom
corners (xi, -b) against the lower guide y = -(b + c), xi = -a, +a; gap of a corner at local
(xi, eta): y = l1 sin theta1 + l2 sin theta2 + xi sin theta3 + eta cos theta3, h = (b + c) - y on
top, y + (b + c) below. With friction the relation has a second row, the corner's x.

--driven stands in for a constant-speed driver with a crank inertia of 1e3 kg m^2 (1.3e7 times J1):
the mechanism's reaction torques then move the crank's 150 rad/s by less than 1e-3 rad/s over 80
revolutions (measured). The energy column then holds that crank's kinetic energy too. --crank-speed
sets the crank's initial speed (rad/s; the coupler's is minus half of it, as at crank angle 0 with
l2 = 2 l1).

The plugins are C, generated here with the parameters and compiled with the system's cc (Siconos
calls them at every Newton iteration; Python callbacks would be slow).
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

try:
    import siconos.kernel as sk
except ImportError:
    sys.exit("flg_siconos.py: Siconos's Python package is not installed (apt-get install python3-siconos)")

L1, L2 = 0.153, 0.306
A, B, C = 0.05, 0.025, 0.001
M1, M2, M3 = 0.038, 0.038, 0.076
J1, J2, J3 = 7.4e-5, 5.9e-4, 2.7e-6
G = 9.81
CORNERS = [(-A, B, +1), (A, B, +1), (-A, -B, -1), (A, -B, -1)]  # (xi, eta, surface: +1 upper, -1 lower)


def plugin_source(friction, j1):
    c = (M2 / 2 + M3) * L1 * L2
    g1 = G * L1 * (M1 / 2 + M2 + M3)
    g2 = G * L2 * (M2 / 2 + M3)
    src = [f"""#include <math.h>
#define CC {c!r}
#define G1 {g1!r}
#define G2 {g2!r}
void mass(unsigned int n, const double* q, double* m, unsigned int nz, double* z) {{
  (void)n; (void)nz; (void)z;
  for (int i = 0; i < 9; ++i) m[i] = 0.0;
  m[0] = {M1 * L1 * L1 / 4 + (M2 + M3) * L1 * L1 + j1!r};
  m[3] = m[1] = CC * cos(q[0] - q[1]);
  m[4] = {M2 * L2 * L2 / 4 + M3 * L2 * L2 + J2!r};
  m[8] = {J3!r};
}}
void fgyr(unsigned int n, const double* q, const double* v, double* f, unsigned int nz, double* z) {{
  (void)n; (void)nz; (void)z;
  const double s = sin(q[0] - q[1]);
  f[0] = CC * s * v[1] * v[1] + G1 * cos(q[0]);
  f[1] = -CC * s * v[0] * v[0] + G2 * cos(q[1]);
  f[2] = 0.0;
}}
void jfgyrq(unsigned int n, const double* q, const double* v, double* j, unsigned int nz, double* z) {{
  (void)n; (void)nz; (void)z;
  const double co = cos(q[0] - q[1]);
  for (int i = 0; i < 9; ++i) j[i] = 0.0;
  j[0] = CC * co * v[1] * v[1] - G1 * sin(q[0]);  /* d f0 / d q0 (column-major: j[row + 3 col]) */
  j[3] = -CC * co * v[1] * v[1];                 /* d f0 / d q1 */
  j[1] = -CC * co * v[0] * v[0];                 /* d f1 / d q0 */
  j[4] = CC * co * v[0] * v[0] - G2 * sin(q[1]); /* d f1 / d q1 */
}}
void jfgyrv(unsigned int n, const double* q, const double* v, double* j, unsigned int nz, double* z) {{
  (void)n; (void)nz; (void)z;
  const double s = sin(q[0] - q[1]);
  for (int i = 0; i < 9; ++i) j[i] = 0.0;
  j[3] = 2.0 * CC * s * v[1];
  j[1] = -2.0 * CC * s * v[0];
}}
"""]
    rows = 2 if friction else 1
    for k, (xi, eta, side) in enumerate(CORNERS):
        half = B + C
        src.append(f"""
void h{k}(unsigned int n, const double* q, unsigned int ny, double* y, unsigned int nz, double* z) {{
  (void)n; (void)ny; (void)nz; (void)z;
  const double yc = {L1!r} * sin(q[0]) + {L2!r} * sin(q[1]) + ({xi!r}) * sin(q[2]) + ({eta!r}) * cos(q[2]);
  y[0] = {'%r - yc' % half if side > 0 else 'yc + %r' % half};
""" + ("""  y[1] = %r * cos(q[0]) + %r * cos(q[1]) + (%r) * cos(q[2]) - (%r) * sin(q[2]);
""" % (L1, L2, xi, eta) if friction else "") + f"""}}
void jh{k}(unsigned int n, const double* q, unsigned int ny, double* j, unsigned int nz, double* z) {{
  (void)n; (void)ny; (void)nz; (void)z;
  const double s = {'-1.0' if side > 0 else '1.0'};
  j[0 * {rows}] = s * {L1!r} * cos(q[0]);
  j[1 * {rows}] = s * {L2!r} * cos(q[1]);
  j[2 * {rows}] = s * (({xi!r}) * cos(q[2]) - ({eta!r}) * sin(q[2]));
""" + ("""  j[0 * 2 + 1] = -%r * sin(q[0]);
  j[1 * 2 + 1] = -%r * sin(q[1]);
  j[2 * 2 + 1] = -(%r) * sin(q[2]) - (%r) * cos(q[2]);
""" % (L1, L2, xi, eta) if friction else "") + "}\n")
    return "".join(src)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out")
    ap.add_argument("--restitution", type=float, default=0.4)
    ap.add_argument("--friction", type=float, default=0.0)
    ap.add_argument("--step", type=float, default=1e-5)
    ap.add_argument("--duration", type=float, default=0.2)
    ap.add_argument("--theta", type=float, default=0.5, help="Moreau-Jean's theta")
    ap.add_argument("--driven", action="store_true", help="a crank of inertia 1e3 kg m^2 in place of a driver")
    ap.add_argument("--crank-speed", type=float, default=150.0, help="the crank's initial speed, rad/s")
    args = ap.parse_args()
    friction = args.friction > 0.0
    j1 = 1e3 if args.driven else J1

    work = tempfile.mkdtemp(prefix="flg_siconos_")
    src = os.path.join(work, "flg_plugins.c")
    lib = os.path.join(work, "flg_plugins.so")
    with open(src, "w") as f:
        f.write(plugin_source(friction, j1))
    subprocess.run(["cc", "-O2", "-shared", "-fPIC", "-o", lib, src, "-lm"], check=True)

    q0 = np.array([0.0, 0.0, 0.0])
    v0 = np.array([args.crank_speed, -0.5 * args.crank_speed, 0.0])
    ds = sk.LagrangianDS(q0, v0)
    ds.setComputeMassFunction(lib, "mass")
    ds.setComputeFGyrFunction(lib, "fgyr")
    ds.setComputeJacobianFGyrqFunction(lib, "jfgyrq")
    ds.setComputeJacobianFGyrqDotFunction(lib, "jfgyrv")

    t0, T = 0.0, args.duration
    nsds = sk.NonSmoothDynamicalSystem(t0, T)
    nsds.insertDynamicalSystem(ds)
    interactions = []
    for k in range(4):
        if friction:
            law = sk.NewtonImpactFrictionNSL(args.restitution, 0.0, args.friction, 2)
        else:
            law = sk.NewtonImpactNSL(args.restitution)
        stem = lib[:-3]  # Siconos appends the shared-library suffix itself
        rel = sk.LagrangianScleronomousR(stem + ":h%d" % k, stem + ":jh%d" % k)
        inter = sk.Interaction(law, rel)
        nsds.link(inter, ds)
        interactions.append(inter)

    td = sk.TimeDiscretisation(t0, args.step)
    osi = sk.MoreauJeanOSI(args.theta)
    osnspb = sk.FrictionContact(2) if friction else sk.LCP()
    sim = sk.TimeStepping(nsds, td, osi, osnspb)

    rows = []
    while sim.hasNextEvent():
        sim.computeOneStep()
        q = np.array(ds.q())
        v = np.array(ds.velocity())
        c12 = np.cos(q[0] - q[1])
        m11 = M1 * L1 * L1 / 4 + (M2 + M3) * L1 * L1 + j1
        m22 = M2 * L2 * L2 / 4 + M3 * L2 * L2 + J2
        m12 = (M2 / 2 + M3) * L1 * L2 * c12
        kinetic = 0.5 * (m11 * v[0] ** 2 + 2 * m12 * v[0] * v[1] + m22 * v[1] ** 2 + J3 * v[2] ** 2)
        potential = G * (L1 * (M1 / 2 + M2 + M3) * np.sin(q[0]) + L2 * (M2 / 2 + M3) * np.sin(q[1]))
        impulse = sum(float(np.abs(np.array(inter.lambda_(1))).max()) for inter in interactions)
        y_slider = L1 * np.sin(q[0]) + L2 * np.sin(q[1])
        vy_slider = L1 * np.cos(q[0]) * v[0] + L2 * np.cos(q[1]) * v[1]
        rows.append((sim.nextTime(), q[0], q[1], q[2], v[0], v[1], v[2], y_slider, kinetic + potential, impulse,
                     vy_slider))
        sim.nextStep()
    with open(args.out, "w") as f:
        f.write("# flg_siconos.py: Siconos %s MoreauJeanOSI(theta %g), h %g, e_N %g, mu %g, J1 %g\n"
                % (getattr(sk, "__version__", "4.4"), args.theta, args.step, args.restitution, args.friction, j1))
        f.write("# t\tcrank_angle\tconrod_angle\tslider_angle\tcrank_rate\tconrod_rate\tslider_rate\tslider_y\tenergy\timpulse\tslider_vy\n")
        for r in rows:
            f.write("\t".join("%.10g" % x for x in r) + "\n")


if __name__ == "__main__":
    main()
