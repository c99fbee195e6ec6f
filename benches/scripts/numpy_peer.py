"""The numpy peer of ``benches/sweep.rs``: the oblique Coulomb-friction closed form
written the way a numpy user would, vectorised over the bench's 200,000 points.

Scene (``base()`` in benches/sweep.rs): a non-central lamina, m = 1, I = 0.00125,
d_c = 0.01, d_d = 0.05, v_n = -1, omega = 2, e = 0.93, f = 0.123, with v_t swept
over linspace(-5, 5, 200000). Two variants, as the bench's ``all_outputs`` and
``one_output``: every planar output, and the final tangential contact velocity
alone. Each is timed best-of-N on one thread (the BLAS/OpenMP thread counts are
set to 1 before numpy is imported; the closed form is elementwise anyway) and
reported in M points/s, min and median.

Then the peer checks itself against the service: it runs ``restitution sweep``
for the same sweep with CSV output and requires every numeric output column to
agree within 1e-12 of the row's scale (the largest magnitude among that row's
outputs) and the regime to be the same string, on the service's own points.
The service refuses the points whose answer would create energy (sliding just
past the switch, T_L < 0); the peer answers them, and they must be exactly the
points where its T_L < 0. Exit status 1 on any disagreement.

Like ``bare()`` in benches/sweep.rs, the peer validates nothing: no input
ranges, no refusals (D <= 0, energy created: those points are answered anyway),
no finiteness checks, and it takes the sliding direction from the sign of the
initial slip v_ct (the service also handles v_ct = 0 exactly, which this grid
does not contain). Outputs that do not vary along the sweep (e, v_cn, V_cn)
come out as numpy broadcasts them.

Usage: python numpy_peer.py [PATH/TO/restitution] [--repetitions N] [--no-check]
"""

from __future__ import annotations

import os

for _var in (
    "OMP_NUM_THREADS",
    "OPENBLAS_NUM_THREADS",
    "MKL_NUM_THREADS",
    "VECLIB_MAXIMUM_THREADS",
    "NUMEXPR_NUM_THREADS",
):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import csv  # noqa: E402
import json  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

POINTS = 200_000
SWEEP_START, SWEEP_STOP = -5.0, 5.0

# The bench's scene (benches/sweep.rs, base()).
MASS = 1.0
INERTIA = 0.00125
TANGENTIAL_OFFSET = 0.01  # d_c
NORMAL_OFFSET = 0.05  # d_d
NORMAL_VELOCITY = -1.0
ANGULAR_VELOCITY = 2.0
RESTITUTION = 0.93
FRICTION = 0.123

TOLERANCE = 1e-12


def oblique_coulomb(vt, m=MASS, inertia=INERTIA, dc=TANGENTIAL_OFFSET, dd=NORMAL_OFFSET,
                    vn=NORMAL_VELOCITY, w=ANGULAR_VELOCITY, e=RESTITUTION, f=FRICTION):
    """Every planar output of a lamina striking a barrier under Coulomb friction.

    Arguments broadcast against each other. Contact space per unit mass:
    A = k^2 + d_c^2, B = -d_c d_d, C = k^2 + d_d^2, det = k^2 S with
    S = k^2 + d_c^2 + d_d^2. The sticking impulse (U_n = -e v_cn, U_t = 0) has
    ratio mu_c; if |mu_c| <= f the contact sticks with mu = mu_c, else it slides
    with mu = -f sign(v_ct). Either way the impulse is the one with ratio mu
    that meets restitution: dn = k^2 q_n / (A + mu B), dt = mu dn.
    Returns a dict keyed by the service's CSV column names.
    """
    k2 = inertia / m
    vcn = vn + dc * w
    vct = vt - dd * w
    qn = -(1.0 + e) * vcn
    a, b, c = k2 + dc * dc, -dc * dd, k2 + dd * dd
    s = a + dd * dd

    # The sticking impulse, scaled by det (adj W q), and its ratio mu_c.
    det_dn = c * qn + b * vct
    det_dt = -b * qn - a * vct
    mu_c = det_dt / det_dn
    sticking = np.abs(mu_c) <= f
    mu = np.where(sticking, mu_c, -np.copysign(f, vct))

    per = qn / (a + mu * b)
    dn = k2 * per
    dt = mu * dn
    vct_final = np.where(sticking, 0.0, vct + (b + mu * c) * per)
    vcn_final = -e * vcn

    vn_final = vn + dn
    vt_final = vt + dt
    w_final = w + (dc - mu * dd) * per

    # Energies: T_L from the work of the impulse, T_M the loss when the contact
    # point ends at rest (src/model/barrier.rs, energy).
    initial = 0.5 * m * (vn * vn + vt * vt) + 0.5 * inertia * w * w
    work = dn * ((1.0 - e) * vcn) + dt * (vct + vct_final)
    loss = -0.5 * m * work
    lever = dd * vcn + dc * vct
    max_loss = 0.5 * m * (k2 * (vcn * vcn + vct * vct) + lever * lever) / s

    shape = np.shape(vt_final)
    return {
        "/final_velocity/normal": vn_final,
        "/final_velocity/tangential": vt_final,
        "/final_velocity/angular": w_final,
        "/contact_velocity/initial/normal": np.broadcast_to(vcn, shape),
        "/contact_velocity/initial/tangential": vct,
        "/contact_velocity/final/normal": np.broadcast_to(vcn_final, shape),
        "/contact_velocity/final/tangential": vct_final,
        "/impulse/normal": m * dn,
        "/impulse/tangential": m * dt,
        "/impulse_ratio": mu,
        "/critical_impulse_ratio": mu_c,
        "/restitution": np.broadcast_to(e, shape),
        "/kinetic_restitution": np.broadcast_to(e, shape),
        "/regime": sticking,  # True: sticking, False: sliding
        "/energy/initial": initial,
        "/energy/final": initial - loss,
        "/energy/loss": loss,
        "/energy/max_loss": max_loss,
        "/energy/normalized_loss": loss / max_loss,
    }


def final_tangential_contact_velocity(vt, m=MASS, inertia=INERTIA, dc=TANGENTIAL_OFFSET,
                                      dd=NORMAL_OFFSET, vn=NORMAL_VELOCITY, w=ANGULAR_VELOCITY,
                                      e=RESTITUTION, f=FRICTION):
    """V_ct alone: 0 where the contact sticks (|det dt| <= f |det dn|), else the
    slip after sliding with mu = -f sign(v_ct)."""
    k2 = inertia / m
    vct = vt - dd * w
    qn = -(1.0 + e) * (vn + dc * w)
    a, b, c = k2 + dc * dc, -dc * dd, k2 + dd * dd
    sticking = np.abs(b * qn + a * vct) <= f * np.abs(c * qn + b * vct)
    mu = -np.copysign(f, vct)
    return np.where(sticking, 0.0, vct + (b + mu * c) * qn / (a + mu * b))


def points():
    """The swept tangential velocities."""
    return np.linspace(SWEEP_START, SWEEP_STOP, POINTS)


def time_variant(solve, repetitions, inputs=None):
    """Seconds per sweep (inputs generated and solved) of each repetition after
    one warm-up; the inputs are this sweep's points unless another peer gives
    its own generator (a tuple of arguments)."""
    inputs = inputs or (lambda: (points(),))
    solve(*inputs())
    seconds = []
    for _ in range(repetitions):
        start = time.perf_counter()
        solve(*inputs())
        seconds.append(time.perf_counter() - start)
    return seconds


def print_rates(variants, points_per_sweep, repetitions, inputs=None, digits=1):
    """One line per (label, solve): M points/s, best and median."""
    for label, solve in variants:
        seconds = time_variant(solve, repetitions, inputs)
        best, median = min(seconds), statistics.median(seconds)
        print(f"{label}: {points_per_sweep / best / 1e6:.{digits}f} M points/s best ({best * 1e3:.2f} ms), "
              f"{points_per_sweep / median / 1e6:.{digits}f} M points/s median ({median * 1e3:.2f} ms)")


def service_sweep(binary):
    """The service's answer to the same sweep (every output), as CSV rows by column name."""
    request = {
        "case": "oblique",
        "base": {
            "body": {"mass": MASS, "inertia": INERTIA},
            "contact": {"tangential_offset": TANGENTIAL_OFFSET, "normal_offset": NORMAL_OFFSET},
            "velocity": {"normal": NORMAL_VELOCITY, "tangential": 0.0, "angular": ANGULAR_VELOCITY},
            "restitution": RESTITUTION,
            "friction": FRICTION,
        },
        "axes": [
            {"path": "/velocity/tangential",
             "linspace": {"start": SWEEP_START, "stop": SWEEP_STOP, "count": POINTS}},
        ],
    }
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "sweep.json")
        with open(path, "w") as file:
            json.dump(request, file)
        command = [binary, "sweep", "--request", path, "--format", "csv"]
        print("cross-check:", " ".join(command), flush=True)
        text = subprocess.run(command, check=True, capture_output=True, text=True, timeout=300).stdout
    rows = list(csv.reader(text.splitlines()))
    header, body = rows[0], rows[1:]
    return {name: [row[i] for row in body] for i, name in enumerate(header)}


def cross_check(binary):
    """Compares both variants with the service; True when every column agrees."""
    service = service_sweep(binary)
    if len(service["/regime"]) != POINTS:
        print(f"service answered {len(service['/regime'])} rows, expected {POINTS}")
        return False
    service_vt = np.array(service["/velocity/tangential"], dtype=float)
    print(f"points: largest |numpy linspace - service point| = {np.max(np.abs(points() - service_vt)):.3g}")

    # Checked on the service's own points, so only the model is compared.
    ours = oblique_coulomb(service_vt)

    # The service refuses the points whose answer would create energy (T_L < 0,
    # sliding just past the switch); the peer answers them regardless. The two
    # must name the same points.
    errors = np.array(service["error"])
    refused = errors != ""
    creates_energy = ours["/energy/loss"] < 0
    agree = bool(np.array_equal(refused, creates_energy))
    agree &= set(errors[refused].tolist()) <= {"Answer would create energy"}
    reasons = ", ".join(sorted(set(errors[refused].tolist()))) or "none"
    print(f"refused by the service: {np.count_nonzero(refused)} points ({reasons}); "
          f"numpy's T_L < 0 at {np.count_nonzero(creates_energy)}, "
          f"{'the same' if np.array_equal(refused, creates_energy) else 'NOT the same'} points")

    answered = ~refused
    ours = {name: np.asarray(value)[answered] for name, value in ours.items()}
    service = {name: np.array(column)[answered] for name, column in service.items()}
    numeric = [name for name in ours if name != "/regime"]
    theirs = {name: service[name].astype(float) for name in numeric}
    at = service_vt[answered].tolist()
    scale = np.max(np.abs(np.stack([theirs[name] for name in numeric])), axis=0)

    worst = (0.0, "", 0.0)
    for name in numeric:
        relative = np.abs(ours[name] - theirs[name]) / scale
        row = int(np.argmax(relative))
        if relative[row] > worst[0]:
            worst = (float(relative[row]), name, at[row])
        bad = np.count_nonzero(~(relative <= TOLERANCE))
        if bad:
            agree = False
            print(f"{name}: {bad} rows differ by more than {TOLERANCE:g} of the row's scale "
                  f"(worst at v_t = {at[row]!r}: numpy {float(ours[name][row])!r}, "
                  f"service {float(theirs[name][row])!r})")
    print(f"all outputs: largest difference {worst[0]:.3g} of the row's scale "
          f"({worst[1]} at v_t = {worst[2]!r})")

    regime = np.where(ours["/regime"], "sticking", "sliding")
    mismatched = np.count_nonzero(regime != service["/regime"])
    print(f"regime: {mismatched} rows differ ({np.count_nonzero(ours['/regime'])} of "
          f"{np.count_nonzero(answered)} answered points sticking)")
    agree &= mismatched == 0

    one = final_tangential_contact_velocity(service_vt)[answered]
    name = "/contact_velocity/final/tangential"
    relative = np.abs(one - theirs[name]) / scale
    print(f"one output: largest difference {np.max(relative):.3g} of the row's scale")
    agree &= bool(np.all(relative <= TOLERANCE))
    return agree


def grid_request(case, scene, axes, outputs=None, one_point=False):
    """A sweep request of ``case`` from ``scene`` over ``axes`` ((path, (start, stop, count))
    each, the first the slowest), with ``outputs`` (every output when None), or its first point."""
    body = {"case": case, "base": scene, "axes": [
        {"path": path, "linspace": {"start": start, "stop": stop, "count": 1 if one_point else count}}
        for path, (start, stop, count) in axes]}
    if outputs:
        body["outputs"] = outputs
    return body


def service_grid(binary, body):
    """The service's answer to a two-axis sweep ``body`` as CSV: the swept inputs (the
    first two columns, in request order) as arrays, and every column by name (an axis's
    name that comes again among the outputs keeps the output's values)."""
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "sweep.json")
        with open(path, "w") as file:
            json.dump(body, file)
        command = [binary, "sweep", "--request", path, "--format", "csv"]
        print("cross-check:", " ".join(command), flush=True)
        text = subprocess.run(command, check=True, capture_output=True, text=True, timeout=300).stdout
    rows = list(csv.reader(text.splitlines()))
    header, values = rows[0], rows[1:]
    inputs = [np.array([row[i] for row in values], dtype=float) for i in (0, 1)]
    return inputs, {name: [row[i] for row in values] for i, name in enumerate(header)}


def check_grid_and_refusals(service, inputs, grid, ours, points_per_sweep):
    """The part of a grid peer's cross-check before its columns: the service answered
    every point, its grid is numpy's, and it refused exactly the points where numpy's
    T_L < 0. Returns (agree, the answered points' mask), or None when rows are missing."""
    if len(service["/regime"]) != points_per_sweep:
        print(f"service answered {len(service['/regime'])} rows, expected {points_per_sweep}")
        return None
    print(f"points: numpy's grid and the service's differ by at most "
          f"{max(float(np.max(np.abs(g - i))) for g, i in zip(grid, inputs)):.3g}")
    errors = np.array(service["error"])
    refused = errors != ""
    creates_energy = ours["/energy/loss"] < 0
    agree = bool(np.array_equal(refused, creates_energy))
    print(f"refused by the service: {np.count_nonzero(refused)} points "
          f"({', '.join(sorted(set(errors[refused].tolist()))) or 'none'}); numpy's T_L < 0 at "
          f"{np.count_nonzero(creates_energy)}")
    return agree, ~refused


def time_service(binary, repetitions, points_per_sweep, requests):
    """The service's own sweep of a grid, one thread: ``restitution sweep --format arrow``
    to /dev/null with RAYON_NUM_THREADS=1, best of N wall-clock seconds, minus the best of
    N of the same command on one point of the grid (start-up, parsing, the Arrow schema).
    ``requests``: the request bodies for "all outputs", "one output" and "point"."""
    env = dict(os.environ, RAYON_NUM_THREADS="1")

    def best(path):
        seconds = []
        for _ in range(repetitions + 1):
            start = time.perf_counter()
            subprocess.run([binary, "sweep", "--request", path, "--format", "arrow"], check=True,
                           stdout=subprocess.DEVNULL, env=env, timeout=300)
            seconds.append(time.perf_counter() - start)
        return min(seconds[1:])

    with tempfile.TemporaryDirectory() as tmp:
        paths = {}
        for index, (name, body) in enumerate(requests.items()):
            paths[name] = os.path.join(tmp, f"{index}.json")
            with open(paths[name], "w") as file:
                json.dump(body, file)
        start_up = best(paths["point"])
        print(f"service: {binary} sweep --format arrow > /dev/null, RAYON_NUM_THREADS=1, best of "
              f"{repetitions}, minus one point's run ({start_up * 1e3:.2f} ms)")
        for label in ["all outputs", "one output"]:
            seconds = best(paths[label]) - start_up
            print(f"{label}: {points_per_sweep / seconds / 1e6:.2f} M points/s best ({seconds * 1e3:.2f} ms)")


def peer_main(description, variants, points_per_sweep, grid, requests, cross_check, tolerance_ulps):
    """A grid peer's command line: times ``variants`` (numpy) on ``grid``, or with
    --time-service the service's sweep of ``requests()``, then checks the peer against
    the service with ``cross_check`` unless --no-check. Returns the exit status."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("binary", nargs="?", default="target/release/restitution")
    parser.add_argument("--repetitions", type=int, default=20)
    parser.add_argument("--no-check", action="store_true")
    parser.add_argument("--time-service", action="store_true",
                        help="time the service's sweep of the grid instead of numpy")
    args = parser.parse_args()
    if args.time_service:
        time_service(args.binary, args.repetitions, points_per_sweep, requests())
        return 0
    print(f"numpy {np.__version__}, python {sys.version.split()[0]}, {points_per_sweep} points, "
          f"best of {args.repetitions}, one thread")
    print_rates(variants, points_per_sweep, args.repetitions, inputs=grid, digits=2)
    if args.no_check:
        return 0
    if not cross_check(args.binary):
        print("FAIL: numpy and the service disagree")
        return 1
    print(f"OK: numpy agrees with the service within {tolerance_ulps} ulps of each column's largest magnitude")
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("binary", nargs="?", default="target/release/restitution",
                        help="the restitution binary for the cross-check")
    parser.add_argument("--repetitions", type=int, default=20)
    parser.add_argument("--no-check", action="store_true",
                        help="time only (benches/scripts/numpy-vs-sweep checks once, then times)")
    args = parser.parse_args()

    print(f"numpy {np.__version__}, python {sys.version.split()[0]}, {POINTS} points, "
          f"best of {args.repetitions}, one thread")
    print_rates([("all outputs", oblique_coulomb), ("one output", final_tangential_contact_velocity)],
                POINTS, args.repetitions)

    if args.no_check:
        return 0
    if not cross_check(args.binary):
        print("FAIL: numpy and the service disagree")
        return 1
    print(f"OK: numpy agrees with the service within {TOLERANCE:g} of each row's scale")
    return 0


if __name__ == "__main__":
    sys.exit(main())
