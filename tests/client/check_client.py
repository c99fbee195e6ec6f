"""Calls every endpoint through the client generated from openapi/openapi.json.

Usage: python check_client.py BASE_URL   (the generated package must be installed)
Exits non-zero if any call fails or any value is off.
"""

import json
import math
import sys

from restitution_client import Client
from restitution_client.api.impacts import (
    impacts_normal,
    impacts_oblique,
    impacts_planar,
    impacts_spatial,
    impacts_tangential,
    impacts_torsional,
)
from restitution_client.api.fits import fits_planar, fits_spatial, fits_tangential, fits_torsional
from restitution_client.api.service import healthz
from restitution_client.api.sweeps import plan, sweeps
from restitution_client.models import (
    NormalRequest,
    ObliqueRequest,
    PlanarContactRequest,
    PlanarFitRequest,
    PlanarFitResponse,
    PlanarContactResponse,
    PlanarResponse,
    PlanRequest,
    SweepPlan,
    SweepReduction,
    SpatialContactRequest,
    SpatialContactResponse,
    SpatialFitRequest,
    SpatialFitResponse,
    Problem,
    SweepRequest,
    TangentialFitRequest,
    TangentialFitResponse,
    TangentialRequest,
    TorsionalFitRequest,
    TorsionalRequest,
    TorsionalResponse,
)

FAILURES = []


def check(name, condition, detail=""):
    print(("ok   " if condition else "FAIL ") + name + (f": {detail}" if detail and not condition else ""))
    if not condition:
        FAILURES.append(name)


def close(a, b, tol=1e-12):
    return math.isclose(a, b, rel_tol=tol, abs_tol=tol)


def maw(vt, **law):
    request = {
        "body": {"mass": 1.0, "inertia": 0.00125},
        "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
        "velocity": {"normal": -1.0, "tangential": vt, "angular": 0.0},
        "restitution": 0.93,
    }
    request.update(law)
    return request


def main(base):
    client = Client(base_url=base, raise_on_unexpected_status=True)

    health = healthz.sync(client=client)
    check("healthz", health is not None and health.status == "ok")

    # Point mass: V_n = −e v_n, P_n = m (1 + e)|v_n|.
    body = NormalRequest.from_dict({"body": {"mass": 2.0}, "velocity": {"normal": -3.0}, "restitution": 0.5})
    out = impacts_normal.sync(client=client, body=body)
    check("normal", isinstance(out, PlanarResponse) and out.final_velocity.normal == 1.5
          and out.impulse.normal == 9.0 and out.regime == "frictionless", repr(out))

    # Maw disc sliding (Fig 3's sliding line): μ = −f, V_ct = v_ct − f (1 + e) 3 |v_n|.
    out = impacts_oblique.sync(client=client, body=ObliqueRequest.from_dict(maw(2.0, friction=0.123)))
    check("oblique sliding", isinstance(out, PlanarResponse) and out.impulse_ratio == -0.123
          and close(out.contact_velocity.final.tangential, 2.0 - 0.123 * 1.93 * 3), repr(out))

    # Maw disc, small slip: sticking with V_ct = 0.
    out = impacts_oblique.sync(client=client, body=ObliqueRequest.from_dict(maw(0.1, friction=0.123)))
    check("oblique sticking", isinstance(out, PlanarResponse) and out.regime == "sticking"
          and out.contact_velocity.final.tangential == 0.0, repr(out))

    # Tangential restitution branch: V_ct = −e_t v_ct.
    out = impacts_tangential.sync(client=client, body=TangentialRequest.from_dict(
        maw(0.1, friction=0.123, tangential_restitution=0.34)))
    check("tangential", isinstance(out, PlanarResponse) and out.regime == "restitution"
          and close(out.contact_velocity.final.tangential, -0.034), repr(out))

    # Torsional sliding branch (Eq 30 with the moment opposing the spin).
    request = {
        "body": {"mass": 0.6, "normal_inertia": 0.003456},
        "velocity": {"normal": -3.0, "spin": 20.0},
        "restitution": 0.7,
        "torsion": {"restitution": 0.2, "friction": 0.3, "pitch_radius": 0.01},
    }
    out = impacts_torsional.sync(client=client, body=TorsionalRequest.from_dict(request))
    switch = 0.3 * 0.01 * 0.6 * 1.7 * 3.0 / 0.003456
    check("torsional", isinstance(out, TorsionalResponse) and out.regime == "sliding"
          and close(out.final_velocity.spin, 0.8 * 20.0 - switch) and close(out.switch_spin, switch), repr(out))

    # Two cars (the planar endpoint's example): momentum of the pair conserved.
    cars = {
        "bodies": [
            {"mass": 1500.0, "inertia": 2500.0, "position": {"x": 0.0, "y": 0.0},
             "velocity": {"x": 15.0, "y": 0.0}, "angular_velocity": 0.0},
            {"mass": 1200.0, "inertia": 1800.0, "position": {"x": 3.0, "y": -1.5},
             "velocity": {"x": 0.0, "y": 12.0}, "angular_velocity": 0.0},
        ],
        "contact": {"point": {"x": 2.2, "y": -0.6}, "normal": {"x": -1.0, "y": 0.0}},
        "restitution": 0.2,
        "friction": 0.6,
    }
    out = impacts_planar.sync(client=client, body=PlanarContactRequest.from_dict(cars))
    check("planar", isinstance(out, PlanarContactResponse) and out.regime == "sticking"
          and close(1500.0 * out.bodies[0].velocity_change.x + 1200.0 * out.bodies[1].velocity_change.x, 0.0, 1e-9)
          and close(out.contact_velocity.final.normal, 3.0), repr(out))

    # A tennis ball with topspin in space (canonical tensor form): V_z = −e v_z.
    ball = {
        "bodies": [{"mass": 0.057,
                    "inertia": {"xx": 4.1e-5, "yy": 4.1e-5, "zz": 4.1e-5, "xy": 0.0, "xz": 0.0, "yz": 0.0},
                    "position": {"x": 0.0, "y": 0.0, "z": 0.033},
                    "velocity": {"x": 20.0, "y": 0.0, "z": -10.0},
                    "angular_velocity": {"x": 0.0, "y": 300.0, "z": 0.0}}],
        "contact": {"point": {"x": 0.0, "y": 0.0, "z": 0.0}, "normal": {"x": 0.0, "y": 0.0, "z": 1.0}},
        "restitution": 0.75,
        "friction": 0.6,
        "torsion": {"restitution": 0.3, "friction": 0.2, "pitch_radius": 0.005},
    }
    bounce = impacts_spatial.sync(client=client, body=SpatialContactRequest.from_dict(ball))
    check("spatial", isinstance(bounce, SpatialContactResponse) and close(bounce.bodies[0].velocity.z, 7.5)
          and bounce.energy.loss >= 0.0, repr(bounce))

    # A planar sweep over body B's speed, delta-V of both cars as columns.
    sweep = SweepRequest.from_dict({
        "case": "planar",
        "base": cars,
        "axes": [{"path": "/bodies/1/velocity/y", "values": [6.0, 12.0]}],
        "outputs": ["/bodies/0/delta_v", "/bodies/1/delta_v"],
    })
    response = sweeps.sync_detailed(client=client, body=sweep)
    table = json.loads(response.content)
    check("planar sweep", response.status_code == 200 and table["points"] == 2
          and close(table["rows"][1][1], out.bodies[0].delta_v) and close(table["rows"][1][2], out.bodies[1].delta_v),
          repr(table))

    # Reconstruction: e and μ back from the two cars' velocity changes.
    def measured(b):
        m = lambda v: {"value": v, "uncertainty": 0.1}
        return {"velocity_change": {"x": m(b.velocity_change.x), "y": m(b.velocity_change.y)},
                "angular_velocity_change": m(b.angular_velocity_change)}
    fit = fits_planar.sync(client=client, body=PlanarFitRequest.from_dict({
        "bodies": cars["bodies"], "contact": cars["contact"], "measured": [measured(b) for b in out.bodies]}))
    check("planar fit", isinstance(fit, PlanarFitResponse) and close(fit.restitution.value, 0.2, 1e-9)
          and close(fit.impulse_ratio.value, out.impulse_ratio, 1e-9), repr(fit))

    # A documented error comes back as a parsed problem.
    response = impacts_oblique.sync_detailed(client=client, body=ObliqueRequest.from_dict(maw(2.0, friction=-1.0)))
    check("problem", response.status_code == 422 and isinstance(response.parsed, Problem)
          and response.parsed.pointer == "/friction", repr(response.parsed))

    # A sweep of Figure 3's restitution line, as a JSON table.
    sweep = SweepRequest.from_dict({
        "case": "tangential",
        "base": maw(0.0, friction=0.123, tangential_restitution=0.34),
        "axes": [{"path": "/velocity/tangential", "values": [0.1, 0.2, 2.0]}],
        "outputs": ["/contact_velocity/final/tangential", "/regime"],
    })
    response = sweeps.sync_detailed(client=client, body=sweep)
    table = json.loads(response.content)
    check("sweep", response.status_code == 200 and table["points"] == 3
          and close(table["rows"][0][1], -0.034) and table["rows"][2][2] == "sliding", repr(table))

    # The plan of a larger sweep, one of its ranges, and its reduction, parsed as typed models.
    grid = {
        "case": "tangential",
        "base": maw(0.0, friction=0.123, tangential_restitution=0.34),
        "axes": [{"path": "/velocity/tangential", "linspace": {"start": -1.0, "stop": 5.0, "count": 1000}}],
        "outputs": ["/energy/loss", "/regime"],
    }
    layout = plan.sync(client=client, body=PlanRequest.from_dict({"sweep": grid, "shards": 3}))
    check("plan", isinstance(layout, SweepPlan) and layout.points == 1000 and len(layout.ranges) == 3
          and layout.ranges[1].start == 333 and layout.ranges[2].end == 1000, repr(layout))
    part = sweeps.sync_detailed(client=client, body=SweepRequest.from_dict(
        dict(grid, range=layout.ranges[1].to_dict())))
    check("range", part.status_code == 200 and json.loads(part.content)["points"] == 333, repr(part.content[:200]))
    reduced = sweeps.sync(client=client, body=SweepRequest.from_dict(dict(grid, reduce={"histograms": [
        {"output": "/energy/loss", "start": 0.0, "stop": 2.0, "bins": 4}]})))
    loss = reduced.outputs.additional_properties["/energy/loss"] if isinstance(reduced, SweepReduction) else None
    check("reduction", isinstance(reduced, SweepReduction) and reduced.points == 1000 and loss is not None
          and sum(loss.histogram.counts) + loss.histogram.below + loss.histogram.above == loss.count,
          repr(reduced))

    # Fit: coefficients back from observations the service itself computed.
    observations = []
    for vt in [0.05, 0.1, 0.2, 0.3, 1.0, 1.5, 2.0, 3.0]:
        out = impacts_tangential.sync(client=client, body=TangentialRequest.from_dict(
            maw(vt, friction=0.123, tangential_restitution=0.34)))
        observations.append({
            "body": {"mass": 1.0, "inertia": 0.00125},
            "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
            "initial": {"normal": -1.0, "tangential": vt, "angular": 0.0},
            "final": out.final_velocity.to_dict(),
        })
    fit = fits_tangential.sync(client=client, body=TangentialFitRequest.from_dict({"observations": observations}))
    check("fit", isinstance(fit, TangentialFitResponse) and close(fit.restitution.value, 0.93, 1e-9)
          and close(fit.friction.value, 0.123, 1e-9) and close(fit.tangential_restitution.value, 0.34, 1e-9),
          repr(fit))

    # Torsional fit from the rubber ball of examples/figure4 (switch 22.5 rad/s).
    ball = {"body": {"mass": 0.1, "normal_inertia": 0.000036}, "pitch_radius": 0.005}
    spins = [(-80.0, -41.5), (-10.0, 2.0), (5.0, -1.0), (10.0, -2.0), (40.0, 9.5), (80.0, 41.5)]
    torsional_fit = fits_torsional.sync(client=client, body=TorsionalFitRequest.from_dict({"observations": [
        dict(ball, initial={"normal": -3.0, "spin": w}, final={"normal": 2.4, "spin": s}) for w, s in spins]}))
    check("torsional fit", torsional_fit is not None and close(torsional_fit.torsional_restitution.value, 0.2, 1e-9)
          and close(torsional_fit.torsional_friction.value, 0.3, 1e-9), repr(torsional_fit))

    # Spatial fit: e and f back from two tennis-ball bounces answered above
    # through the client (one slides, one sticks).
    impacts = []
    for vx, wy in [(20.0, -300.0), (2.0, 0.0)]:
        scene = {"bodies": [{"mass": 0.057, "inertia": {"sphere": {"radius": 0.033, "hollow": True}},
                             "position": {"x": 0.0, "y": 0.0, "z": 0.033},
                             "velocity": {"x": vx, "y": 0.0, "z": -10.0},
                             "angular_velocity": {"x": 0.0, "y": wy, "z": 0.0}}],
                 "contact": {"point": {"x": 0.0, "y": 0.0, "z": 0.0}, "normal": {"x": 0.0, "y": 0.0, "z": 1.0}}}
        answer = impacts_spatial.sync(client=client, body=SpatialContactRequest.from_dict(
            dict(scene, restitution=0.75, friction=0.6)))
        dv = answer.bodies[0].velocity_change
        m = lambda v: {"value": v, "uncertainty": 0.01}
        impacts.append(dict(scene, measured=[{"velocity_change": {"x": m(dv.x), "y": m(dv.y), "z": m(dv.z)}}]))
    spatial_fit = fits_spatial.sync(client=client, body=SpatialFitRequest.from_dict({"law": "friction", "impacts": impacts}))
    fitted = {c.member: c.value for c in spatial_fit.coefficients} if isinstance(spatial_fit, SpatialFitResponse) else {}
    # Members are JSON pointers into the request.
    check("spatial fit", close(fitted.get("/restitution", math.nan), 0.75, 1e-9)
          and close(fitted.get("/friction", math.nan), 0.6, 1e-9), repr(spatial_fit))

    print(f"{len(FAILURES)} failed" if FAILURES else "all client checks passed")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
