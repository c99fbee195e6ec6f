"""Fan a restitution sweep out over service replicas with Dask distributed.

The service is stateless and a sweep is a pure function of its request, so a
sweep scales out without a coordinator of its own: ask one replica for the
plan (``POST /v1/sweeps/plan``: the number of points and ranges tiling them),
let Dask run one task per range against the replicas, each task fetching its
range as an Arrow stream (``"range"`` in the sweep request) and writing it as
one Parquet partition, or reducing it (``"reduce"``) to a summary that merges
exactly with the others.

Functions here take the replicas' base URLs and a sweep request (the body of
``POST /v1/sweeps``, a dict) and a ``distributed.Client``.
"""

from __future__ import annotations

import json
import math
import os
import urllib.request
from typing import Any, Iterable, Sequence

import pyarrow as pa
import pyarrow.ipc as ipc
import pyarrow.parquet as pq

ARROW = "application/vnd.apache.arrow.stream"

__all__ = [
    "plan",
    "fetch_range",
    "reduce_range",
    "merge_reductions",
    "sweep_to_parquet",
    "sweep_table",
    "reduce",
]


def _post(url: str, body: dict, accept: str = "application/json", timeout: float = 600.0) -> bytes:
    request = urllib.request.Request(
        url,
        data=json.dumps(body).encode(),
        headers={"content-type": "application/json", "accept": accept},
        method="POST",
    )
    with urllib.request.urlopen(request, timeout=timeout) as response:
        return response.read()


def plan(base_url: str, sweep: dict, shards: int | None = None, points_per_shard: int | None = None) -> dict:
    """The sweep's number of points and the ranges tiling it (``POST /v1/sweeps/plan``)."""
    body: dict[str, Any] = {"sweep": sweep}
    if shards is not None:
        body["shards"] = shards
    if points_per_shard is not None:
        body["points_per_shard"] = points_per_shard
    return json.loads(_post(f"{base_url}/v1/sweeps/plan", body))


def fetch_range(base_url: str, sweep: dict, start: int, end: int) -> pa.Table:
    """One range of the sweep as an Arrow table (the service streams it; read whole here)."""
    body = dict(sweep, range={"start": start, "end": end})
    data = _post(f"{base_url}/v1/sweeps", body, accept=ARROW)
    return ipc.open_stream(pa.BufferReader(data)).read_all()


def _write_shard(base_url: str, sweep: dict, shard: int, start: int, end: int, out_dir: str) -> dict:
    """Fetches one range and writes it as ``out_dir/shard=NNNNN/part.parquet``; returns its row count and hash."""
    table = fetch_range(base_url, sweep, start, end)
    directory = os.path.join(out_dir, f"shard={shard:05d}")
    os.makedirs(directory, exist_ok=True)
    pq.write_table(table, os.path.join(directory, "part.parquet"))
    metadata = table.schema.metadata or {}
    return {
        "shard": shard,
        "rows": table.num_rows,
        "sweep_sha256": metadata.get(b"restitution.sweep_sha256", b"").decode(),
    }


def sweep_to_parquet(client, urls: Sequence[str], sweep: dict, shards: int, out_dir: str) -> list[dict]:
    """Computes the sweep in ``shards`` ranges over the replicas (round robin), one
    Dask task per range, writing Parquet partitioned by shard. Checks that every
    part belongs to the same sweep (its request hash) and that the rows add up."""
    layout = plan(urls[0], sweep, shards=shards)
    futures = [
        client.submit(_write_shard, urls[i % len(urls)], sweep, i, r["start"], r["end"], out_dir, pure=False)
        for i, r in enumerate(layout["ranges"])
    ]
    parts = client.gather(futures)
    hashes = {p["sweep_sha256"] for p in parts}
    if len(hashes) != 1:
        raise RuntimeError(f"parts of different sweeps: {hashes}")
    rows = sum(p["rows"] for p in parts)
    if rows != layout["points"]:
        raise RuntimeError(f"{rows} rows for a sweep of {layout['points']} points")
    return parts


def sweep_table(client, urls: Sequence[str], sweep: dict, shards: int) -> pa.Table:
    """The whole sweep as one Arrow table, fetched in ``shards`` ranges by Dask tasks."""
    layout = plan(urls[0], sweep, shards=shards)
    futures = [
        client.submit(fetch_range, urls[i % len(urls)], sweep, r["start"], r["end"], pure=False)
        for i, r in enumerate(layout["ranges"])
    ]
    return pa.concat_tables(client.gather(futures))


def reduce_range(base_url: str, sweep: dict, start: int, end: int) -> dict:
    """The reduction of one range (``"reduce"`` in the sweep request)."""
    body = dict(sweep, range={"start": start, "end": end})
    body.setdefault("reduce", {})
    return json.loads(_post(f"{base_url}/v1/sweeps", body))


def _merge_extreme(a: dict | None, b: dict | None, better) -> dict | None:
    if a is None:
        return b
    if b is None:
        return a
    if better(b["value"], a["value"]) or (b["value"] == a["value"] and b["index"] < a["index"]):
        return b
    return a


def merge_reductions(parts: Iterable[dict]) -> dict:
    """Merges reductions of ranges of one sweep into the reduction of their union,
    exactly: counts add, extremes keep the earliest point on ties, sums are the
    exact sums of all parts' ``sum_parts`` (``math.fsum`` rounds correctly),
    histograms add."""
    parts = list(parts)
    if not parts:
        raise ValueError("nothing to merge")
    if len({p["sweep_sha256"] for p in parts}) != 1:
        raise ValueError("reductions of different sweeps")
    ordered = sorted(parts, key=lambda p: p["range"]["start"])
    merged: dict[str, Any] = {
        "points": sum(p["points"] for p in parts),
        "total_points": parts[0]["total_points"],
        "range": {"start": ordered[0]["range"]["start"], "end": ordered[-1]["range"]["end"]},
        "answered": sum(p["answered"] for p in parts),
        "refused": {},
        "outputs": {},
        "precision": parts[0]["precision"],
        "sweep_sha256": parts[0]["sweep_sha256"],
    }
    for p in parts:
        for slug, r in p["refused"].items():
            entry = merged["refused"].setdefault(slug, {"title": r["title"], "count": 0})
            entry["count"] += r["count"]
    for name in parts[0]["outputs"]:
        summaries = [p["outputs"][name] for p in parts]
        if "values" in summaries[0]:
            values: dict[str, int] = {}
            for s in summaries:
                for k, n in s["values"].items():
                    values[k] = values.get(k, 0) + n
            merged["outputs"][name] = {"count": sum(s["count"] for s in summaries), "values": values}
            continue
        count = sum(s["count"] for s in summaries)
        overflowed = any(s["sum"] is None and s["count"] > 0 for s in summaries)
        sum_parts = [x for s in summaries for x in s["sum_parts"]]
        total = None if overflowed else math.fsum(sum_parts)
        if total is not None and math.isinf(total):
            total = None
        out = {
            "count": count,
            "min": None,
            "max": None,
            "sum": total,
            "sum_parts": sum_parts,
            "mean": (total / count) if (total is not None and count > 0) else None,
            "histogram": None,
        }
        for s in summaries:
            out["min"] = _merge_extreme(out["min"], s["min"], lambda x, y: x < y)
            out["max"] = _merge_extreme(out["max"], s["max"], lambda x, y: x > y)
        hists = [s["histogram"] for s in summaries if s["histogram"] is not None]
        if hists:
            h = dict(hists[0])
            h["counts"] = [sum(c) for c in zip(*(x["counts"] for x in hists))]
            h["below"] = sum(x["below"] for x in hists)
            h["above"] = sum(x["above"] for x in hists)
            out["histogram"] = h
        merged["outputs"][name] = out
    return merged


def reduce(client, urls: Sequence[str], sweep: dict, shards: int) -> dict:
    """The reduction of the whole sweep: one Dask task per range, merged exactly."""
    layout = plan(urls[0], sweep, shards=shards)
    futures = [
        client.submit(reduce_range, urls[i % len(urls)], sweep, r["start"], r["end"], pure=False)
        for i, r in enumerate(layout["ranges"])
    ]
    return merge_reductions(client.gather(futures))
