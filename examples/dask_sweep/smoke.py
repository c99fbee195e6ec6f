"""CI smoke test: two service replicas on loopback ports, a LocalCluster with two
workers, a sweep of about a million points fanned out in shards; the Parquet
dataset equals the single-server sweep, and the merged reduction equals the
single-server reduction. Usage: python smoke.py PATH/TO/restitution [POINTS]"""

from __future__ import annotations

import json
import math
import os
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request

import pyarrow as pa
import pyarrow.dataset as ds
from distributed import Client, LocalCluster

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import restitution_dask as rd  # noqa: E402


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start(binary: str) -> tuple[subprocess.Popen, str]:
    port = free_port()
    process = subprocess.Popen(
        [binary, "serve", "--bind", f"127.0.0.1:{port}"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        env=dict(os.environ, RESTITUTION_LOG="warn"),
    )
    url = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + 20
    while True:
        try:
            with urllib.request.urlopen(f"{url}/readyz", timeout=1) as r:
                if r.status == 200:
                    return process, url
        except OSError:
            pass
        if time.monotonic() > deadline:
            process.kill()
            raise RuntimeError(f"{binary} did not become ready on {url}")
        time.sleep(0.05)


def main() -> int:
    binary = sys.argv[1]
    side = int(math.isqrt(int(sys.argv[2]) if len(sys.argv) > 2 else 1_000_000))
    sweep = {
        "case": "oblique",
        "base": {
            "body": {"mass": 1.0, "inertia": 0.00125},
            "contact": {"tangential_offset": 0.01, "normal_offset": 0.05},
            "velocity": {"normal": -1.0, "tangential": 0.0, "angular": 2.0},
            "restitution": 0.93, "friction": 0.123,
        },
        "axes": [
            {"path": "/velocity/normal", "linspace": {"start": -3.0, "stop": 0.2, "count": side}},
            {"path": "/velocity/tangential", "linspace": {"start": -5.0, "stop": 5.0, "count": side}},
        ],
        "outputs": ["/contact_velocity/final", "/regime", "/energy/loss"],
    }
    replicas = [start(binary) for _ in range(2)]
    urls = [url for _, url in replicas]
    try:
        started = time.monotonic()
        whole = rd.fetch_range(urls[0], sweep, 0, side * side)
        single = time.monotonic() - started
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None, processes=True)
        with Client(cluster) as client, tempfile.TemporaryDirectory() as out:
            started = time.monotonic()
            parts = rd.sweep_to_parquet(client, urls, sweep, shards=8, out_dir=out)
            fanned = time.monotonic() - started
            dataset = ds.dataset(out, format="parquet", partitioning="hive")
            table = dataset.to_table()
            # Partition order: sort by shard, keep each shard's own row order.
            shards = table.column("shard").to_pylist()
            order = sorted(range(table.num_rows), key=lambda i: (shards[i], i))
            table = table.take(pa.array(order)).drop_columns(["shard"])
            assert table.num_rows == whole.num_rows == side * side, (table.num_rows, whole.num_rows)
            assert table.column_names == whole.column_names, (table.column_names, whole.column_names)
            for name in whole.column_names:
                a, b = whole.column(name).combine_chunks(), table.column(name).combine_chunks()
                if pa.types.is_dictionary(a.type):
                    a, b = a.cast(pa.string()), b.cast(pa.string())
                assert a.equals(b), f"column {name} differs"
            refused = whole.column("error").null_count
            assert 0 < refused < whole.num_rows, "the sweep has refused points and answers"

            reduced = dict(sweep, reduce={"histograms": [
                {"output": "/energy/loss", "start": 0.0, "stop": 2.0, "bins": 20}]})
            single_reduction = json.loads(rd._post(f"{urls[1]}/v1/sweeps", reduced))
            started = time.monotonic()
            merged = rd.reduce(client, urls, reduced, shards=8)
            reduce_time = time.monotonic() - started
            for key in ["points", "answered", "refused", "sweep_sha256"]:
                assert merged[key] == single_reduction[key], (key, merged[key], single_reduction[key])
            for name, s in single_reduction["outputs"].items():
                m = merged["outputs"][name]
                for key in ["count", "min", "max", "sum", "mean", "histogram", "values"]:
                    assert m.get(key) == s.get(key), (name, key, m.get(key), s.get(key))
        cluster.close()
        print(
            f"dask smoke: {side * side} points; single server {single:.2f} s; "
            f"8 shards over 2 replicas and 2 workers {fanned:.2f} s (Parquet); reduction {reduce_time:.2f} s; "
            f"{len(parts)} parts equal the single-server sweep, the merged reduction equals the single one"
        )
        return 0
    finally:
        for process, _ in replicas:
            process.terminate()
            process.wait(timeout=20)


if __name__ == "__main__":
    sys.exit(main())
