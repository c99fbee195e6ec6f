"""Checks the bare closed form (benches/bare-oblique) against the numpy peer.

Reads the columns `bare-oblique --dump FILE` wrote (f64, little-endian, column
after column: the swept v_t, the numpy peer's outputs in the order of
`COLUMNS`, then V_ct of the one-output loop) and compares each with what
`numpy_peer.oblique_coulomb` and `final_tangential_contact_velocity` give on
`numpy_peer.points()`. Both evaluate the same formulas in the same order of
operations, so they must be bit-identical; the script prints the largest
difference in ulps per column and exits 1 unless every one is 0.

Usage: python bare_oblique_check.py DUMP
"""

from __future__ import annotations

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np  # noqa: E402

import numpy_peer  # noqa: E402

COLUMNS = [
    "/final_velocity/normal",
    "/final_velocity/tangential",
    "/final_velocity/angular",
    "/contact_velocity/initial/normal",
    "/contact_velocity/initial/tangential",
    "/contact_velocity/final/normal",
    "/contact_velocity/final/tangential",
    "/impulse/normal",
    "/impulse/tangential",
    "/impulse_ratio",
    "/critical_impulse_ratio",
    "/restitution",
    "/kinetic_restitution",
    "/regime",
    "/energy/initial",
    "/energy/final",
    "/energy/loss",
    "/energy/max_loss",
    "/energy/normalized_loss",
]


def ulps(a, b):
    """|a - b| in units in the last place, by the ordered integer images of the doubles."""
    def ordered(x):
        i = np.ascontiguousarray(x, dtype=np.float64).view(np.int64)
        return np.where(i < 0, np.int64(-0x8000000000000000) - i, i)
    return np.abs(ordered(a).astype(object) - ordered(b).astype(object)).max() if len(a) else 0


def main():
    dump = np.fromfile(sys.argv[1], dtype="<f8")
    n = numpy_peer.POINTS
    if dump.size != n * (len(COLUMNS) + 2):
        print(f"dump holds {dump.size} values, expected {n * (len(COLUMNS) + 2)}")
        return 1
    bare = dump.reshape(len(COLUMNS) + 2, n)
    vt = numpy_peer.points()
    worst = {"/velocity/tangential (linspace)": ulps(bare[0], vt)}
    ours = numpy_peer.oblique_coulomb(vt)
    for k, name in enumerate(COLUMNS, start=1):
        mine = np.broadcast_to(np.asarray(ours[name], dtype=np.float64), (n,))
        worst[name] = ulps(bare[k], mine)
    worst["V_ct, one output"] = ulps(bare[-1], numpy_peer.final_tangential_contact_velocity(vt))
    for name, value in worst.items():
        print(f"  {name}: largest difference {value} ulps")
    sticking = int(np.count_nonzero(bare[COLUMNS.index("/regime") + 1]))
    if any(worst.values()):
        print(f"FAIL: the bare closed form and numpy differ ({sticking} of {n} points sticking)")
        return 1
    print(f"OK: bare closed form and numpy bit-identical on all {len(worst)} columns, "
          f"{n} points ({sticking} sticking)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
