#!/usr/bin/env bash
# protocols.sh: the protocol descriptors (`tbgen protocols --json`, declared
# in model/src/<protocol>/descriptor.rs) as lines for the bash scripts, so
# that no script keeps a list of protocols, cores or closed loops of its own.
# Sourced, after $root is set; runs the tbgen of this checkout's target
# (make build, scripts/emu_lib.sh), builds nothing.
#
#   closed_loops   one line per closed loop, in registry order:
#                  name top stem kind emu_module quick bench_transactions
#                  (kind: the emulator's, `+<kind>_emu_config` its plusarg)

protocols_json() {
    local tbgen="${CARGO_TARGET_DIR:-$root/target}/release/tbgen"
    [ -x "$tbgen" ] || { echo "protocols.sh: no $tbgen: build it first (make build)" >&2; return 2; }
    "$tbgen" protocols --json
}

closed_loops() {
    local json
    json=$(protocols_json) || return 2
    python3 -c '
import json, sys
for p in json.load(sys.stdin):
    for l in p["closed_loops"]:
        e = p["emulator"]
        print(l["name"], l["top"], p["stem"], e["kind"], e["module"], l["quick"], l["bench_transactions"])
' <<< "$json"
}
