#!/usr/bin/env bash
# Checks the Dockerfile without a Docker daemon (CI has none): its runtime
# stage installs the Debian package of every shared library scallopd and
# scallop load; it runs as a non-root user, exposes the ports and has a
# HEALTHCHECK; and its CMD and HEALTHCHECK, run here as written (ports moved
# to free loopback ones), start a server that the health check calls healthy,
# and unhealthy once it drains on SIGTERM.
# Usage: dockerfile_test.sh DOCKERFILE SCALLOPD SCALLOP_CLI
set -euo pipefail
dockerfile=$1 scallopd=$2 cli=$3
fail() { echo "dockerfile: $*" >&2; exit 1; }
work=$(mktemp -d)
server_pid=
cleanup() {
  [ -n "$server_pid" ] && kill -9 "$server_pid" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT

# The runtime stage: from "FROM debian:12-slim" to the end.
sed -n '/^FROM debian:12-slim/,$p' "$dockerfile" >"$work/runtime"
[ -s "$work/runtime" ] || fail "no debian:12-slim runtime stage"
grep -q '^FROM debian:12 AS build' "$dockerfile" || fail "no debian:12 build stage"
grep -q 'scripts/install-deps.sh' "$dockerfile" || fail "build stage does not use install-deps.sh"
grep -Eo '\blib[a-z0-9.+-]+|\bzlib1g\b' "$work/runtime" | sort -u >"$work/listed"

# Every library the programs load, by the Debian package that owns it (one
# dpkg query for all); libc, libgcc and libstdc++ come with the base image,
# and sanitizer runtimes only with the test build, never with an image.
ldd "$scallopd" "$cli" | awk '$3 ~ /^\// {print $3}' | sort -u | xargs readlink -f >"$work/libraries"
dpkg -S $(cat "$work/libraries") 2>/dev/null | cut -d: -f1 | tr -d ' ' | tr ',' '\n' | sort -u |
  grep -vxE 'libc6|libgcc-s1|libstdc\+\+6|lib(a|ub|l|t)san[0-9]+' >"$work/needed" || true
[ "$(wc -l <"$work/needed")" -gt 5 ] || fail "could not map the programs' libraries to packages"
missing=$(comm -23 "$work/needed" "$work/listed")
[ -z "$missing" ] || fail "runtime stage lacks packages: $missing"
# Qualified by the machine's architecture: a machine that also holds another
# architecture's copy (the aarch64 cross build's) would find the bare name ambiguous.
arch=$(dpkg --print-architecture)
while read -r package; do
  dpkg -s "$package:$arch" >/dev/null 2>&1 || dpkg -s "$package" >/dev/null 2>&1 ||
    fail "runtime package $package is not a Debian 12 package here"
done <"$work/listed"

grep -Eq '^USER [a-z]' "$work/runtime" || fail "no USER: the server would run as root"
grep -q '^USER root' "$work/runtime" && fail "USER is root"
grep -Eq '^EXPOSE .*50051' "$work/runtime" || fail "gRPC port 50051 not exposed"
grep -q '^HEALTHCHECK' "$work/runtime" || fail "no HEALTHCHECK"

# CMD and HEALTHCHECK's command, as JSON arrays (continuation lines joined).
json_of() {  # json_of INSTRUCTION: the JSON array ending that instruction
  /usr/bin/python3 -c 'import re,sys
text = open(sys.argv[1]).read().replace("\\\n", " ")
match = re.search(r"^" + sys.argv[2] + r"\b.*?(\[.*\])\s*$", text, re.M)
print(match.group(1) if match else "")' "$work/runtime" "$1"
}
cmd=$(json_of CMD)
health=$(json_of HEALTHCHECK)
[ -n "$cmd" ] && [ -n "$health" ] || fail "CMD or HEALTHCHECK is not in exec (JSON) form"
mapfile -t server_args < <(/usr/bin/python3 -c 'import json,sys; [print(a.replace("0.0.0.0:50051","127.0.0.1:0").replace("0.0.0.0:9090","127.0.0.1:0")) for a in json.loads(sys.argv[1])]' "$cmd")
"$scallopd" "${server_args[@]}" --drain-seconds 3 >"$work/out" 2>"$work/log" &
server_pid=$!
for _ in $(seq 100); do grep -q listening "$work/out" 2>/dev/null && break; sleep 0.1; done
address=$(sed -n 's/^scallopd listening on //p' "$work/out")
[ -n "$address" ] || { cat "$work/log"; fail "CMD did not start scallopd"; }
mapfile -t probe < <(/usr/bin/python3 -c 'import json,sys; [print(a.replace("127.0.0.1:50051",sys.argv[2])) for a in json.loads(sys.argv[1])]' "$health" "$address")
[ "${probe[0]}" = scallop ] || fail "HEALTHCHECK runs ${probe[0]}, not scallop"
for _ in $(seq 50); do "$cli" "${probe[@]:1}" && break; sleep 0.1; done
"$cli" "${probe[@]:1}" || fail "HEALTHCHECK fails on a healthy server"
kill -TERM "$server_pid"
sleep 1  # within --drain-seconds: NOT_SERVING but still answering
if "$cli" "${probe[@]:1}"; then fail "HEALTHCHECK passes on a draining server"; fi
wait "$server_pid" || fail "scallopd did not exit 0 after SIGTERM"
server_pid=
echo "dockerfile: runtime packages cover $(wc -l <"$work/needed") libraries; CMD and HEALTHCHECK work"
