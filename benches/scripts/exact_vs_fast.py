"""`exact` against `fast` per swept point, for every scene in examples/.

Each example becomes a sweep of N points (default 10^5): a sweep request's
first axis with N values, or a single impact's body A velocity x over
+-10 % (at least +-0.1). Each sweep runs through `restitution sweep` to an
Arrow file on one core (RAYON_NUM_THREADS=1), best of ROUNDS, less the best
of a 1-point run of the same request (the process's start-up).

    python3 benches/scripts/exact_vs_fast.py target/release/restitution . [ROUNDS]
    N=10000 python3 benches/scripts/exact_vs_fast.py ...
"""
import copy, glob, json, os, subprocess, sys, tempfile, time
WORK = tempfile.mkdtemp(prefix="exact-vs-fast-")
REQ, REQ1, OUT = (os.path.join(WORK, n) for n in ("req.json", "req1.json", "out.arrow"))
binary = sys.argv[1]
root = sys.argv[2]
rounds = int(sys.argv[3]) if len(sys.argv) > 3 else 3
N = int(os.environ.get("N", "100000"))
def request(path):
    d = json.load(open(path))
    name = os.path.basename(path)
    if 'case' in d:
        d = copy.deepcopy(d)
        ax = d['axes'][0]
        d['axes'] = [ax]
        lin = ax.get('linspace')
        if lin is None:
            raise SystemExit(f"{name}: axis form {ax}")
        lin['count'] = N
        d['base'].pop('precision', None)
        return d
    case = name.split('_')[0]
    base = copy.deepcopy(d)
    base.pop('precision', None)
    b0 = base['bodies'][0]['velocity']
    key = 'x'
    v = b0[key]
    span = max(abs(v), 1.0) * 0.1
    axis = {"path": f"/bodies/0/velocity/{key}", "linspace": {"start": v - span, "stop": v + span, "count": N}}
    return {"case": case, "base": base, "axes": [axis]}
def timed(extra):
    t = time.perf_counter()
    subprocess.run([binary, "sweep", "--request", extra[0], "--output", OUT, "--format", "arrow"], env=env, capture_output=True, check=True)
    return time.perf_counter() - t
env = dict(os.environ, RAYON_NUM_THREADS="1")
for path in sorted(glob.glob(f"{root}/examples/*.json")):
    name = os.path.basename(path)
    req = request(path)
    res = {}
    for prec in ("fast", "exact"):
        r = dict(req, precision=prec)
        with open(REQ, "w") as f:
            json.dump(r, f)
        best = 1e9
        r1 = copy.deepcopy(r); r1['axes'][0]['linspace']['count'] = 1
        with open(REQ1, "w") as f:
            json.dump(r1, f)
        base_t = min(timed([REQ1]) for _ in range(rounds))
        for _ in range(rounds):
            t = time.perf_counter()
            p = subprocess.run([binary, "sweep", "--request", REQ, "--output", OUT, "--format", "arrow"], env=env, capture_output=True, text=True)
            dt = time.perf_counter() - t
            if p.returncode != 0:
                print(name, prec, "failed", p.stderr[:300]); break
            best = min(best, dt - base_t)
        res[prec] = best
    # subtract process start-up: a 1-point sweep
    print(f"{name:45s} fast {res['fast']*1e6/N:9.2f} us/pt  exact {res['exact']*1e6/N:9.2f} us/pt  ratio {res['exact']/res['fast']:6.2f}", flush=True)
