# Sourced by wrk_bare.sh and wrk_profile_diff: the release binary and the
# load harness (built with cargo -j1 unless LOAD and SERVICE are given), and
# servers started on 127.0.0.1 only, each on a free port, stopped on exit.
#
# After sourcing: $load, $service; start NAME PROGRAM ARGS... (PORT in the
# arguments stands for the port; env assignments in front) appends to
# names, ports and pids; $log is where the servers' output goes.

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
log=${LOG:-/dev/null}
cd "$root"

if [ -n "${LOAD:-}" ] && [ -n "${SERVICE:-}" ]; then
    load=$LOAD service=$SERVICE
else
    built=$(cargo build --release -j1 --bin restitution --bench load --message-format=json-render-diagnostics)
    executable() { jq -r --arg name "$1" 'select(.reason == "compiler-artifact" and .target.name == $name) | .executable' <<<"$built" | tail -1; }
    load=$(executable load)
    service=${SERVICE:-$(executable restitution)}
fi
[ -x "$load" ] && [ -x "$service" ] || { echo "no load harness or service binary" >&2; exit 1; }

pids=()
cleanup() { for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done; wait 2>/dev/null || true; }
trap cleanup EXIT

free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }
wait_port() {
    for _ in $(seq 200); do
        (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null && return 0
        sleep 0.05
    done
    echo "server on port $1 did not start" >&2; exit 1
}

names=(); ports=()
start() { # name, program and arguments (PORT stands for the port); env assignments in front
    local name=$1; shift
    local port; port=$(free_port)
    "${@//PORT/$port}" >>"$log" 2>&1 &
    pids+=($!)
    wait_port "$port"
    names+=("$name"); ports+=("$port")
}

# One bounded wrk run of the oblique request: port, seconds -> "requests/s requests".
run() {
    wrk -t1 -c"$connections" -d"$2"s -s "$here/oblique.lua" "http://127.0.0.1:$1/v1/impacts/oblique" |
        awk '/requests in/ {n = $1} /^Requests\/sec:/ {r = $2} /Non-2xx/ {bad = 1}
             END {if (bad) {print "non-2xx answers" > "/dev/stderr"; exit 1} printf "%.0f %d\n", r, n}'
}
