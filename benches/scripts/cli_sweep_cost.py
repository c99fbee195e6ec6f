"""The shipped binary's sweeps, before and after a change: ns per point of
`restitution sweep --format arrow` to /dev/null on one thread
(RAYON_NUM_THREADS=1) for two or more builds, rounds alternated, each figure
the best of three runs (start-up included: a few ms in 10^5 to 10^6 points).

A bench or driver in another crate compiles its own copy of the generic
model, which can run faster than the binary's (docs/performance-log.md,
2026-11-29): where the service is what matters, time the binary.

    cargo build --release && cp target/release/restitution /tmp/after
    git stash && cargo build --release && cp target/release/restitution /tmp/before && git stash pop
    python3 benches/scripts/cli_sweep_cost.py /tmp/before /tmp/after [ROUNDS]

Scenes: Figure 2's Coulomb scene (examples/figure2_coulomb_friction.json)
over 2 x 10^6 values of v_t, sliding ones (v_t in [2, 5]) with one output
(V_ct), and v_t in [-5, 5] with one output and with every output; the
two cars of examples/planar_car_to_car_sweep.json over 10^6 values of
car B's velocity, every output; Figure 4's rubber ball
(examples/figure4_torsional_rubber_ball.json) over 2 x 10^6 spins in
[-100, 100], every output; the topspin tennis ball
(examples/spatial_tennis_topspin.json) over sideways velocity x topspin,
400 x 500 points, every output.
"""
import copy, json, os, subprocess, sys, tempfile, time

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
WORK = tempfile.mkdtemp(prefix="cli-sweep-cost-")


def example(name):
    with open(os.path.join(ROOT, "examples", name)) as f:
        return json.load(f)


def oblique(start, stop, outputs):
    request = copy.deepcopy(example("figure2_coulomb_friction.json"))
    request["axes"] = [{"path": "/velocity/tangential", "linspace": {"start": start, "stop": stop, "count": 2_000_000}}]
    if outputs is None:
        request.pop("outputs")
    else:
        request["outputs"] = outputs
    return request


def cars():
    request = copy.deepcopy(example("planar_car_to_car_sweep.json"))
    request["axes"] = [{"path": "/bodies/1/velocity/y", "linspace": {"start": 2.0, "stop": 30.0, "count": 1_000_000}}]
    request.pop("outputs")
    return request


def torsional():
    request = copy.deepcopy(example("figure4_torsional_rubber_ball.json"))
    request["axes"] = [{"path": "/velocity/spin", "linspace": {"start": -100.0, "stop": 100.0, "count": 2_000_000}}]
    request.pop("outputs")
    return request


def tennis():
    return {
        "case": "spatial",
        "base": example("spatial_tennis_topspin.json"),
        "axes": [
            {"path": "/bodies/0/velocity/y", "linspace": {"start": -20.0, "stop": 20.0, "count": 400}},
            {"path": "/bodies/0/angular_velocity/y", "linspace": {"start": -900.0, "stop": 900.0, "count": 500}},
        ],
    }


V_CT = ["/contact_velocity/final/tangential"]
SCENES = {
    "figure 2, sliding, V_ct": (oblique(2.0, 5.0, V_CT), 2_000_000),
    "figure 2, V_ct": (oblique(-5.0, 5.0, V_CT), 2_000_000),
    "figure 2, every output": (oblique(-5.0, 5.0, None), 2_000_000),
    "two cars, every output": (cars(), 1_000_000),
    "figure 4 torsional, every output": (torsional(), 2_000_000),
    "tennis ball, every output": (tennis(), 200_000),
}


def main():
    binaries = sys.argv[1:]
    rounds = 3
    if binaries and binaries[-1].isdigit():
        rounds = int(binaries.pop())
    if len(binaries) < 2:
        raise SystemExit(__doc__)
    env = dict(os.environ, RAYON_NUM_THREADS="1")
    paths = {}
    for name, (request, _) in SCENES.items():
        paths[name] = os.path.join(WORK, f"{len(paths)}.json")
        with open(paths[name], "w") as f:
            json.dump(request, f)
    figures = {}
    for _ in range(rounds):
        for binary in binaries:
            for name, (_, points) in SCENES.items():
                best = float("inf")
                for _ in range(3):
                    start = time.perf_counter()
                    subprocess.run(
                        [binary, "sweep", "--request", paths[name], "--format", "arrow", "--output", "/dev/null"],
                        env=env,
                        check=True,
                    )
                    best = min(best, time.perf_counter() - start)
                figures.setdefault((name, binary), []).append(best / points * 1e9)
    print("| scene | " + " | ".join(binaries) + " |")
    print("| --- |" + " ---: |" * len(binaries))
    for name in SCENES:
        cells = ["/".join(f"{x:.0f}" for x in figures[(name, b)]) for b in binaries]
        print(f"| {name} | " + " | ".join(cells) + " |")
    print(f"\nns a point, {rounds} rounds (each the best of three runs), one thread")


if __name__ == "__main__":
    main()
