#!/usr/bin/env bash
# "On two machines": tvo_firmware_node in one network namespace, a plant in another, joined by a veth
# pair; LCM multicast (ttl=1) crosses the link between them, as between two hosts. Two plants in turn,
# each against a fresh node: the example plant client, then the simulator (tvo_sim without --firmware).
# Asserts each run converges (each plant hears the node's announcement, its boot, across the link and
# names it in its START), the node exits with 0 after the plant's STOP, and the traffic went over the
# link. Skipped (exit 77) where namespaces cannot be created (not root, no CAP_NET_ADMIN).
# Every address lives inside the two namespaces it creates; they are removed on exit.
#
# Usage: two_hosts.sh NODE PLANT_CLIENT SIM PORT OUT_DIR [DURATION_S [MAX_ERROR_M]]
set -euo pipefail

skip_code=77
if [[ $# -lt 5 ]]; then
  echo "usage: two_hosts.sh NODE PLANT_CLIENT SIM PORT OUT_DIR [DURATION_S [MAX_ERROR_M]]" >&2
  exit 2
fi
node="$1" client="$2" sim="$3" port="$4" out_dir="$5" duration="${6:-5}" max_error="${7:-1e-3}"
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
below() { awk -v e="$1" -v m="$2" 'BEGIN { exit !(e < m) }'; }
packets() { ip netns exec "$1" cat "/sys/class/net/$2/statistics/$3"; }

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
mkdir -p "$out_dir"

# run_across NAME COMMAND...: a fresh node at 10.99.0.1, the plant COMMAND at 10.99.0.2; the node
# must exit with 0 after the plant's STOP, and at least one packet per period must cross each way.
run_across() {
  local name="$1"
  shift
  local rx_before
  rx_before="$(packets "$ns_node" vA rx_packets)"
  ip netns exec "$ns_node" "$node" --lcm-url "$url" --boot-file "$out_dir/node.boot" --exit-with-parent &
  node_pid=$!
  local code=0
  ip netns exec "$ns_plant" "$@" >"$out_dir/$name.log" 2>&1 || code=$?
  [[ $code -eq 0 ]] || { cat "$out_dir/$name.log" >&2; fail "$name exited with $code"; }
  for _ in $(seq 100); do
    kill -0 "$node_pid" 2>/dev/null || break
    sleep 0.1
  done
  kill -0 "$node_pid" 2>/dev/null && fail "tvo_firmware_node still running 10 s after $name's STOP"
  code=0
  wait "$node_pid" || code=$?
  node_pid=""
  [[ $code -eq 0 ]] || fail "tvo_firmware_node exited with $code after $name"
  local node_rx plant_rx steps
  node_rx=$(($(packets "$ns_node" vA rx_packets) - rx_before))
  plant_rx="$(packets "$ns_plant" vB rx_packets)"
  steps="$(awk -v d="$duration" 'BEGIN { printf "%d", d * 100 }')"
  echo "two_hosts: $name: $node_rx packets in at the node (10.99.0.1), $plant_rx in at the plant side so far"
  [[ $node_rx -ge $steps ]] || fail "$name: fewer than $steps packets reached the node over the link"
}

run_across plant_client "$client" "$url" "$duration"
error="$(sed -n 's/^final_error_m=//p' "$out_dir/plant_client.log")"
[[ -n "$error" ]] || fail "plant_client printed no final_error_m"
below "$error" "$max_error" || fail "plant_client: final error $error m, bound $max_error m"
echo "two_hosts: PASS: plant_client converged across the link, final error $error m < $max_error m"

run_across tvo_sim "$sim" --lcm-url "$url" --duration-s "$duration" --out-dir "$out_dir/tvo_sim"
error="$(sed -n 's/.*"final_error_m": *\([0-9.eE+-]*\).*/\1/p' "$out_dir/tvo_sim/summary.json")"
[[ -n "$error" ]] || fail "tvo_sim wrote no final_error_m in $out_dir/tvo_sim/summary.json"
below "$error" "$max_error" || fail "tvo_sim: final error $error m, bound $max_error m"
echo "two_hosts: PASS: tvo_sim converged across the link, final error $error m < $max_error m"
