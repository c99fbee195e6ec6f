"""``restitution-dask``: a sweep over service replicas, with Dask.

    restitution-dask --url http://replica-a:8080 --url http://replica-b:8080 \\
        --request sweep.json --shards 64 --out results/          # Parquet, partitioned by shard
    restitution-dask ... --reduce                                 # the merged reduction, as JSON

Without ``--scheduler`` a ``LocalCluster`` runs here; with it (``tcp://host:8786``)
the tasks run on that Dask cluster's workers, which must reach the URLs.
"""

from __future__ import annotations

import argparse
import json
import sys

from distributed import Client, LocalCluster

from . import reduce, sweep_to_parquet


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="restitution-dask", description=__doc__.split("\n\n")[0])
    parser.add_argument("--url", action="append", required=True, help="a replica's base URL (repeat for more)")
    parser.add_argument("--request", required=True, help="a file holding the sweep request (the body of POST /v1/sweeps)")
    parser.add_argument("--shards", type=int, default=16, help="number of ranges (tasks)")
    parser.add_argument("--out", help="directory for the Parquet dataset (partitioned by shard)")
    parser.add_argument("--reduce", action="store_true", help="print the merged reduction instead of writing rows")
    parser.add_argument("--scheduler", help="address of a Dask scheduler (default: a LocalCluster here)")
    parser.add_argument("--workers", type=int, default=2, help="LocalCluster workers")
    args = parser.parse_args(argv)
    with open(args.request) as f:
        sweep = json.load(f)
    if args.scheduler:
        client = Client(args.scheduler)
    else:
        client = Client(LocalCluster(n_workers=args.workers, threads_per_worker=1, dashboard_address=None))
    with client:
        if args.reduce:
            json.dump(reduce(client, args.url, sweep, args.shards), sys.stdout, indent=1)
            print()
        elif args.out:
            parts = sweep_to_parquet(client, args.url, sweep, args.shards, args.out)
            print(f"{sum(p['rows'] for p in parts)} rows in {len(parts)} shards under {args.out}")
        else:
            parser.error("give --out DIR or --reduce")
    return 0


if __name__ == "__main__":
    sys.exit(main())
