#!/usr/bin/env bash
# POST /v1/impacts/oblique under wrk: a bare axum handler (benches/load.rs
# --serve-bare: same request and response shape, no middleware, no physics)
# against the service with its default configuration (access log at info,
# metrics on) and with RESTITUTION_LOG=warn, alternated round by round.
#
#   benches/scripts/wrk_bare.sh                  # 3 rounds of 4 s per server, 16 connections
#   ROUNDS=5 SECONDS_PER_CELL=4 CONNECTIONS=16 benches/scripts/wrk_bare.sh
#   BEFORE=/path/to/an/older/restitution benches/scripts/wrk_bare.sh   # also that binary, alternated
#   LOAD=/path/to/load-harness SERVICE=/path/to/restitution benches/scripts/wrk_bare.sh   # no build
#
# Builds the release binary and the load harness (cargo -j1), serves on
# 127.0.0.1 only, every wrk run bounded; the servers' logs go to /dev/null
# (LOG=FILE to keep them). Needs wrk and jq (Debian: apt-get install wrk jq).
set -euo pipefail

rounds=${ROUNDS:-3}
seconds=${SECONDS_PER_CELL:-4}
connections=${CONNECTIONS:-16}
# shellcheck source=benches/scripts/servers.sh
. "$(dirname "$0")/servers.sh"

start bare "$load" --serve-bare PORT
start service env -u RESTITUTION_LOG "$service" --bind 127.0.0.1:PORT
start "service, RESTITUTION_LOG=warn" env RESTITUTION_LOG=warn "$service" --bind 127.0.0.1:PORT
if [ -n "${BEFORE:-}" ]; then
    start before env -u RESTITUTION_LOG "$BEFORE" --bind 127.0.0.1:PORT
    start "before, RESTITUTION_LOG=warn" env RESTITUTION_LOG=warn "$BEFORE" --bind 127.0.0.1:PORT
fi

# CPU time (user + system, in clock ticks) a server has used so far.
ticks() { awk '{print $14 + $15}' "/proc/$1/stat"; }

for port in "${ports[@]}"; do run "$port" 1 >/dev/null; done
hz=$(getconf CLK_TCK)
declare -A cpu

echo "wrk -t1 -c$connections -d${seconds}s -s benches/scripts/oblique.lua http://127.0.0.1:PORT/v1/impacts/oblique, $rounds rounds, $(nproc) cores"
echo
header="| round |"; rule="|---|"
for name in "${names[@]}"; do header+=" $name |"; rule+="---:|"; done
echo "$header"; echo "$rule"
for round in $(seq "$rounds"); do
    row="| $round |"; bare=""
    for i in "${!ports[@]}"; do
        before=$(ticks "${pids[$i]}")
        read -r rps requests < <(run "${ports[$i]}" "$seconds")
        after=$(ticks "${pids[$i]}")
        # The server's CPU time per request, in microseconds.
        cpu[$i]+="$(awk -v t=$((after - before)) -v hz="$hz" -v n="$requests" 'BEGIN {printf "%.1f", t / hz * 1e6 / n}') "
        if [ -z "$bare" ]; then bare=$rps; row+=" $rps |"
        else row+=" $rps ($(awk -v a="$rps" -v b="$bare" 'BEGIN {printf "%.2f", a/b}')) |"; fi
    done
    echo "$row"
done
echo
echo "Server CPU time (user + system) per request, microseconds, each round (bare/server in brackets: the throughput ratio if CPU were the only limit):"
echo
echo "| server | CPU µs/request by round | bare/server |"
echo "|---|---|---:|"
for i in "${!ports[@]}"; do
    ratio=$(awk -v a="${cpu[0]}" -v b="${cpu[$i]}" 'BEGIN {n = split(a, x, " "); split(b, y, " "); s = 0; t = 0;
        for (k = 1; k <= n; k++) {s += x[k]; t += y[k]} printf "%.2f", s / t}')
    echo "| ${names[$i]} | ${cpu[$i]% } | $ratio |"
done
