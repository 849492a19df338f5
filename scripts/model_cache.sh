# model_cache.sh: sourced by sim.sh. A cache of built Verilator replay
# models (the Vtb binaries) for the whole machine, shared by every clone.
#
# Why: even when ccache has every object, a Verilator build still runs
# Verilator's parse and elaboration, ccache's look-ups and the link: about
# 2.5 s of CPU, for some 130 builds in make test (a third of the hdl stage's
# CPU). A fresh clone (CI's checkout) has an empty build/sim/ and pays them
# all again. The models are the same bytes in any clone (Verilator runs on
# names relative to the repository: verilator_ccache.sh; checked with cmp
# across clones), so one built here can be copied there instead.
#
# The entry's name is a hash of sim.sh's build key (parameters, flags and
# the contents of every source), the sources' names as Verilator saw them,
# and the versions of Verilator and the C++ compiler: any change to what the
# model is built from, or with, is another entry.
#
#   ENCODER_TB_MODEL_CACHE     the folder (default ~/.cache/encoder-tb/models);
#                              set it empty to build every model in place
#   ENCODER_TB_MODEL_CACHE_MB  its size limit (default 1024): after each
#                              store, the least recently used models go
#                              until it fits (a replay model is about 1 MB)
model_cache_dir=${ENCODER_TB_MODEL_CACHE-${XDG_CACHE_HOME:-$HOME/.cache}/encoder-tb/models}

# model_cache_key WORDS...: the entry name for a build described by WORDS,
# with the tools' versions added.
model_cache_key() {
    { printf '%s\n' "$@"; verilator --version 2>&1; "${CXX:-g++}" --version 2>&1 | head -n 1; } | sha1sum | cut -c1-20
}

# model_cache_get KEY DEST: copy the cached model KEY to DEST (atomically);
# fails when there is none or the cache is off.
model_cache_get() {
    [ -n "$model_cache_dir" ] && [ -f "$model_cache_dir/$1" ] || return 1
    cp "$model_cache_dir/$1" "$2.cache.$$" 2> /dev/null || { rm -f "$2.cache.$$"; return 1; }
    chmod +x "$2.cache.$$" && mv "$2.cache.$$" "$2"
    touch "$model_cache_dir/$1" 2> /dev/null || true   # recently used: evicted last
}

# model_cache_put KEY SRC: store the model SRC as KEY, then evict the least
# recently used models past the size limit. Never fails the build: a full
# disk or a read-only cache only means the next clone builds again.
model_cache_put() {
    [ -n "$model_cache_dir" ] || return 0
    mkdir -p "$model_cache_dir" 2> /dev/null || return 0
    cp "$2" "$model_cache_dir/.tmp.$1.$$" 2> /dev/null && mv "$model_cache_dir/.tmp.$1.$$" "$model_cache_dir/$1" \
        || { rm -f "$model_cache_dir/.tmp.$1.$$"; return 0; }
    local limit=$(( ${ENCODER_TB_MODEL_CACHE_MB:-1024} * 1024 * 1024 )) total size name
    total=$(find "$model_cache_dir" -maxdepth 1 -type f -printf '%s\n' 2> /dev/null | awk '{ s += $1 } END { print s + 0 }')
    [ "$total" -gt "$limit" ] || return 0
    find "$model_cache_dir" -maxdepth 1 -type f -printf '%T@ %s %f\n' 2> /dev/null | sort -n \
        | while read -r _ size name; do
            [ "$total" -gt "$limit" ] || break
            rm -f "$model_cache_dir/$name" && total=$(( total - size ))
        done
    return 0
}
