#!/usr/bin/env bash
# The real simulators on the same contact as `impact`: MuJoCo, LAMMPS, Kratos DEM and Drake each run a
# sphere on a wall or two spheres head-on (no gravity, no friction), and each driver prints the e the program gives
# beside impact's prediction at the program's time step (and in the continuous limit). Not run in CI: the programs
# are large. A program that is not installed is skipped with a message, and the script still exits 0 (1 if a
# driver fails otherwise).
#
#   scripts/peer-simulators.sh [mujoco] [lammps] [kratos] [drake]     # all four by default
#
# PEERS_PYTHON names the Python that has the programs (a venv's, see scripts/peers/README.md); python3 otherwise.
# Builds `impact` (cargo build --release) when the binary is older than the sources; IMPACT names another binary.
# (scripts/peers.sh is another comparison: the ODE solver peers of the Hunt-Crossley benchmark.)
set -u
cd "$(dirname "$0")/.."   # the repository's root
python=${PEERS_PYTHON:-python3}
if ! command -v "$python" >/dev/null 2>&1; then
    echo "no Python at '$python' (set PEERS_PYTHON to the venv's python, see scripts/peers/README.md)" >&2
    exit 2
fi

export IMPACT=${IMPACT:-$PWD/target/release/impact}
if [ "$IMPACT" = "$PWD/target/release/impact" ]; then
    newer=$(find src Cargo.toml Cargo.lock -newer "$IMPACT" -print -quit 2>/dev/null)
    if [ ! -x "$IMPACT" ] || [ -n "$newer" ]; then
        echo "building impact (cargo build --release) ..." >&2
        CARGO_BUILD_JOBS=${CARGO_BUILD_JOBS:-1} cargo build --release --quiet || exit 1
    fi
fi

drivers=("$@")
[ ${#drivers[@]} -eq 0 ] && drivers=(mujoco lammps kratos drake)
echo "impact $(git rev-parse --short HEAD 2>/dev/null), $("$python" --version 2>&1) at $(command -v "$python"), $(date -u '+%Y-%m-%d %H:%M UTC')"
status=0
for name in "${drivers[@]}"; do
    driver=scripts/peers/${name}_peer.py
    if [ ! -f "$driver" ]; then
        echo "no driver $driver (known: mujoco lammps kratos drake)" >&2
        status=1
        continue
    fi
    echo
    "$python" "$driver"
    rc=$?
    if [ $rc -eq 3 ]; then
        :   # skipped: the driver said why
    elif [ $rc -ne 0 ]; then
        echo "$name: the driver failed (exit status $rc)" >&2
        status=1
    fi
done
exit $status
