#!/usr/bin/env bash
# scripts/synth.sh — synthesise each core for a Lattice iCE40 HX8K (ct256 package),
# place & route it, and check it meets its required clock frequency.
#
# Usage:
#   scripts/synth.sh              every core with a hdl/tb/<core>/synth.cfg
#   scripts/synth.sh CORE...      only these cores (each must have its synth.cfg)
#
# Flow, per core (all outputs in build/synth/):
#   1. yosys 0.23:  read_verilog -defer hdl/rtl/*.v      (all RTL files; only what the
#                   chparam -set PARAM VALUE CORE         top instantiates is elaborated)
#                   synth_ice40 -top CORE -json CORE.json
#      The generated script is kept as CORE.ys, its log as CORE.yosys.log.
#   2. nextpnr-ice40 0.4: --hx8k --package ct256 --freq REQUIRED --seed 1
#      --timing-allow-fail (we judge Fmax ourselves), no .pcf (IO auto-placed),
#      writes CORE.asc, log CORE.nextpnr.log.
#   3. From the nextpnr log: ICESTORM_LC, ICESTORM_RAM and SB_IO usage, and the last
#      (post-route) "Max frequency for clock" figure of the core's clock.
# Then one table row per core: LCs | RAM | IO | Fmax | required | PASS/FAIL | seconds.
#
# Exit status: 0 if every core passed; 1 if any core missed its Fmax or a tool failed
# (the core and its log file are named); 2 for a bad config or command line.
#
# Environment overrides (paths may be relative to the current directory):
#   SYNTH_CFG          one config file listing cores, instead of every
#                      hdl/tb/<core>/synth.cfg (each core keeps its target in
#                      its own folder, so a new core adds no line elsewhere)
#   RTL_DIR            directory of *.v files (default: <repo>/hdl/rtl)
#   SYNTH_BUILD_DIR    output directory       (default: <repo>/build/synth)
#   SYNTH_SEED         nextpnr placer seed    (default: 1, fixed so figures reproduce)
#   SYNTH_CLOCK        names of the clock input port judged against the required Fmax
#                      when a core has several clocks (space-separated, first match
#                      wins; default: "clk i_clk clk_i"). A core with a single clock
#                      is judged on that clock whatever its name.
#   SYNTH_SKIP_MISSING =1: a core whose RTL_DIR/<core>.v does not exist yet is shown
#                      as SKIP instead of FAIL.
#
# Config file format (hdl/tb/<core>/synth.cfg, or SYNTH_CFG):
#
# One core per line:
#
#   <core-name> <required-fmax-MHz> [PARAM=value ...]
#
#   core-name     Verilog module name; its RTL is hdl/rtl/<core-name>.v. All of
#                 hdl/rtl/*.v are read, so sub-modules may live in other files.
#                 Each core may appear only once (outputs are named after it).
#   required-fmax Clock frequency in MHz the core must reach after place & route
#                 (integer or decimal). It is also nextpnr's --freq target. If the
#                 core has several clocks, the one from input port clk, i_clk or
#                 clk_i is judged (override with SYNTH_CLOCK="<port> ...").
#   PARAM=value   Top-level parameter overrides, applied with yosys
#                 `chparam -set PARAM value <core>`. No spaces around '='.
#                 Prefer plain decimal values (12, 200): like unsized Verilog
#                 literals they become 32-bit. A sized literal (4'd3) keeps its
#                 width, and a string needs double quotes (NAME="abc").
#
# '#' starts a comment (whole line or end of line); blank lines are ignored.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

# Resolve a path given by the user relative to the directory we were started in.
abspath() { case $1 in /*) echo "$1" ;; *) echo "$PWD/$1" ;; esac; }

if [[ -n ${SYNTH_CFG:-} ]]; then
    CFGS=("$(abspath "$SYNTH_CFG")")
else
    shopt -s nullglob
    CFGS=("$ROOT"/hdl/tb/*/synth.cfg)
    shopt -u nullglob
fi
RTL=$(abspath "${RTL_DIR:-$ROOT/hdl/rtl}")
OUT=$(abspath "${SYNTH_BUILD_DIR:-$ROOT/build/synth}")
SEED=${SYNTH_SEED:-1}
CLOCKS=${SYNTH_CLOCK:-clk i_clk clk_i}
SKIP_MISSING=${SYNTH_SKIP_MISSING:-0}

DEVICE_ARGS=(--hx8k --package ct256)

die()  { printf 'synth: ERROR: %s\n' "$*" >&2; exit 2; }
now()  { echo "${EPOCHREALTIME:-$(date +%s.%N)}"; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }   # seconds since $1

if [[ ${1:-} == -h || ${1:-} == --help ]]; then
    sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'
    exit 0
fi

for tool in yosys nextpnr-ice40; do
    command -v "$tool" >/dev/null 2>&1 || die "$tool not found; run scripts/deps.sh (or: apt-get install $tool)"
done
(( ${#CFGS[@]} )) || die "no hdl/tb/<core>/synth.cfg found (nor SYNTH_CFG)"
for CFG in "${CFGS[@]}"; do [[ -f $CFG ]] || die "config file $CFG not found"; done
[[ -d $RTL ]] || die "RTL directory $RTL not found"

# ---------------------------------------------------------------------------
# Read the config: CORES[i], FMAX[i], PARAMS[i] (space-separated NAME=VALUE list).
# ---------------------------------------------------------------------------
CORES=(); FMAX=(); PARAMS=()
for CFG in "${CFGS[@]}"; do
lineno=0
while IFS= read -r line || [[ -n $line ]]; do
    lineno=$((lineno + 1))
    line=${line%%#*}                          # drop comments
    read -r -a words <<<"$line" || true       # split on blanks
    (( ${#words[@]} )) || continue            # blank line
    where="$CFG:$lineno"
    (( ${#words[@]} >= 2 )) || die "$where: expected '<core> <fmax-MHz> [PARAM=value ...]'"
    core=${words[0]} fmax=${words[1]}
    [[ $core =~ ^[A-Za-z_][A-Za-z0-9_]*$ ]] || die "$where: '$core' is not a Verilog module name"
    [[ $fmax =~ ^[0-9]+(\.[0-9]+)?$ ]]      || die "$where: required Fmax '$fmax' is not a number of MHz"
    for p in "${words[@]:2}"; do
        [[ $p =~ ^[A-Za-z_][A-Za-z0-9_]*=[^=]+$ ]] || die "$where: '$p' is not PARAM=value"
    done
    for c in "${CORES[@]}"; do
        [[ $c != "$core" ]] || die "$where: core '$core' is listed twice"
    done
    CORES+=("$core"); FMAX+=("$fmax"); PARAMS+=("${words[*]:2}")
done <"$CFG"
done

# Which cores to run: all, or those named on the command line.
SELECTED=()
if (( $# )); then
    for want in "$@"; do
        found=
        for i in "${!CORES[@]}"; do [[ ${CORES[i]} == "$want" ]] && found=$i; done
        [[ -n $found ]] || die "core '$want' has no synthesis target: add hdl/tb/$want/synth.cfg"
        SELECTED+=("$found")
    done
else
    SELECTED=("${!CORES[@]}")
fi
if (( ${#SELECTED[@]} == 0 )); then
    echo "synth: no cores listed; nothing to do."
    exit 0
fi

shopt -s nullglob
RTL_FILES=("$RTL"/*.v)
shopt -u nullglob
mkdir -p "$OUT"

# ---------------------------------------------------------------------------
# parse_nextpnr LOG — print "LC_USED LC_AVAIL RAM_USED RAM_AVAIL IO_USED IO_AVAIL CLOCKS"
# where CLOCKS is "name=MHz,name=MHz..." with the LAST figure seen for each clock
# (nextpnr 0.4 prints one after placement and a final one after routing; the final
# one is an ERROR: line instead of Info: when timing fails without --timing-allow-fail).
# Missing figures are printed as "-".
# ---------------------------------------------------------------------------
parse_nextpnr() {
    awk -v q="'" '
        # utilisation table line: "Info:  <tab>   ICESTORM_LC:    36/ 7680     0%"
        function usage(key,   a) {
            split($3 $4, a, "/"); used[key] = a[1]; avail[key] = a[2]
        }
        $1 == "Info:" && $2 == "ICESTORM_LC:"  { usage("lc") }
        $1 == "Info:" && $2 == "ICESTORM_RAM:" { usage("ram") }
        $1 == "Info:" && $2 == "SB_IO:"        { usage("io") }
        /Max frequency for clock/ {
            split($0, part, q)                   # ... clock <q>NAME<q>: 190.33 MHz (PASS ...
            name = part[2]
            mhz = part[3]; sub(/^: */, "", mhz); sub(/ MHz.*/, "", mhz)
            if (!(name in fmax)) order[++n] = name
            fmax[name] = mhz
        }
        END {
            clocks = ""
            for (i = 1; i <= n; i++) clocks = clocks (i > 1 ? "," : "") order[i] "=" fmax[order[i]]
            printf "%s %s %s %s %s %s %s\n",
                ("lc"  in used ? used["lc"]  : "-"), ("lc"  in avail ? avail["lc"]  : "-"),
                ("ram" in used ? used["ram"] : "-"), ("ram" in avail ? avail["ram"] : "-"),
                ("io"  in used ? used["io"]  : "-"), ("io"  in avail ? avail["io"]  : "-"),
                (clocks == "" ? "-" : clocks)
        }' "$1"
}

# pick_clock "name=MHz,..." — print "MHz NAME" for the clock that judges the core:
# the only clock; else the first one whose net comes from a port named in $CLOCKS
# (nextpnr names the net of port clk e.g. clk$SB_IO_IN_$glb_clk); else the slowest
# one. Prints nothing if there is no clock.
pick_clock() {
    local list=$1 entry name mhz port best='' bestname=''
    [[ $list == - ]] && return 0
    local -a entries
    IFS=, read -r -a entries <<<"$list"
    if (( ${#entries[@]} == 1 )); then
        echo "${entries[0]##*=} ${entries[0]%=*}"; return 0
    fi
    for port in $CLOCKS; do
        for entry in "${entries[@]}"; do
            name=${entry%=*}; mhz=${entry##*=}
            if [[ ${name%%\$*} == "$port" ]]; then echo "$mhz $name"; return 0; fi
        done
    done
    for entry in "${entries[@]}"; do
        name=${entry%=*}; mhz=${entry##*=}
        if [[ -z $best ]] || awk -v a="$mhz" -v b="$best" 'BEGIN { exit !(a < b) }'; then
            best=$mhz; bestname=$name
        fi
    done
    echo "$best $bestname (slowest of ${#entries[@]} clocks; none from a port named: $CLOCKS)"
}

# ---------------------------------------------------------------------------
# Run every selected core. Results go into row arrays printed at the end.
# ---------------------------------------------------------------------------
ROWS=(); PROBLEMS=(); NOTES=()
overall=0
row() { ROWS+=("$(printf '%-20s %13s %7s %9s %9s %9s  %-6s %6s' "$@")"); }

for i in "${SELECTED[@]}"; do
    core=${CORES[i]}; req=${FMAX[i]}; params=${PARAMS[i]}
    ys=$OUT/$core.ys; json=$OUT/$core.json; asc=$OUT/$core.asc
    ylog=$OUT/$core.yosys.log; plog=$OUT/$core.nextpnr.log
    t0=$(now)
    rm -f "$json" "$asc"            # never report stale results
    echo "synth: $core (required ${req} MHz${params:+, $params})" >&2

    if [[ ! -f $RTL/$core.v ]]; then
        if [[ $SKIP_MISSING == 1 ]]; then
            row "$core" - - - - "$req" SKIP -
            NOTES+=("$core: $RTL/$core.v does not exist yet (skipped)")
        else
            row "$core" - - - - "$req" FAIL -
            PROBLEMS+=("$core: RTL file $RTL/$core.v not found"); overall=1
        fi
        continue
    fi

    # --- 1. yosys -----------------------------------------------------------
    {
        echo "# generated by scripts/synth.sh for core $core"
        echo "read_verilog -defer -I $RTL ${RTL_FILES[*]}"
        for p in $params; do echo "chparam -set ${p%%=*} ${p#*=} $core"; done
        echo "synth_ice40 -top $core -json $json"
    } >"$ys"
    if ! yosys -q -l "$ylog" -s "$ys" >/dev/null 2>&1 || [[ ! -s $json ]]; then
        row "$core" - - - - "$req" FAIL "$(since "$t0")"
        PROBLEMS+=("$core: yosys failed: $(grep -m1 'ERROR' "$ylog" || echo 'no ERROR line') (log: $ylog)")
        overall=1
        continue
    fi
    nwarn=$(grep -c '^Warning:' "$ylog" || true)
    (( nwarn == 0 )) || NOTES+=("$core: $nwarn yosys warning(s), see $ylog")

    # --- 2. nextpnr ---------------------------------------------------------
    if ! nextpnr-ice40 "${DEVICE_ARGS[@]}" --json "$json" --freq "$req" --seed "$SEED" \
            --timing-allow-fail --asc "$asc" --log "$plog" -q >/dev/null 2>&1 || [[ ! -s $asc ]]; then
        row "$core" - - - - "$req" FAIL "$(since "$t0")"
        PROBLEMS+=("$core: nextpnr-ice40 failed: $(grep -m1 'ERROR' "$plog" || echo 'no ERROR line') (log: $plog)")
        overall=1
        continue
    fi
    secs=$(since "$t0")

    # --- 3. figures ---------------------------------------------------------
    read -r lc lcav ram ramav io ioav clocks < <(parse_nextpnr "$plog")
    clk=$(pick_clock "$clocks")
    if [[ -z $clk ]]; then
        row "$core" "$lc/$lcav" "$ram/$ramav" "$io/$ioav" - "$req" FAIL "$secs"
        if grep -q 'has no interior paths' "$plog"; then
            why="no register-to-register path on any clock, so nextpnr gives no Fmax"
        else
            why="no clock found (combinational core?), so nextpnr gives no Fmax"
        fi
        PROBLEMS+=("$core: $why (log: $plog)")
        overall=1
        continue
    fi
    mhz=${clk%% *}
    [[ $clk == *"slowest of"* ]] && NOTES+=("$core: Fmax is for ${clk#* }")
    if awk -v f="$mhz" -v r="$req" 'BEGIN { exit !(f >= r) }'; then
        verdict=PASS
    else
        verdict=FAIL; overall=1
        PROBLEMS+=("$core: Fmax $mhz MHz < required $req MHz on clock ${clk#* } (log: $plog)")
    fi
    row "$core" "$lc/$lcav" "$ram/$ramav" "$io/$ioav" "$mhz" "$req" "$verdict" "$secs"
done

# ---------------------------------------------------------------------------
# Report
# ---------------------------------------------------------------------------
echo
echo "iCE40 HX8K ct256, yosys synth_ice40 + nextpnr-ice40 --seed $SEED   (outputs: $OUT)"
printf '%-20s %13s %7s %9s %9s %9s  %-6s %6s\n' core LCs RAM IO "Fmax MHz" "req MHz" result "time s"
printf '%s\n' "-------------------------------------------------------------------------------------"
printf '%s\n' "${ROWS[@]}"
for n in "${NOTES[@]}"; do echo "note: $n"; done
if (( overall )); then
    for p in "${PROBLEMS[@]}"; do echo "synth: FAIL: $p" >&2; done
    exit 1
fi
nskip=$(printf '%s\n' "${ROWS[@]}" | grep -c ' SKIP ' || true)
if (( nskip )); then
    echo "synth: $(( ${#SELECTED[@]} - nskip )) core(s) PASS, $nskip SKIPPED (no RTL yet)"
else
    echo "synth: all ${#SELECTED[@]} core(s) PASS"
fi
