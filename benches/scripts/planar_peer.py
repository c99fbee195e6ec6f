"""The numpy peer of the two-body planar sweep (``POST /v1/impacts/planar``):
two laminae in world axes, Coulomb friction, written the way a numpy user
would, vectorised over a grid of 200,000 points.

Scene (examples/planar_car_to_car_sweep.json): car A (m = 1500, I = 2500) at
the origin, car B (m = 1200, I = 1800) at (3, -1.5), contact at (2.2, -0.6)
with normal (-1, 0), e = 0.2, f = 0.6, no spin; the grid sweeps A's v_x over
linspace(5, 25, 400) and B's v_y over linspace(-30, 30, 500) (B's v_y the
faster axis, as the service orders a sweep). Two variants: every output the
service gives for the case, and the final tangential contact velocity V_t
alone. Each is timed best-of-N on one thread, points generated and solved,
in M points/s.

The model (docs/physics.md, "Two bodies in the plane"): with r_b = C - G_b,
t = z x n, rho_b = (r_b x n, r_b . n), alpha = |n|^2 (1/m_A + 1/m_B),
W = alpha 1 + sum rho_b rho_b^T / I_b in the (n, t) basis; the sticking answer
q = W^-1 ((1 + e) s, -u_t) (s = -u_n) if its ratio |mu_c| <= f, else sliding
with mu = -f sign(u_t): q_n = (1 + e) s / (W_nn + mu W_nt), q_t = mu q_n.

Then the peer checks itself against the service: ``restitution sweep`` on the
same grid with CSV output; every numeric column must agree within a few ulps
of the column's largest magnitude (TOLERANCE_ULPS); the largest difference in
ulps of the value itself is printed too (large where a value near zero comes
from cancellation, as a velocity change along y when the impulse is nearly
along x). mu_c = sdt / sdn, which passes a pole on this grid, is measured row
by row in ulps of its terms' magnitude
(|W_nt q_n| + |W_nn u_t| + |mu_c| (|W_tt q_n| + |W_nt u_t|)) / |sdn|. The regime must be the same string; the points the service refuses
(energy created) must be exactly those where the peer's T_L < 0. Like the
oblique peer it validates nothing and clamps nothing (the service clamps
E_final at 0 and T_L* at 1, which this scene never reaches).

With --time-service it times the service's own sweep of the grid instead:
``restitution sweep --format arrow`` to /dev/null, RAYON_NUM_THREADS=1, best
of N, minus the same on one point of the grid (the start-up).

Usage: python planar_peer.py [PATH/TO/restitution] [--repetitions N] [--no-check | --time-service]
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS",
             "VECLIB_MAXIMUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ[_var] = "1"

import json  # noqa: E402
import sys  # noqa: E402

import numpy as np  # noqa: E402

import numpy_peer  # noqa: E402

A_VX = (5.0, 25.0, 400)  # /bodies/0/velocity/x, the slower axis
B_VY = (-30.0, 30.0, 500)  # /bodies/1/velocity/y, the faster axis
POINTS = A_VX[2] * B_VY[2]

# The two cars of examples/planar_car_to_car_sweep.json (Coulomb friction 0.6).
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples",
                       "planar_car_to_car_sweep.json")) as _example:
    SCENE = json.load(_example)["base"]

TOLERANCE_ULPS = 8  # of each column's largest magnitude


def grid():
    """The swept (A's v_x, B's v_y) as flat arrays, B's v_y varying fastest."""
    ax, by = np.meshgrid(np.linspace(*A_VX), np.linspace(*B_VY), indexing="ij")
    return ax.ravel(), by.ravel()


def _scene():
    a, b = SCENE["bodies"]
    c = SCENE["contact"]
    return a, b, (c["point"]["x"], c["point"]["y"]), (c["normal"]["x"], c["normal"]["y"])


def planar_coulomb(avx, bvy):
    """Every output of the two-body planar Coulomb impact, keyed by the service's CSV columns."""
    a, b, (cx, cy), (nx, ny) = _scene()
    e, f = SCENE["restitution"], SCENE["friction"]
    ma, ia, mb, ib = a["mass"], a["inertia"], b["mass"], b["inertia"]
    avy, aw = a["velocity"]["y"], a["angular_velocity"]
    bvx, bw = b["velocity"]["x"], b["angular_velocity"]
    tx, ty = -ny, nx
    nn = nx * nx + ny * ny

    # Lever arms and contact-point velocities.
    rax, ray = cx - a["position"]["x"], cy - a["position"]["y"]
    rbx, rby = cx - b["position"]["x"], cy - b["position"]["y"]
    uax, uay = avx - aw * ray, avy + aw * rax
    ubx, uby = bvx - bw * rby, bvy + bw * rbx
    ux, uy = uax - ubx, uay - uby
    un = ux * nx + uy * ny
    ut = ux * tx + uy * ty

    # The contact space: rho_b = (r x n, r . n), W in the (n, t) basis.
    rhoan, rhoat = rax * ny - ray * nx, rax * nx + ray * ny
    rhobn, rhobt = rbx * ny - rby * nx, rbx * nx + rby * ny
    alpha = nn * (1.0 / ma + 1.0 / mb)
    wnn = alpha + rhoan * rhoan / ia + rhobn * rhobn / ib
    wnt = rhoan * rhoat / ia + rhobn * rhobt / ib
    wtt = alpha + rhoat * rhoat / ia + rhobt * rhobt / ib
    det = wnn * wtt - wnt * wnt

    # The sticking answer q = W^-1 ((1 + e) s, -u_t), scaled by det, and its ratio.
    qn_target = -(1.0 + e) * un
    sdn = wtt * qn_target + wnt * ut
    sdt = -wnt * qn_target - wnn * ut
    mu_c = sdt / sdn
    sticking = np.abs(sdt) <= f * np.abs(sdn)
    mu = np.where(sticking, mu_c, -np.copysign(f, ut))
    qn = np.where(sticking, sdn / det, qn_target / (wnn + mu * wnt))
    qt = mu * qn
    un_final = -e * un
    ut_final = np.where(sticking, 0.0, ut + wnt * qn + wtt * qt)

    # World impulse on A and each body's changes.
    px, py = nx * qn + tx * qt, ny * qn + ty * qt
    p_abs = np.hypot(px, py)
    dva_x, dva_y = px / ma, py / ma
    dvb_x, dvb_y = -px / mb, -py / mb
    dwa = (rhoan * qn + rhoat * qt) / ia
    dwb = -(rhobn * qn + rhobt * qt) / ib

    # Energies: T_L from the work of the impulse, T_M the plastic sticking loss.
    initial = 0.5 * (ma * (avx ** 2 + avy ** 2) + ia * aw ** 2) + 0.5 * (mb * (bvx ** 2 + bvy ** 2) + ib * bw ** 2)
    work = qn * (un + un_final) + qt * (ut + ut_final)
    loss = -0.5 * work
    lever_a = rhoat * un - rhoan * ut
    lever_b = rhobt * un - rhobn * ut
    max_loss = 0.5 * (alpha * (un ** 2 + ut ** 2) + lever_a ** 2 / ia + lever_b ** 2 / ib) / det

    norm = np.sqrt(nn)
    shape = np.shape(qn)
    full = lambda x: np.broadcast_to(x, shape)  # noqa: E731
    return {
        "/bodies/0/velocity/x": avx + dva_x,
        "/bodies/0/velocity/y": avy + dva_y,
        "/bodies/0/angular_velocity": aw + dwa,
        "/bodies/0/velocity_change/x": dva_x,
        "/bodies/0/velocity_change/y": dva_y,
        "/bodies/0/delta_v": p_abs / ma,
        "/bodies/0/angular_velocity_change": dwa,
        "/bodies/1/velocity/x": bvx + dvb_x,
        "/bodies/1/velocity/y": bvy + dvb_y,
        "/bodies/1/angular_velocity": bw + dwb,
        "/bodies/1/velocity_change/x": dvb_x,
        "/bodies/1/velocity_change/y": dvb_y,
        "/bodies/1/delta_v": p_abs / mb,
        "/bodies/1/angular_velocity_change": dwb,
        "/contact_velocity/initial/normal": full(un / norm),
        "/contact_velocity/initial/tangential": ut / norm,
        "/contact_velocity/final/normal": full(un_final / norm),
        "/contact_velocity/final/tangential": ut_final / norm,
        "/impulse/normal": qn * norm,
        "/impulse/tangential": qt * norm,
        "/impulse/x": px,
        "/impulse/y": py,
        "/impulse_ratio": mu,
        "/critical_impulse_ratio": mu_c,
        "/restitution": full(e),
        "/kinetic_restitution": full(e),
        "/regime": sticking,  # True: sticking, False: sliding
        "/energy/initial": initial,
        "/energy/final": initial - loss,
        "/energy/loss": loss,
        "/energy/max_loss": max_loss,
        "/energy/normalized_loss": loss / max_loss,
        # Not an output: the magnitude mu_c's terms have, for the cross-check
        # (mu_c = sdt / sdn swings through a pole where sdn crosses zero).
        "_mu_c_terms": (np.abs(wnt * qn_target) + np.abs(wnn * ut)
                        + np.abs(mu_c) * (np.abs(wtt * qn_target) + np.abs(wnt * ut))) / np.abs(sdn),
    }


def final_tangential_contact_velocity(avx, bvy):
    """V_t alone: 0 where the contact sticks, else the slip after sliding with mu = -f sign(u_t)."""
    a, b, (cx, cy), (nx, ny) = _scene()
    e, f = SCENE["restitution"], SCENE["friction"]
    ma, ia, mb, ib = a["mass"], a["inertia"], b["mass"], b["inertia"]
    avy, aw = a["velocity"]["y"], a["angular_velocity"]
    bvx, bw = b["velocity"]["x"], b["angular_velocity"]
    tx, ty = -ny, nx
    nn = nx * nx + ny * ny
    rax, ray = cx - a["position"]["x"], cy - a["position"]["y"]
    rbx, rby = cx - b["position"]["x"], cy - b["position"]["y"]
    ux = (avx - aw * ray) - (bvx - bw * rby)
    uy = (avy + aw * rax) - (bvy + bw * rbx)
    un = ux * nx + uy * ny
    ut = ux * tx + uy * ty
    rhoan, rhoat = rax * ny - ray * nx, rax * nx + ray * ny
    rhobn, rhobt = rbx * ny - rby * nx, rbx * nx + rby * ny
    alpha = nn * (1.0 / ma + 1.0 / mb)
    wnn = alpha + rhoan * rhoan / ia + rhobn * rhobn / ib
    wnt = rhoan * rhoat / ia + rhobn * rhobt / ib
    wtt = alpha + rhoat * rhoat / ia + rhobt * rhobt / ib
    qn_target = -(1.0 + e) * un
    sticking = np.abs(-wnt * qn_target - wnn * ut) <= f * np.abs(wtt * qn_target + wnt * ut)
    mu = -np.copysign(f, ut)
    slid = ut + (wnt + mu * wtt) * qn_target / (wnn + mu * wnt)
    return np.where(sticking, 0.0, slid) / np.sqrt(nn)


def request(outputs=None, one_point=False):
    """The service's sweep request for this grid (or one point of it)."""
    return numpy_peer.grid_request("planar", SCENE, [("/bodies/0/velocity/x", A_VX), ("/bodies/1/velocity/y", B_VY)], outputs, one_point)


def service_sweep(binary):
    """The service's answer on the grid (every output): the swept inputs, and CSV columns by name."""
    return numpy_peer.service_grid(binary, request())


def ulps(a, b):
    """Largest |a - b| in units in the last place (ordered integer images of the doubles)."""
    def ordered(x):
        i = np.ascontiguousarray(x, dtype=np.float64).view(np.int64)
        return np.where(i < 0, np.int64(-0x8000000000000000) - i, i)
    return int(np.abs(ordered(a).astype(object) - ordered(b).astype(object)).max()) if len(a) else 0


def column_ulps(ours, theirs):
    """Largest |ours - theirs| in ulps of the column's largest magnitude (the
    service's): values near zero that come from cancellation keep the absolute
    error of the terms they were formed from, which the value's own ulps magnify."""
    big = float(np.max(np.abs(theirs)))
    return float(np.max(np.abs(ours - theirs))) / np.spacing(big) if big else float(np.max(np.abs(ours)))


def cross_check(binary):
    """Compares both variants with the service; True when every column agrees."""
    (avx, bvy), service = service_sweep(binary)
    ours = planar_coulomb(avx, bvy)
    checked = numpy_peer.check_grid_and_refusals(service, (avx, bvy), grid(), ours, POINTS)
    if checked is None:
        return False
    agree, answered = checked
    ours = {name: np.asarray(value)[answered] for name, value in ours.items()}
    numeric = [name for name in ours if name != "/regime" and not name.startswith("_")]
    theirs = {name: np.array(service[name])[answered].astype(float) for name in numeric}
    worst_col, worst_ulps = (0.0, ""), (0, "")
    for name in numeric:
        if name == "/critical_impulse_ratio":
            # In ulps of its terms' magnitude, row by row, rather than of the column's largest.
            column = float(np.max(np.abs(ours[name] - theirs[name]) / np.spacing(ours["_mu_c_terms"])))
        else:
            column = column_ulps(ours[name], theirs[name])
        u = ulps(ours[name], theirs[name])
        if column > worst_col[0]:
            worst_col = (column, name)
        if u > worst_ulps[0]:
            worst_ulps = (u, name)
        unit = "its terms' magnitude" if name == "/critical_impulse_ratio" else "the column's largest magnitude"
        print(f"  {name}: {column:.3g} ulps of {unit}, {u} ulps of the value")
        if not column <= TOLERANCE_ULPS:
            agree = False
            print(f"  {name}: differs by more than {TOLERANCE_ULPS} ulps")
    print(f"all outputs: largest difference {worst_col[0]:.3g} ulps of the column's largest magnitude "
          f"({worst_col[1]}), largest in ulps of the value {worst_ulps[0]} ({worst_ulps[1]})")
    regime = np.where(ours["/regime"], "sticking", "sliding")
    mismatched = np.count_nonzero(regime != np.array(service["/regime"])[answered])
    print(f"regime: {mismatched} rows differ ({np.count_nonzero(ours['/regime'])} of "
          f"{np.count_nonzero(answered)} answered points sticking)")
    agree &= mismatched == 0
    one = final_tangential_contact_velocity(avx, bvy)[answered]
    name = "/contact_velocity/final/tangential"
    column = column_ulps(one, theirs[name])
    print(f"one output: {column:.3g} ulps of the column's largest magnitude, "
          f"{ulps(one, theirs[name])} ulps of the value")
    agree &= column <= TOLERANCE_ULPS
    return agree


def main():
    def requests():
        return {"all outputs": request(), "one output": request(["/contact_velocity/final/tangential"]),
                "point": request(one_point=True)}

    return numpy_peer.peer_main(__doc__.splitlines()[0], [("all outputs", planar_coulomb), ("one output", final_tangential_contact_velocity)],
                                POINTS, grid, requests, cross_check, TOLERANCE_ULPS)


if __name__ == "__main__":
    sys.exit(main())
