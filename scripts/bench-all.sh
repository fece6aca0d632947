#!/bin/sh
# Every speed figure of the project in one run, each beside its peers: the single impact's work-precision study
# (`impact bench`), the frictional oblique impacts (`impact bench --oblique`), the world runs (`impact bench
# --worlds`), the scipy and numba peers of the Hunt-Crossley impact (scripts/peers.sh), and LAMMPS on the bead chain
# (scripts/lammps_chain.py), the settling pile (scripts/lammps_pile.py) and Chung & Ooi's test 4 over a sweep of angles
# (scripts/lammps_oblique.py). Then OUT_DIR/summary.md: one table per study (case, program and setting, error against
# its reference, time, ratio to impact), with the machine, the build (git describe) and the load average, built by
# scripts/bench_summary.py from the CSV and JSON files the runs wrote. It measures and judges nothing: not for CI.
#
#   scripts/bench-all.sh [--quick] [OUT_DIR]       # OUT_DIR: default out/bench-all
#
#   --quick      each study's short form (a 100-bead chain, the pile's first 0.3 s, 17 angles of test 4, the coarser
#                LAMMPS steps): under a minute; the full run took 6-7 minutes on this project's 2-core machine
#                (docs/bench.md).
#
# Environment:
#   PEERS_DIR       the folder of scipy_peer.py and numba_peer.py (default /work/shared/tools)
#   PEERS_PYTHON    a Python with scipy and numba; otherwise python3 if it has them, or else a virtual environment
#                   target/peers-venv made here with pip install scipy numba
#   LAMMPS_PYTHON   a Python (3.11 or later) in which `import lammps` works (default python3), e.g.
#                   LAMMPS_PYTHON=/tmp/lmpvenv/bin/python; this script never installs LAMMPS
# A peer that is missing is skipped with one line saying why; the summary says so too.
#
# OUT_DIR must be new, empty, or a folder this script wrote before (it holds .bench-all): the script never writes
# over files it did not make. Each step's output and errors go to OUT_DIR/logs/; OUT_DIR/steps.tsv holds each
# step's exit status and duration. Exit status: 0 when every step ran or was skipped, 1 when a step failed (the
# summary is still written from what the others wrote), 2 for bad arguments.
set -u
me="bench-all.sh"

usage() {
    sed -n '2,/^$/p' "$0" | sed -n 's/^# \{0,1\}//p'
}
die() {
    echo "$me: $*" >&2
    exit 2
}

quick=0
out=""
while [ $# -gt 0 ]; do
    case $1 in
        --quick) quick=1 ;;
        -h | --help) usage; exit 0 ;;
        --) shift; [ $# -gt 0 ] && { [ -z "$out" ] || die "one OUT_DIR only (got '$out' and '$1')"; out=$1; shift; }
            [ $# -eq 0 ] || die "one OUT_DIR only (got more after '$out')"; break ;;
        -*) die "unknown option '$1' (expected --quick, --help, or OUT_DIR; see $0 --help)" ;;
        *) [ -z "$out" ] || die "one OUT_DIR only (got '$out' and '$1')"; out=$1 ;;
    esac
    shift
done
[ -n "$out" ] || out=out/bench-all
case $out in
    /*) ;;
    *) out="$PWD/$out" ;;
esac
out=$(realpath -m -- "$out" 2> /dev/null || echo "$out") # no .. nor links left, for the checks below

command -v python3 > /dev/null 2>&1 || die "python3 not found: the summary and the peers need Python 3"
root=$(cd "$(dirname "$0")/.." && pwd) || die "cannot find the repository from $0"
# The output folder: not among the sources, a folder, new or empty or written by this script before, writable.
case "$out/" in
    "$root/src/"* | "$root/models/"* | "$root/scripts/"* | "$root/docs/"* | "$root/tests/"* | "$root/plots/"* | \
        "$root/python/"* | "$root/examples/"* | "$root/benches/"* | "$root/fuzz/"* | "$root/" | "$root//")
        die "OUT_DIR '$out' is among the repository's sources: give a folder under out/ or elsewhere" ;;
esac
if [ -e "$out" ] && [ ! -d "$out" ]; then
    die "OUT_DIR '$out' exists and is not a folder"
fi
if [ -d "$out" ] && [ -n "$(ls -A "$out" 2>/dev/null)" ] && [ ! -f "$out/.bench-all" ]; then
    die "OUT_DIR '$out' holds files this script did not write: it never writes over them (give a new or empty folder)"
fi
mkdir -p "$out" 2>/dev/null || die "cannot create OUT_DIR '$out'"
{ : > "$out/.bench-all"; } 2>/dev/null || die "cannot write into OUT_DIR '$out'"
out=$(cd "$out" && pwd)
cd "$root" || die "cannot enter the repository $root"

rm -rf "$out/logs" "$out/bench" "$out/oblique" "$out/worlds" "$out/peers" "$out/lammps" "$out/steps.tsv" \
    "$out/run.tsv" "$out/summary.md"
mkdir -p "$out/logs" "$out/lammps" || die "cannot write into OUT_DIR '$out'"
: > "$out/steps.tsv"
failures=0
started=$(date +%s)
load_start=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown)
echo "$me: $( [ $quick = 1 ] && echo quick || echo full ) run into $out (load average $load_start)" >&2

now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }
# step NAME COMMAND...: runs COMMAND, its output to logs/NAME.out and errors to logs/NAME.log; records it.
step() {
    name=$1
    shift
    echo "[$(date -u +%H:%M:%S)] $name ..." >&2
    t0=$(now)
    "$@" > "$out/logs/$name.out" 2> "$out/logs/$name.log"
    rc=$?
    seconds=$(elapsed "$t0" "$(now)")
    printf '%s\t%s\t%s\n' "$name" "$rc" "$seconds" >> "$out/steps.tsv"
    if [ $rc -ne 0 ]; then
        echo "$me: $name failed (exit $rc) after $seconds s: see $out/logs/$name.log" >&2
        tail -n 3 "$out/logs/$name.log" | sed 's/^/    /' >&2
        failures=$((failures + 1))
    fi
    return $rc
}
# skip NAME WHY: one line, and a row of steps.tsv that the summary shows.
skip() {
    echo "$me: skipped $1: $2" >&2
    printf '%s\tskipped\t%s\n' "$1" "$2" >> "$out/steps.tsv"
}

if command -v cargo > /dev/null 2>&1; then
    cargo build --release --quiet 2> "$out/logs/build.log" || die "cargo build --release failed: see $out/logs/build.log"
fi
impact=$root/target/release/impact
[ -x "$impact" ] || die "no $impact: build it with cargo build --release"
build=$(git describe --always --dirty 2> /dev/null || echo unknown)

# --- impact's own studies ----------------------------------------------------------------------------------------
q=""
[ $quick = 1 ] && q="--quick"
step impact-bench "$impact" bench $q --out "$out/bench"
step impact-oblique "$impact" bench --oblique $q --out "$out/oblique"
step impact-worlds "$impact" bench --worlds $q --out "$out/worlds"

# --- the scipy and numba peers -----------------------------------------------------------------------------------
peers_dir=${PEERS_DIR:-/work/shared/tools}
has_peer_modules() { "$1" -c "import scipy, numba" > /dev/null 2>&1; }
peers_python=""
if [ ! -f "$peers_dir/scipy_peer.py" ] || [ ! -f "$peers_dir/numba_peer.py" ]; then
    skip peers "no scipy_peer.py and numba_peer.py in '$peers_dir' (set PEERS_DIR)"
elif [ -n "${PEERS_PYTHON:-}" ]; then
    if has_peer_modules "$PEERS_PYTHON"; then
        peers_python=$PEERS_PYTHON
    else
        skip peers "PEERS_PYTHON='$PEERS_PYTHON' cannot import scipy and numba"
    fi
elif has_peer_modules python3; then
    peers_python=python3
else
    venv=$root/target/peers-venv
    if ! has_peer_modules "$venv/bin/python"; then
        echo "$me: installing scipy and numba into $venv (pip) ..." >&2
        { python3 -m venv "$venv" && "$venv/bin/python" -m pip install --quiet scipy numba; } \
            > "$out/logs/peers-install.log" 2>&1
    fi
    if has_peer_modules "$venv/bin/python"; then
        peers_python=$venv/bin/python
    else
        skip peers "no Python with scipy and numba (installing them into $venv failed: see $out/logs/peers-install.log)"
    fi
fi
if [ -n "$peers_python" ]; then
    mkdir -p "$out/peers"
    step peers env PYTHON="$peers_python" sh scripts/peers.sh "$peers_dir" "$out/peers"
fi

# --- LAMMPS ------------------------------------------------------------------------------------------------------
lammps_python=${LAMMPS_PYTHON:-python3}
if ! command -v "$lammps_python" > /dev/null 2>&1; then
    skip lammps "LAMMPS_PYTHON='$lammps_python' is not a program (set LAMMPS_PYTHON=/path/to/python)"
elif ! "$lammps_python" -c 'import importlib.util, sys
sys.exit(0 if sys.version_info >= (3, 11) and importlib.util.find_spec("lammps") else 1)' > /dev/null 2>&1; then
    skip lammps "no 'import lammps' in $lammps_python (Python 3.11 or later; set LAMMPS_PYTHON=/path/to/python)"
else
    lmp=$out/lammps
    # The chain of impact's --worlds study (100 beads with --quick, 1000 without), to its end time, and impact's own
    # run of it at 1e-13: LAMMPS' error is its largest bead velocity difference from that run, over v0.
    if [ $quick = 1 ]; then beads=100; chain_steps="50 200"; else beads=1000; chain_steps="50 200 800"; fi
    tau=3.0082056890973155e-05 # the beads' two-ball contact time at 1 m/s (scripts/lammps_chain.py)
    chain_end=$(python3 -c "import math; print(math.ceil(0.488 * ($beads - 1) + 10) * $tau)")
    python3 scripts/bench_summary.py --chain-scene "$beads" "$chain_end" 1e-13 > "$lmp/chain-$beads-reference.toml"
    step chain-reference sh -c '"$0" run "$1" --json > "$2"' "$impact" "$lmp/chain-$beads-reference.toml" \
        "$lmp/chain-$beads-reference.json"
    for s in $chain_steps; do
        step "lammps-chain-$s" "$lammps_python" scripts/lammps_chain.py --beads "$beads" --steps-per-contact "$s" \
            --end-time "$chain_end" --out "$lmp/chain-$beads-s$s.json"
    done
    # The settling pile: its 2 s (the first 0.3 s with --quick, as impact's study runs it).
    if [ $quick = 1 ]; then
        sed 's/^end_time = 2.0/end_time = 0.3/' models/settling-pile.toml > "$lmp/settling-pile-0.3s.toml"
        pile_scene=$lmp/settling-pile-0.3s.toml
        pile_steps="1e-6"
    else
        pile_scene=models/settling-pile.toml
        pile_steps="1e-6 2.5e-7"
    fi
    for dt in $pile_steps; do
        step "lammps-pile-$dt" "$lammps_python" scripts/lammps_pile.py --scene "$pile_scene" --dt "$dt" \
            --out "$lmp/pile-$dt.json"
    done
    # Chung & Ooi's test 4 over a sweep of angles.
    if [ $quick = 1 ]; then
        step lammps-oblique "$lammps_python" scripts/lammps_oblique.py --angles 5:85:17 --steps-per-contact 50 200 \
            --impact "$impact" --out "$lmp/oblique.json"
    else
        step lammps-oblique "$lammps_python" scripts/lammps_oblique.py --impact "$impact" --out "$lmp/oblique.json"
    fi
fi

# --- the summary -------------------------------------------------------------------------------------------------
load_end=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown)
duration=$(($(date +%s) - started))
machine="$(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | cut -d: -f2 | sed 's/^ //'), $(nproc) cores"
# The run's own facts, beside its files: scripts/bench_summary.py OUT_DIR rebuilds the summary from them alone.
printf 'quick\t%s\nbuild\t%s\nmachine\t%s\nload_start\t%s\nload_end\t%s\nduration\t%s\nstarted\t%s\n' "$quick" \
    "$build" "$machine" "$load_start" "$load_end" "$duration" "$(date -u -d "@$started" '+%Y-%m-%d %H:%M UTC')" \
    > "$out/run.tsv"
python3 scripts/bench_summary.py "$out" > "$out/summary.md.partial" 2> "$out/logs/summary.log"
if [ $? -eq 0 ]; then
    mv "$out/summary.md.partial" "$out/summary.md"
    echo "$me: wrote $out/summary.md ($duration s, load average $load_start at the start, $load_end at the end)" >&2
else
    rm -f "$out/summary.md.partial"
    echo "$me: the summary failed: see $out/logs/summary.log" >&2
    tail -n 3 "$out/logs/summary.log" | sed 's/^/    /' >&2
    exit 1
fi
[ $failures -eq 0 ] || { echo "$me: $failures step(s) failed (see $out/steps.tsv)" >&2; exit 1; }
exit 0
