#!/usr/bin/env python3
"""memload: start the restitution server on loopback, drive sweeps or single
impacts at it, and record its resident memory.

Subcommands:
  bodies DIR EXAMPLES   write the request bodies (every case, every format)
  sweep  ...            one configuration: N concurrent sweeps, fast or slow readers
  mixed  ...            single-impact load with wrk (idle RSS before and after)

Every run starts its own server (so VmHWM is that run's peak), samples
/proc/PID/status every 10 ms (VmRSS, VmHWM, Threads) and `ss -tmn` every
second (bytes queued in the server's socket send buffers: kernel memory, not
in RSS, but charged to a container's memory cgroup), and appends one JSON
line to the results file. Only 127.0.0.1 is ever connected to; every load is
bounded by --duration, every wait by a timeout.
"""
import argparse
import asyncio
import copy
import json
import os
import re
import signal
import socket
import subprocess
import sys
import threading
import time
import urllib.request

HOST = "127.0.0.1"  # the only address this tool connects to


# ---------------------------------------------------------------- bodies ---

ONE_BODY = {
    "normal": {"body": {"mass": 2.0, "inertia": 0.3},
               "contact": {"tangential_offset": 0.2, "normal_offset": 0.5},
               "velocity": {"normal": -3.0, "tangential": 0.3, "angular": 0.2},
               "restitution": 0.5},
    "oblique": {"body": {"mass": 1.0, "inertia": 0.00125},
                "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
                "velocity": {"normal": -1.0, "tangential": 2.0, "angular": 0.0},
                "restitution": 0.93, "friction": 0.123},
    "tangential": {"body": {"mass": 1.0, "inertia": 0.00125},
                   "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
                   "velocity": {"normal": -1.0, "tangential": 0.1, "angular": 0.0},
                   "restitution": 0.93, "friction": 0.123, "tangential_restitution": 0.34},
    "torsional": {"body": {"mass": 0.6, "normal_inertia": 0.003456},
                  "velocity": {"normal": -3.0, "spin": 20.0}, "restitution": 0.7,
                  "torsion": {"restitution": 0.2, "friction": 0.3, "pitch_radius": 0.01}},
}

# Two swept inputs per case: (path, start, stop).
AXES = {
    "normal": [("/velocity/normal", -5.0, -0.5), ("/restitution", 0.1, 0.9)],
    "oblique": [("/velocity/tangential", 0.0, 5.0), ("/friction", 0.05, 0.8)],
    "tangential": [("/velocity/tangential", 0.0, 5.0), ("/friction", 0.05, 0.8)],
    "torsional": [("/velocity/spin", -40.0, 40.0), ("/torsion/friction", 0.05, 0.8)],
    "planar": [("/bodies/1/velocity/y", 2.0, 30.0), ("/friction", 0.05, 0.9)],
    "spatial": [("/bodies/0/velocity/x", 0.5, 2.0), ("/bodies/0/angular_velocity/y", -50.0, 50.0)],
}

# Accept header per format; the buffered ones have the smaller point limit.
FORMATS = {
    "csv": "text/csv",
    "ndjson": "application/x-ndjson",
    "arrow": "application/vnd.apache.arrow.stream",
    "json": "application/json",
    "svg": "image/svg+xml",
    "reduce": "application/json",  # a body with "reduce": the streamed point limit
}
BUFFERED = {"json", "svg"}


def bases(examples):
    out = copy.deepcopy(ONE_BODY)
    with open(os.path.join(examples, "planar_car_to_car.json")) as f:
        out["planar"] = json.load(f)
    with open(os.path.join(examples, "spatial_dem_spheres.json")) as f:
        spatial = json.load(f)
    # A twist law too, so that every spatial output (54 with two bodies) is answered.
    spatial["torsion"] = {"restitution": 0.2, "friction": 0.3, "pitch_radius": 0.005}
    out["spatial"] = spatial
    return out


def sweep_body(case, base, counts, outputs=None, extra_axes=()):
    axes = [{"path": p, "linspace": {"start": a, "stop": b, "count": n}}
            for (p, a, b), n in zip(AXES[case], counts)]
    axes += list(extra_axes)
    body = {"case": case, "base": base, "axes": axes}
    if outputs is not None:
        body["outputs"] = outputs
    return body


def cmd_bodies(args):
    os.makedirs(args.dir, exist_ok=True)
    b = bases(args.examples)
    for case in AXES:
        # streamed: 10,000 x 1,000 = 10,000,000 points (the default --max-sweep-points)
        # buffered: 3,125 x 64 = 200,000 points (--max-buffered-sweep-points; 64 = the plot's series limit)
        for kind, counts in (("stream", (10_000, 1_000)), ("buffered", (3_125, 64))):
            with open(os.path.join(args.dir, f"{case}-{kind}.json"), "w") as f:
                json.dump(sweep_body(case, b[case], counts), f)
    # Column amplification: "outputs" repeated ("" names every output) is
    # admitted, each repetition adding all 54 spatial columns again.
    for k in args.dup:
        with open(os.path.join(args.dir, f"spatial-buffered-dup{k}.json"), "w") as f:
            json.dump(sweep_body("spatial", b["spatial"], (3_125, 64), outputs=[""] * k), f)
        with open(os.path.join(args.dir, f"spatial-stream-dup{k}.json"), "w") as f:
            json.dump(sweep_body("spatial", b["spatial"], (10_000, 1_000), outputs=[""] * k), f)
    # Single impacts for the mixed load (wrk): one body per endpoint.
    singles = dict(ONE_BODY)
    singles["planar"] = b["planar"]
    singles["spatial"] = b["spatial"]
    with open(os.path.join(args.dir, "singles.json"), "w") as f:
        json.dump(singles, f)
    reduce = sweep_body("spatial", b["spatial"], (10_000, 1_000))
    reduce["reduce"] = {"histograms": [{"output": "/energy/loss", "start": 0.0, "stop": 0.05, "bins": 10_000}]}
    with open(os.path.join(args.dir, "spatial-reduce.json"), "w") as f:
        json.dump(reduce, f)
    for name in sorted(os.listdir(args.dir)):
        print(name, os.path.getsize(os.path.join(args.dir, name)), "bytes")


# ---------------------------------------------------------------- server ---

def free_port():
    with socket.socket() as s:
        s.bind((HOST, 0))
        return s.getsockname()[1]


def cpu_seconds(pid):
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def wait_idle(pid, max_s):
    """Waits until the server has used < 2 % of a core for 1 s (work it goes on
    doing for clients that are gone), at most max_s; returns the seconds waited."""
    t0 = time.monotonic()
    try:
        last = cpu_seconds(pid)
        while time.monotonic() - t0 < max_s:
            time.sleep(1.0)
            now = cpu_seconds(pid)
            if now - last < 0.02:
                break
            last = now
    except (FileNotFoundError, ProcessLookupError, IndexError):
        pass
    return time.monotonic() - t0


def read_status(pid):
    d = {}
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            k, _, v = line.partition(":")
            if k in ("VmRSS", "VmHWM", "VmSize", "Threads", "RssAnon"):
                d[k] = int(v.split()[0])
    return d


class Server:
    """The release binary with the Deployment's environment, bound to loopback."""

    def __init__(self, binary, port, log_path, extra_env=()):
        env = {k: v for k, v in os.environ.items() if not k.startswith("RESTITUTION_")}
        env.update({
            # deploy/kubernetes/deployment.yaml sets exactly these three ...
            "RESTITUTION_SHUTDOWN_GRACE_MS": "10000",
            "RESTITUTION_LOG": "info",
            # ... and RESTITUTION_BIND=0.0.0.0:8080, here loopback on a free port.
            "RESTITUTION_BIND": f"{HOST}:{port}",
        })
        env.update(dict(extra_env))
        self.port = port
        self.log = open(log_path, "wb")
        self.proc = subprocess.Popen([binary, "serve"], env=env, stdout=self.log,
                                     stderr=subprocess.STDOUT)
        self.pid = self.proc.pid
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline:
            try:
                with urllib.request.urlopen(f"http://{HOST}:{port}/readyz", timeout=1) as r:
                    if r.status == 200:
                        return
            except Exception:
                time.sleep(0.02)
        self.stop()
        raise RuntimeError("server did not become ready")

    def stop(self):
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
            try:
                self.proc.wait(timeout=15)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait(timeout=5)
        self.log.close()
        return self.proc.returncode


SKMEM = re.compile(r"skmem:\(r(\d+),rb(\d+),t(\d+),tb(\d+),f(\d+),w(\d+),o(\d+)")


def socket_queued(port):
    """Bytes in the server's sockets' send queues (w) and receive memory (r)."""
    try:
        out = subprocess.run(["ss", "-tmnH", "state", "established", f"( sport = :{port} )"],
                             capture_output=True, text=True, timeout=5).stdout
    except Exception:
        return None, None
    w = r = 0
    for m in SKMEM.finditer(out):
        r += int(m.group(1))
        w += int(m.group(6))
    return w, r


class Sampler(threading.Thread):
    """VmRSS every `period` s into a CSV; kills the server past `kill_kib`."""

    def __init__(self, server, csv_path, kill_kib, period=0.01):
        super().__init__(daemon=True)
        self.server, self.kill_kib, self.period = server, kill_kib, period
        self.csv = open(csv_path, "w")
        self.csv.write("t_s,rss_kib,hwm_kib,threads,sock_send_queue_kib\n")
        self.stop_event = threading.Event()
        self.max_rss = 0
        self.hwm = 0
        self.max_threads = 0
        self.max_sock_w = 0
        self.killed_at_kib = None
        self.t0 = time.monotonic()
        self.peak_t = 0.0

    def run(self):
        next_ss = 0.0
        sock_w = None
        while not self.stop_event.is_set():
            t = time.monotonic() - self.t0
            try:
                st = read_status(self.server.pid)
            except (FileNotFoundError, ProcessLookupError):
                break
            if "VmRSS" not in st:  # exiting
                break
            rss = st["VmRSS"]
            self.hwm = max(self.hwm, st.get("VmHWM", 0))
            self.max_threads = max(self.max_threads, st.get("Threads", 0))
            if rss > self.max_rss:
                self.max_rss, self.peak_t = rss, t
            if t >= next_ss:
                w, _ = socket_queued(self.server.port)
                if w is not None:
                    sock_w = w // 1024
                    self.max_sock_w = max(self.max_sock_w, sock_w)
                next_ss = t + 1.0
            self.csv.write(f"{t:.3f},{rss},{st.get('VmHWM', 0)},{st.get('Threads', 0)},"
                           f"{'' if sock_w is None else sock_w}\n")
            if self.kill_kib and rss > self.kill_kib and self.killed_at_kib is None:
                self.killed_at_kib = rss
                os.kill(self.server.pid, signal.SIGKILL)
                break
            time.sleep(self.period)
        self.csv.close()

    def finish(self):
        self.stop_event.set()
        self.join(timeout=5)


# ---------------------------------------------------------------- clients ---

def http_request(method, path, body, accept, port):
    head = (f"{method} {path} HTTP/1.1\r\nHost: {HOST}:{port}\r\n"
            f"Content-Type: application/json\r\nAccept: {accept}\r\n"
            f"Content-Length: {len(body)}\r\nConnection: close\r\n\r\n")
    return head.encode() + body


async def one_client(port, request, mode, deadline, stats, slow_bytes, slow_interval):
    loop = asyncio.get_running_loop()
    s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    if mode == "slow":
        # A small receive window: the server's data backs up into its own buffers.
        s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 16 * 1024)
    s.setblocking(False)
    status, got, head, outcome, ttfb = None, 0, b"", "deadline", None
    t0 = time.monotonic()
    try:
        await asyncio.wait_for(loop.sock_connect(s, (HOST, port)), timeout=max(0.1, deadline - t0))
        await loop.sock_sendall(s, request)
        buf = bytearray(slow_bytes if mode == "slow" else 256 * 1024)
        while True:
            left = deadline - time.monotonic()
            if left <= 0:
                break
            try:
                n = await asyncio.wait_for(loop.sock_recv_into(s, buf), timeout=left)
            except asyncio.TimeoutError:
                break
            if n == 0:
                outcome = "eof"
                break
            if ttfb is None:
                ttfb = time.monotonic() - t0
            got += n
            if status is None:
                head += bytes(buf[:n])
                if b"\r\n" in head:
                    try:
                        status = int(head.split(b" ", 2)[1])
                    except Exception:
                        status = -1
                    head = b""
            if mode == "slow":
                await asyncio.sleep(slow_interval)
    except (ConnectionResetError, BrokenPipeError) as e:
        outcome = "reset"
    except (asyncio.TimeoutError, OSError) as e:
        outcome = f"error:{type(e).__name__}"
    finally:
        s.close()
    key = f"{status}/{outcome}"
    stats["outcomes"][key] = stats["outcomes"].get(key, 0) + 1
    stats["bytes"] += got
    if ttfb is not None:
        stats["ttfb"].append(ttfb)


async def drive(port, request, n, mode, duration, ramp_s, slow_bytes, slow_interval):
    stats = {"outcomes": {}, "bytes": 0, "ttfb": []}
    deadline = time.monotonic() + duration
    tasks = []
    for i in range(n):
        tasks.append(asyncio.create_task(
            one_client(port, request, mode, deadline, stats, slow_bytes, slow_interval)))
        if ramp_s and n > 1:
            await asyncio.sleep(ramp_s / n)
    await asyncio.wait(tasks, timeout=duration + 5)
    for t in tasks:
        t.cancel()
    return stats


def cmd_sweep(args):
    os.makedirs(args.outdir, exist_ok=True)
    label = args.label
    port = free_port()
    server = Server(args.bin, port, os.path.join(args.outdir, f"{label}.log"))
    time.sleep(0.3)
    idle = read_status(server.pid)
    sampler = Sampler(server, os.path.join(args.outdir, f"{label}.csv"), args.kill_mib * 1024)
    sampler.start()
    with open(args.body, "rb") as f:
        body = f.read()
    request = http_request("POST", "/v1/sweeps", body, FORMATS[args.format], port)
    t0 = time.monotonic()
    stats = asyncio.run(drive(port, request, args.n, args.mode, args.duration, args.ramp,
                              args.slow_bytes, args.slow_interval))
    elapsed = time.monotonic() - t0
    # Memory just after the clients closed, then after the server settles.
    after = {}
    busy_after = wait_idle(server.pid, args.settle_max)
    time.sleep(args.settle)
    try:
        after = read_status(server.pid)
    except Exception:
        pass
    sampler.finish()
    killed = sampler.killed_at_kib is not None
    code = server.stop()
    with open(os.path.join(args.outdir, f"{label}.log"), "rb") as f:
        log = f.read()
    alloc_fail = len(re.findall(rb"memory allocation of \d+ bytes failed", log))
    result = {
        "label": label, "case": args.case, "format": args.format, "mode": args.mode,
        "n": args.n, "points": args.points, "duration_s": round(elapsed, 1),
        "idle_rss_mib": round(idle["VmRSS"] / 1024, 1),
        "peak_hwm_mib": round(max(sampler.hwm, after.get("VmHWM", 0)) / 1024, 1),
        "peak_sampled_rss_mib": round(sampler.max_rss / 1024, 1),
        "peak_at_s": round(sampler.peak_t, 1),
        "rss_after_mib": round(after["VmRSS"] / 1024, 1) if "VmRSS" in after else None,
        "server_busy_after_clients_s": round(busy_after, 1),
        "max_threads": sampler.max_threads,
        "max_sock_send_queue_mib": round(sampler.max_sock_w / 1024, 1),
        "killed_over_mib": round(sampler.killed_at_kib / 1024, 1) if killed else None,
        "server_exit": code, "alloc_failures_logged": alloc_fail,
        "outcomes": stats["outcomes"], "bytes_received": stats["bytes"],
        "ttfb_max_s": round(max(stats["ttfb"]), 2) if stats["ttfb"] else None,
        "timeouts_408": log.count(b"status=408") or None,
        "stream_stopped_logged": log.count(b"sweep stream stopped"),
    }
    line = json.dumps(result)
    print(line, flush=True)
    with open(args.results, "a") as f:
        f.write(line + "\n")


# ---------------------------------------------------------------- mixed ---

WRK_LUA = r"""
local bodies = %s
local paths = {}
for k, _ in pairs(bodies) do table.insert(paths, k) end
table.sort(paths)
local i = 0
request = function()
  i = i + 1
  local case = paths[(i %% #paths) + 1]
  return wrk.format("POST", "/v1/impacts/" .. case,
    {["Content-Type"] = "application/json"}, bodies[case])
end
"""


def lua_table(singles):
    items = []
    for k, v in singles.items():
        s = json.dumps(v).replace("\\", "\\\\").replace('"', '\\"')
        items.append(f'["{k}"] = "{s}"')
    return "{" + ", ".join(items) + "}"


def cmd_mixed(args):
    os.makedirs(args.outdir, exist_ok=True)
    with open(args.singles) as f:
        singles = json.load(f)
    lua = os.path.join(args.outdir, "mixed.lua")
    with open(lua, "w") as f:
        f.write(WRK_LUA % lua_table(singles))
    port = free_port()
    server = Server(args.bin, port, os.devnull if args.no_log_file else
                    os.path.join(args.outdir, f"{args.label}.log"))
    time.sleep(0.5)
    idle = read_status(server.pid)
    sampler = Sampler(server, os.path.join(args.outdir, f"{args.label}.csv"), args.kill_mib * 1024)
    sampler.start()
    rounds = []
    for c in args.connections:
        out = subprocess.run(["timeout", str(args.duration + 30), "wrk", "-t2", f"-c{c}",
                              f"-d{args.duration}s", "-s", lua, f"http://{HOST}:{port}/"],
                             capture_output=True, text=True)
        rps = re.search(r"Requests/sec:\s+([\d.]+)", out.stdout)
        non2xx = re.search(r"Non-2xx or 3xx responses: (\d+)", out.stdout)
        total = re.search(r"(\d+) requests in", out.stdout)
        rounds.append({"connections": c, "requests": int(total.group(1)) if total else None,
                       "rps": float(rps.group(1)) if rps else None,
                       "non_2xx": int(non2xx.group(1)) if non2xx else 0})
        time.sleep(1)
    time.sleep(args.settle)
    after = read_status(server.pid)
    sampler.finish()
    code = server.stop()
    result = {
        "label": args.label, "kind": "mixed single impacts (wrk, 6 endpoints in turn)",
        "idle_rss_mib": round(idle["VmRSS"] / 1024, 1),
        "peak_hwm_mib": round(max(sampler.hwm, after["VmHWM"]) / 1024, 1),
        "rss_after_load_idle_mib": round(after["VmRSS"] / 1024, 1),
        "max_threads": sampler.max_threads, "rounds": rounds, "server_exit": code,
    }
    line = json.dumps(result)
    print(line, flush=True)
    with open(args.results, "a") as f:
        f.write(line + "\n")


def cmd_table(args):
    rows = [json.loads(l) for l in open(args.results) if l.strip()]
    print("| run | configuration | N | clients | peak RSS (VmHWM) MiB | idle MiB | RSS after MiB | "
          "socket send queues MiB | threads | answers | notes |")
    print("|---|---|---:|---|---:|---:|---:|---:|---:|---|---|")
    for r in rows:
        if "kind" in r:
            rounds = "; ".join(f"c={x['connections']}: {x['requests']} req, {x['rps']:.0f}/s, non-2xx {x['non_2xx']}"
                               for x in r["rounds"])
            print(f"| {r['label']} | single impacts, wrk | | | {r['peak_hwm_mib']} | {r['idle_rss_mib']} | "
                  f"{r['rss_after_load_idle_mib']} | | {r['max_threads']} | {rounds} | |")
            continue
        notes = []
        if r.get("killed_over_mib"):
            notes.append(f"KILLED by watchdog at {r['killed_over_mib']} MiB")
        if r.get("alloc_failures_logged"):
            notes.append(f"allocation failure abort x{r['alloc_failures_logged']}")
        if r.get("server_exit") not in (0, None):
            notes.append(f"server exit {r['server_exit']}")
        if r.get("server_busy_after_clients_s", 0) > 2:
            notes.append(f"server computed {r['server_busy_after_clients_s']} s after clients left")
        notes.append(f"peak at {r['peak_at_s']} s of {r['duration_s']} s")
        answers = ", ".join(f"{k}: {v}" for k, v in sorted(r["outcomes"].items()))
        print(f"| {r['label']} | {r['case']} {r['format']} {r['points']:,} pts | {r['n']} | {r['mode']} | "
              f"{r['peak_hwm_mib'] if not r.get('killed_over_mib') else '> ' + str(r['killed_over_mib'])} | "
              f"{r['idle_rss_mib']} | {r['rss_after_mib']} | {r['max_sock_send_queue_mib']} | "
              f"{r['max_threads']} | {answers} | {'; '.join(notes)} |")


def main():
    p = argparse.ArgumentParser()
    sub = p.add_subparsers(dest="cmd", required=True)
    b = sub.add_parser("bodies")
    b.add_argument("dir")
    b.add_argument("examples")
    b.add_argument("--dup", type=int, nargs="*", default=[])
    s = sub.add_parser("sweep")
    s.add_argument("--bin", required=True)
    s.add_argument("--body", required=True)
    s.add_argument("--case", required=True)
    s.add_argument("--format", required=True, choices=FORMATS)
    s.add_argument("--points", type=int, required=True)
    s.add_argument("--n", type=int, required=True)
    s.add_argument("--mode", choices=["fast", "slow"], required=True)
    s.add_argument("--duration", type=float, default=30)
    s.add_argument("--ramp", type=float, default=1.0, help="seconds over which the N clients start")
    s.add_argument("--slow-bytes", type=int, default=4096)
    s.add_argument("--slow-interval", type=float, default=0.05)
    s.add_argument("--settle", type=float, default=2.0)
    s.add_argument("--settle-max", type=float, default=60.0,
                   help="at most this long waiting for the server to finish work for gone clients")
    s.add_argument("--kill-mib", type=int, default=8704)
    s.add_argument("--label", required=True)
    s.add_argument("--outdir", required=True)
    s.add_argument("--results", required=True)
    m = sub.add_parser("mixed")
    m.add_argument("--bin", required=True)
    m.add_argument("--singles", required=True)
    m.add_argument("--connections", type=int, nargs="+", default=[64, 512])
    m.add_argument("--duration", type=int, default=20)
    m.add_argument("--settle", type=float, default=3.0)
    m.add_argument("--kill-mib", type=int, default=8704)
    m.add_argument("--no-log-file", action="store_true")
    m.add_argument("--label", default="mixed")
    m.add_argument("--outdir", required=True)
    m.add_argument("--results", required=True)
    t = sub.add_parser("table")
    t.add_argument("results")
    args = p.parse_args()
    {"bodies": cmd_bodies, "sweep": cmd_sweep, "mixed": cmd_mixed, "table": cmd_table}[args.cmd](args)


if __name__ == "__main__":
    main()
