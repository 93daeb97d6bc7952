#!/usr/bin/env bash
# "On two machines": tvo_firmware_node in one network namespace, the example plant client in another,
# joined by a veth pair; LCM multicast (ttl=1) crosses the link between them, as between two hosts.
# Asserts the run converges, the node exits with 0 after the client's STOP, and the traffic went over
# the link. Skipped (exit 77) where namespaces cannot be created (not root, no CAP_NET_ADMIN).
# Every address lives inside the two namespaces it creates; they are removed on exit.
#
# Usage: two_hosts.sh NODE PLANT_CLIENT PORT [DURATION_S [MAX_ERROR_M]]
set -euo pipefail

skip_code=77
if [[ $# -lt 3 ]]; then
  echo "usage: two_hosts.sh NODE PLANT_CLIENT PORT [DURATION_S [MAX_ERROR_M]]" >&2
  exit 2
fi
node="$1" client="$2" port="$3" duration="${4:-5}" max_error="${5:-1e-3}"
ns_node="tvo2h_node_$$"
ns_plant="tvo2h_plant_$$"
url="udpm://239.255.76.68:${port}?ttl=1"
node_pid=""

cleanup() {
  # Only what this script started: the node (by its pid), then its two namespaces.
  if [[ -n "$node_pid" ]] && kill -0 "$node_pid" 2>/dev/null; then
    kill "$node_pid" 2>/dev/null || true
    wait "$node_pid" 2>/dev/null || true
  fi
  ip netns del "$ns_node" 2>/dev/null || true
  ip netns del "$ns_plant" 2>/dev/null || true
}
trap cleanup EXIT

fail() { echo "two_hosts: FAIL: $*" >&2; exit 1; }

if ! command -v ip >/dev/null 2>&1; then
  echo "two_hosts: SKIPPED: the 'ip' command (Debian package iproute2) is not installed"
  exit $skip_code
fi
if ! ip netns add "$ns_node" 2>/dev/null; then
  echo "two_hosts: SKIPPED: cannot create a network namespace here (needs root or CAP_NET_ADMIN)"
  exit $skip_code
fi
ip netns add "$ns_plant"
# The pair is created inside the namespaces: the host's own network is never touched.
ip -n "$ns_node" link add vA type veth peer name vB netns "$ns_plant"
ip -n "$ns_node" addr add 10.99.0.1/24 dev vA
ip -n "$ns_plant" addr add 10.99.0.2/24 dev vB
for pair in "$ns_node:vA" "$ns_plant:vB"; do
  ns="${pair%%:*}" dev="${pair##*:}"
  ip -n "$ns" link set lo up
  ip -n "$ns" link set "$dev" up
  ip -n "$ns" route add 224.0.0.0/4 dev "$dev"   # multicast leaves through the link
done

ip netns exec "$ns_node" "$node" --lcm-url "$url" --exit-with-parent &
node_pid=$!
set +e
out="$(ip netns exec "$ns_plant" "$client" "$url" "$duration")"
client_code=$?
set -e
echo "two_hosts: plant_client (10.99.0.2) against tvo_firmware_node (10.99.0.1) on $url: $out"
[[ $client_code -eq 0 ]] || fail "plant_client exited with $client_code"

# The node exits after the client's STOP (no --keep-running).
for _ in $(seq 100); do
  kill -0 "$node_pid" 2>/dev/null || break
  sleep 0.1
done
kill -0 "$node_pid" 2>/dev/null && fail "tvo_firmware_node still running 10 s after the STOP"
set +e
wait "$node_pid"
node_code=$?
set -e
node_pid=""
[[ $node_code -eq 0 ]] || fail "tvo_firmware_node exited with $node_code"

packets() { ip netns exec "$1" cat "/sys/class/net/$2/statistics/$3"; }
node_rx="$(packets "$ns_node" vA rx_packets)" node_tx="$(packets "$ns_node" vA tx_packets)"
plant_rx="$(packets "$ns_plant" vB rx_packets)" plant_tx="$(packets "$ns_plant" vB tx_packets)"
echo "two_hosts: packets over the link: node side rx $node_rx tx $node_tx, plant side rx $plant_rx tx $plant_tx"
# One measurement and one command (plus telemetry) per period: at least one packet per step each way.
steps="$(awk -v d="$duration" 'BEGIN { printf "%d", d * 100 }')"
[[ $node_rx -ge $steps && $plant_rx -ge $steps ]] || fail "fewer than $steps packets crossed the link each way"

error="$(sed -n 's/^final_error_m=//p' <<<"$out")"
[[ -n "$error" ]] || fail "plant_client printed no final_error_m"
awk -v e="$error" -v m="$max_error" 'BEGIN { exit !(e < m) }' || fail "final error $error m, bound $max_error m"
echo "two_hosts: PASS: converged across the link, final error $error m < $max_error m"
