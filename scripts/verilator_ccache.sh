# verilator_ccache.sh: sourced by the scripts that build Verilator models
# (sim.sh, cosim.sh), after they set $root to the repository's root.
#
# Every Verilator build compiles the same runtime (verilated*.cpp): with
# ccache (make deps installs it) each build after the first reuses it.
#
# Verilator writes the file names it is given into the C++ it generates
# ($fatal's file and line, coverage points). Given absolute names, a clone
# in another folder (a fresh CI checkout) generates other C++ and ccache
# misses every model: about 8 s of CPU per build, some 150 builds in make
# test. So the scripts run Verilator from $root and name the files under
# it relative to it (in_repo), and ccache rewrites the absolute paths under
# $root on the compiler's command line (the main's .cpp) relative to the
# build folder (CCACHE_BASEDIR), which is the same in any clone.
command -v ccache > /dev/null 2>&1 && export OBJCACHE=${OBJCACHE:-ccache}
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$root}

# in_repo PATH: PATH relative to $root when it lies inside it, else as it is
# (a mutant's RTL_DIR).
in_repo() { case "$1" in "$root"/*) echo "${1#"$root"/}" ;; *) echo "$1" ;; esac; }
