"""The numpy peer of the spatial sweep (``POST /v1/impacts/spatial``): one body
against a barrier in world axes, Coulomb friction, the slip in any direction,
written the way a numpy user would, vectorised over a grid of 200,000 points.

Scene (examples/spatial_tennis_topspin.json): a tennis ball, m = 0.057, a
hollow sphere of radius 0.033 (I = 2/3 m r^2), its centre at (0, 0, 0.033),
v = (20, 0, -10), omega = (0, 300, 0) (topspin), on the level court (contact
at the origin, n = (0, 0, 1)), e = 0.75, f = 0.6, no twist law. The example
has no axes; the grid sweeps the ball's sideways velocity v_y over
linspace(-20, 20, 400) and its topspin omega_y over linspace(-900, 900, 500)
(omega_y the faster axis, as the service orders a sweep), so the slip
u_t = (20 - 0.033 omega_y, v_y, 0) turns in the court's plane and the contact
sticks inside a circle |u_t| <= 26.25 and slides outside it. Two variants:
every output the service gives for the case, and one output, the final slip
along the shot, U_tx (/contact_velocity/final/tangential/x; 0 where the ball
grips). Each is timed best-of-N on one thread, points generated and solved,
in M points/s.

The model (docs/physics.md, "Space"): with r = C - G, [r]x its cross-product
matrix and I^-1 the inverse inertia tensor in world axes, the contact-space
matrix is W = 1/m + [r]x^T I^-1 [r]x (Delta u = W P). With u = v + omega x r,
nu = |n|^2, u_n = u.n, the slip u_t = u - (u_n/nu) n and q = -(1 + e) u_n:
the sticking impulse P = W^-1 (q n/nu - u_t) (Delta u stops the slip and meets
Eq 1); it is kept when nu |P_t|^2 <= f^2 (P.n)^2, where
P_t = P - (P.n)/nu n; otherwise the ball slides against the initial slip,
P = p d with d = n - f sqrt(nu/|u_t|^2) u_t and p = q / (n.W d), so that
|P_t| = f P_n. Then U_t is 0 (sticking) or the tangential part of u + W P, the
loss T_L = -1/2 [(1 - e) u_n P.n/nu + P.(u_t + U_t)] (the work of the
impulse), T_M = 1/2 u^T W^-1 u, and each body output from m dV = P,
I dOmega = r x P. No twist law: the spin about the normal changes only through
w.P with w = (I^-1 n) x r, and the couple is 0.

Then the peer checks itself against the service: ``restitution sweep`` on the
same grid with CSV output; every numeric column must agree within a few ulps
of the column's largest magnitude (TOLERANCE_ULPS); the largest difference in
ulps of the value itself is printed too. The regime must be the same string;
the points the service refuses must be exactly those where the peer's
T_L < 0 (none on this grid: a sphere on a plane has a diagonal W); the
service's columns the peer does not compute (body B's, the torsional regime)
must be empty. Like the other peers it validates nothing and clamps nothing
(the service clamps E_final at 0 and T_L* at 1, which this scene never
reaches).

With --time-service it times the service's own sweep of the grid instead:
``restitution sweep --format arrow`` to /dev/null, RAYON_NUM_THREADS=1, best
of N, minus the same on one point of the grid (the start-up).

Usage: python spatial_peer.py [PATH/TO/restitution] [--repetitions N] [--no-check | --time-service]
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
from planar_peer import column_ulps, ulps  # noqa: E402

V_Y = (-20.0, 20.0, 400)  # /bodies/0/velocity/y, the slower axis
W_Y = (-900.0, 900.0, 500)  # /bodies/0/angular_velocity/y, the faster axis
POINTS = V_Y[2] * W_Y[2]
ONE_OUTPUT = "/contact_velocity/final/tangential/x"

# The tennis ball of examples/spatial_tennis_topspin.json (Coulomb friction 0.6).
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples",
                       "spatial_tennis_topspin.json")) as _example:
    SCENE = json.load(_example)

TOLERANCE_ULPS = 8  # of each column's largest magnitude


def grid():
    """The swept (v_y, omega_y) as flat arrays, omega_y varying fastest."""
    vy, wy = np.meshgrid(np.linspace(*V_Y), np.linspace(*W_Y), indexing="ij")
    return vy.ravel(), wy.ravel()


def _vector(member):
    return np.array([member["x"], member["y"], member["z"]], dtype=float)


def _scene():
    """The constants of the scene: mass, inertia tensor and its inverse, r = C - G,
    the (unnormalised) normal, W and W^-1, w of the spin about the normal, e, f."""
    (body,) = SCENE["bodies"]
    m = body["mass"]
    sphere = body["inertia"]["sphere"]
    inertia = np.eye(3) * ((2.0 / 3.0 if sphere.get("hollow") else 0.4) * m * sphere["radius"] ** 2)
    inv_i = np.linalg.inv(inertia)
    r = _vector(SCENE["contact"]["point"]) - _vector(body["position"])
    n = _vector(SCENE["contact"]["normal"])
    rx = np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])
    w_matrix = np.eye(3) / m + rx.T @ inv_i @ rx
    return (body, m, inertia, inv_i, r, n, w_matrix, np.linalg.inv(w_matrix),
            np.cross(inv_i @ n, r), SCENE["restitution"], SCENE["friction"])


def _state(body, vy, wy):
    """Each point's velocity and angular velocity, (N, 3), the swept y components set."""
    v = np.tile(_vector(body["velocity"]), (len(vy), 1))
    w = np.tile(_vector(body["angular_velocity"]), (len(wy), 1))
    v[:, 1] = vy
    w[:, 1] = wy
    return v, w


def spatial_coulomb(vy, wy):
    """Every output of the ball's impact on the court, keyed by the service's CSV columns."""
    body, m, inertia, inv_i, r, n, w_matrix, inv_w, w_spin, e, f = _scene()
    nu = n @ n
    root_nu = np.sqrt(nu)
    v, w = _state(body, vy, wy)

    # The contact-point velocity, its normal part and the slip.
    u = v + np.cross(w, r)
    un = u @ n
    ut = u - np.outer(un / nu, n)
    q = -(1.0 + e) * un

    # The sticking impulse: W P = q n/nu - u_t; kept when nu |P_t|^2 <= f^2 (P.n)^2.
    stick = (np.outer(q / nu, n) - ut) @ inv_w
    stick_n = stick @ n
    stick_t = stick - np.outer(stick_n / nu, n)
    stick_t2 = np.einsum("ij,ij->i", stick_t, stick_t)
    sticking = nu * stick_t2 <= (f * stick_n) ** 2

    # Sliding against the initial slip: P = p d, d = n - f sqrt(nu/|u_t|^2) u_t, n.W d p = q.
    slip2 = np.einsum("ij,ij->i", ut, ut)
    d = n - (f * np.sqrt(nu / slip2))[:, None] * ut
    slide = (q / (d @ (w_matrix @ n)))[:, None] * d

    p = np.where(sticking[:, None], stick, slide)
    pn = p @ n
    pt = p - np.outer(pn / nu, n)
    du = p @ w_matrix
    ut_final = np.where(sticking[:, None], 0.0, ut + du - np.outer((du @ n) / nu, n))
    ratio = np.where(sticking, np.sqrt(nu * np.einsum("ij,ij->i", pt, pt)) / np.abs(pn), f)
    mu_c = np.sqrt(nu * stick_t2) / np.abs(stick_n)

    # Body changes: m dV = P, I dOmega = r x P.
    dv = p / m
    dw = np.cross(r, p) @ inv_i
    spin = w @ n

    # Energies: T_L from the work of the impulse, T_M = 1/2 u^T W^-1 u.
    initial = 0.5 * (m * np.einsum("ij,ij->i", v, v) + np.einsum("ij,ij->i", w @ inertia, w))
    work = (1.0 - e) * un * pn / nu + np.einsum("ij,ij->i", p, ut + ut_final)
    loss = -0.5 * work
    max_loss = 0.5 * np.einsum("ij,ij->i", u @ inv_w, u)

    shape = np.shape(pn)
    full = lambda x: np.broadcast_to(x, shape)  # noqa: E731
    xyz = "xyz"
    out = {}
    for k in range(3):
        out[f"/bodies/0/velocity/{xyz[k]}"] = v[:, k] + dv[:, k]
    for k in range(3):
        out[f"/bodies/0/angular_velocity/{xyz[k]}"] = w[:, k] + dw[:, k]
    for k in range(3):
        out[f"/bodies/0/velocity_change/{xyz[k]}"] = dv[:, k]
    out["/bodies/0/delta_v"] = np.sqrt(np.einsum("ij,ij->i", p, p)) / m
    for k in range(3):
        out[f"/bodies/0/angular_velocity_change/{xyz[k]}"] = dw[:, k]
    out["/contact_velocity/initial/normal"] = un / root_nu
    for k in range(3):
        out[f"/contact_velocity/initial/tangential/{xyz[k]}"] = ut[:, k]
    out["/contact_velocity/initial/spin"] = spin / root_nu
    out["/contact_velocity/final/normal"] = -e * un / root_nu
    for k in range(3):
        out[f"/contact_velocity/final/tangential/{xyz[k]}"] = ut_final[:, k]
    out["/contact_velocity/final/spin"] = (spin + p @ w_spin) / root_nu
    out["/impulse/normal"] = pn / root_nu
    for k in range(3):
        out[f"/impulse/tangential/{xyz[k]}"] = pt[:, k]
    out["/impulse/torsional"] = full(0.0)
    for k in range(3):
        out[f"/impulse/{xyz[k]}"] = p[:, k]
    out.update({
        "/impulse_ratio": ratio,
        "/critical_impulse_ratio": mu_c,
        "/restitution": full(e),
        "/regime": sticking,  # True: sticking, False: sliding
        "/energy/initial": initial,
        "/energy/final": initial - loss,
        "/energy/loss": loss,
        "/energy/max_loss": max_loss,
        "/energy/normalized_loss": loss / max_loss,
    })
    return out


def final_slip_along_the_shot(vy, wy):
    """U_tx alone: 0 where the ball grips, else the slip along x after sliding against u_t."""
    body, m, inertia, inv_i, r, n, w_matrix, inv_w, w_spin, e, f = _scene()
    nu = n @ n
    v, w = _state(body, vy, wy)
    u = v + np.cross(w, r)
    un = u @ n
    ut = u - np.outer(un / nu, n)
    q = -(1.0 + e) * un
    stick = (np.outer(q / nu, n) - ut) @ inv_w
    stick_n = stick @ n
    stick_t = stick - np.outer(stick_n / nu, n)
    sticking = nu * np.einsum("ij,ij->i", stick_t, stick_t) <= (f * stick_n) ** 2
    d = n - (f * np.sqrt(nu / np.einsum("ij,ij->i", ut, ut)))[:, None] * ut
    wn = w_matrix @ n
    du = (q / (d @ wn))[:, None] * (d @ w_matrix)
    return np.where(sticking, 0.0, ut[:, 0] + du[:, 0] - (du @ n) / nu * n[0])


def request(outputs=None, one_point=False):
    """The service's sweep request for this grid (or one point of it)."""
    return numpy_peer.grid_request("spatial", SCENE, [("/bodies/0/velocity/y", V_Y), ("/bodies/0/angular_velocity/y", W_Y)], outputs, one_point)


def service_sweep(binary):
    """The service's answer on the grid (every output): the swept inputs, and CSV columns by name."""
    return numpy_peer.service_grid(binary, request())


def cross_check(binary):
    """Compares both variants with the service; True when every column agrees."""
    (vy, wy), service = service_sweep(binary)
    ours = spatial_coulomb(vy, wy)
    checked = numpy_peer.check_grid_and_refusals(service, (vy, wy), grid(), ours, POINTS)
    if checked is None:
        return False
    agree, answered = checked
    missing = [name for name in ours if name not in service]
    if missing:
        agree = False
        print(f"columns the service does not give: {', '.join(missing)}")
    others = [name for name in service if name not in ours and name != "error"
              and name not in ("/bodies/0/velocity/y", "/bodies/0/angular_velocity/y")]
    filled = [name for name in others if any(np.array(service[name])[answered] != "")]
    print(f"service columns numpy does not compute: {len(others)}, "
          f"{'all empty' if not filled else 'NOT empty: ' + ', '.join(filled)}")
    agree &= not filled

    ours = {name: np.asarray(value)[answered] for name, value in ours.items() if name not in missing}
    numeric = [name for name in ours if name != "/regime"]
    theirs = {name: np.array(service[name])[answered].astype(float) for name in numeric}
    worst_col, worst_ulps = (0.0, ""), (0, "")
    for name in numeric:
        column = column_ulps(ours[name], theirs[name])
        u = ulps(ours[name], theirs[name])
        if column > worst_col[0]:
            worst_col = (column, name)
        if u > worst_ulps[0]:
            worst_ulps = (u, name)
        print(f"  {name}: {column:.3g} ulps of the column's largest magnitude, {u} ulps of the value")
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
    one = final_slip_along_the_shot(vy, wy)[answered]
    column = column_ulps(one, theirs[ONE_OUTPUT])
    print(f"one output ({ONE_OUTPUT}): {column:.3g} ulps of the column's largest magnitude, "
          f"{ulps(one, theirs[ONE_OUTPUT])} ulps of the value")
    agree &= column <= TOLERANCE_ULPS
    return agree


def main():
    def requests():
        return {"all outputs": request(), "one output": request([ONE_OUTPUT]),
                "point": request(one_point=True)}

    return numpy_peer.peer_main(__doc__.splitlines()[0], [("all outputs", spatial_coulomb), ("one output", final_slip_along_the_shot)],
                                POINTS, grid, requests, cross_check, TOLERANCE_ULPS)


if __name__ == "__main__":
    sys.exit(main())
