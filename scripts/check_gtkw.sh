#!/usr/bin/env bash
# check_gtkw.sh: open every committed .gtkw in GTKWave (headless, under Xvfb)
# and require that GTKWave resolved every signal it names. GTKWave silently
# drops a name it cannot find in the VCD, so a layout that drifted from the
# waveform would otherwise go unnoticed until an engineer opens it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
script=$(mktemp --suffix=.tcl)
trap 'rm -f "$script"' EXIT
cat > "$script" <<'TCL'
set n [gtkwave::getTotalNumTraces]
for {set i 0} {$i < $n} {incr i} { puts "trace: [gtkwave::getTraceNameFromIndex $i]" }
gtkwave::/File/Quit
TCL
passed=0 failed=0
for gtkw in "$root"/vectors/*/*.gtkw; do
    dir=$(dirname "$gtkw")
    # Names as the save file gives them: top.scope.name[msb:lsb] -> name[msb:lsb].
    expected=$(grep '^top\.' "$gtkw" | sed 's/.*\.//' | sort)
    got=$(cd "$dir" && timeout 120 xvfb-run -a gtkwave -S "$script" "$(basename "$gtkw")" 2>/dev/null \
        | sed -n 's/^trace: //p' | grep -vxF -f <(sed -n 's/^-//p' "$gtkw") | sort || true)
    if [ "$expected" = "$got" ]; then
        passed=$((passed + 1))
    else
        failed=$((failed + 1))
        echo "gtkw FAIL $(basename "$gtkw"): GTKWave shows other signals than the layout names"
        diff <(echo "$expected") <(echo "$got") | head -n 10 | sed 's/^/      /'
    fi
done
echo "gtkw: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
