#!/usr/bin/env bash
# Soak: mixed traffic (every impact endpoint, JSON and CSV sweeps) at
# concurrency 16 against the release binary on 127.0.0.1 for SECONDS (default
# 600), printing requests, failures and the server's resident memory every
# 30 s. Bounded in time and requests; fails if any request fails.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
cargo bench --bench load -- --soak "$seconds"
