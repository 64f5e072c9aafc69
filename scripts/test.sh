#!/usr/bin/env bash
# The one command that runs every test of the workspace on a fresh machine (what CI runs):
#   ./scripts/test.sh
# Steps: formatting; lints (warnings are errors; the library also without its default
# features, which must not depend on plotters or argmin); every Rust test in release mode
# with cargo-nextest (one process a test, the tests marked slow included, a per-test
# timeout: .config/nextest.toml) and the library's doc tests (one merged binary, edition
# 2024); every output of the release CLI against tests/reference/ (values within 1e-9),
# kept in target/ci-out; the commands of the docs (reusing what the reference check ran);
# the Python package (maturin, reusing the release build of the library), its pytest suite
# (per-test timeout) and notebooks. Chromium and the Python packages install in the
# background while Rust compiles. Every step prints its elapsed seconds, and the script
# ends with a table of the steps and the slowest Rust tests. Exits non-zero at the first
# failing step.
#
# The quick tier, for the edit loop:
#   ./scripts/test.sh --quick
# formatting, both lints, the dependency check, and the Rust tests and doc tests without
# the tests marked slow; no reference outputs, no Python, no browser.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

QUICK=0
case "${1:-}" in
    --quick) QUICK=1 ;;
    "") ;;
    *)
        echo "usage: $0 [--quick]" >&2
        exit 2
        ;;
esac

TARGET=${CARGO_TARGET_DIR:-target}
LOGS=$TARGET/ci-logs
mkdir -p "$LOGS"

# ---------------------------------------------------------------------------------------
# Steps and their times
# ---------------------------------------------------------------------------------------
STEP_NAMES=()
STEP_SECS=()
CUR=""
CUR_T0=0
T_START=$(date +%s.%N)

elapsed_since() { # seconds since $1 (date +%s.%N), one decimal
    awk -v a="$1" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }'
}

end_step() {
    if [ -n "$CUR" ]; then
        local s
        s=$(elapsed_since "$CUR_T0")
        STEP_NAMES+=("$CUR")
        STEP_SECS+=("$s")
        printf '<== %s: %s s\n' "$CUR" "$s"
        CUR=""
    fi
}

step() {
    end_step
    CUR="$1"
    CUR_T0=$(date +%s.%N)
    printf '\n==> %s\n' "$*"
}

slowest_tests() { # the slowest Rust tests, from nextest's JUnit file
    local junit=$TARGET/nextest/ci/junit.xml
    [ -f "$junit" ] || return 0
    python3 - "$junit" <<'EOF' || true
import sys
import xml.etree.ElementTree as ET
cases = []
for tc in ET.parse(sys.argv[1]).getroot().iter("testcase"):
    t = float(tc.get("time") or 0)
    cases.append((t, f"{tc.get('classname')} {tc.get('name')}"))
cases.sort(reverse=True)
total = sum(t for t, _ in cases)
print(f"\nslowest Rust tests ({len(cases)} tests, {total:.0f} s of test time in all):")
for t, name in cases[:15]:
    print(f"  {t:7.1f} s  {name}")
EOF
}

summary() {
    local rc=$1
    if [ -n "$CUR" ]; then
        [ "$rc" -ne 0 ] && CUR="$CUR (FAILED)"
        end_step
    fi
    printf '\n%-78s %8s\n' "step" "seconds"
    local i
    for i in "${!STEP_NAMES[@]}"; do
        printf '%-78.78s %8s\n' "${STEP_NAMES[$i]}" "${STEP_SECS[$i]}"
    done
    printf '%-78s %8s\n' "total" "$(elapsed_since "$T_START")"
    [ "$QUICK" -eq 1 ] || slowest_tests
}
trap 'summary $?' EXIT

# ---------------------------------------------------------------------------------------
# Network in the background (full tier): Chromium (Debian's package, for the report's
# browser test) and the Python packages (into .venv), while Rust compiles
# ---------------------------------------------------------------------------------------
PYTHON=${PYTHON:-python3}
VPY=.venv/bin/python
# maturin: builds the wheel; playwright: drives the system Chromium for the report test
# (no browser download); xarray, h5py: Result.to_xarray() and the HDF5 result files
# (python/tests/test_frames.py); matplotlib, tqdm: the .plot() helpers and sweep progress
# bars (test_plot.py, test_progress.py); nbclient, nbformat, ipykernel: the notebooks
# (scripts/run_notebooks.py); pytest-timeout: a hanging Python test fails with its name
# gmsh: the mesher's wheel, which regenerates an example mesh from its .geo (it loads
# libGLU and a few X libraries, installed with Chromium)
PY_DEPS=(maturin numpy pandas xarray h5py "dask[distributed]" pytest pytest-timeout
    playwright matplotlib tqdm nbclient nbformat ipykernel gmsh==4.15.2)
# Debian's packages: Chromium, and the libraries the gmsh wheel loads
DEB_LIBS=(libglu1-mesa libxcursor1 libxft2 libxinerama1)

install_chromium() {
    local have=1
    command -v chromium >/dev/null 2>&1 || have=0
    for lib in libGLU.so.1 libXcursor.so.1 libXft.so.2 libXinerama.so.1; do
        ldconfig -p | grep -q "$lib" || have=0
    done
    if [ "$have" -eq 1 ]; then
        echo "chromium and the gmsh libraries already installed: $(command -v chromium)"
        return 0
    fi
    local sudo=""
    [ "$(id -u)" -ne 0 ] && sudo=sudo
    $sudo apt-get update
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y chromium "${DEB_LIBS[@]}"
}

install_python() {
    if [ ! -x "$VPY" ] || ! "$VPY" -m pip --version >/dev/null 2>&1; then
        rm -rf .venv
        if ! "$PYTHON" -m venv .venv; then
            # python3-venv (ensurepip) missing: virtualenv, installed for the user if needed
            rm -rf .venv
            if ! "$PYTHON" -m virtualenv --version >/dev/null 2>&1; then
                "$PYTHON" -m pip install --user virtualenv ||
                    "$PYTHON" -m pip install --user --break-system-packages virtualenv
            fi
            "$PYTHON" -m virtualenv .venv
        fi
    fi
    "$VPY" -m pip install --upgrade pip
    "$VPY" -m pip install "${PY_DEPS[@]}"
}

wait_background() { # name pid log
    if ! wait "$2"; then
        echo "error: $1 failed; the end of $3:" >&2
        tail -n 40 "$3" >&2
        exit 1
    fi
    echo "$1: done ($3)"
}

if [ "$QUICK" -eq 0 ]; then
    step "start in the background: chromium (apt) and the Python packages (pip, .venv)"
    install_chromium >"$LOGS/chromium.log" 2>&1 &
    CHROMIUM_PID=$!
    install_python >"$LOGS/python.log" 2>&1 &
    PYTHON_PID=$!
    echo "logs: $LOGS/chromium.log, $LOGS/python.log"
fi

# ---------------------------------------------------------------------------------------
# Rust
# ---------------------------------------------------------------------------------------
if command -v rustup >/dev/null 2>&1; then
    step "rustup component add rustfmt clippy"
    rustup component add rustfmt clippy
fi

step "cargo fmt --all -- --check"
cargo fmt --all -- --check

step "cargo clippy --workspace --all-targets -- -D warnings"
cargo clippy --workspace --all-targets -- -D warnings

# The library without its optional parts (features plot, identify, reproduce, hdf5): the
# solvers alone must build, lint clean and pull in neither plotters nor argmin (hdf5-pure,
# pure Rust, stays: measured records are read from HDF5 and MAT v7.3 files). The library
# target is what the feature gating decides; its tests are built with every feature.
step "cargo clippy -p contactwave --no-default-features --lib -- -D warnings"
cargo clippy -p contactwave --no-default-features --lib -- -D warnings

step "cargo tree -p contactwave --no-default-features -e normal (no plotters, no argmin)"
if cargo tree -p contactwave --no-default-features -e normal | grep -E 'plotters|argmin'; then
    echo "error: contactwave without default features depends on plotters or argmin" >&2
    exit 1
fi

# One release build of the library for the tests, the CLI, the doc tests and the wheel:
# their dependency features must agree (crates/contactwave-py/Cargo.toml aligns them)
step "the same dependency features for the tests and the wheel (scripts/feature_sets.py)"
"$PYTHON" scripts/feature_sets.py

# cargo-nextest (on the CI machines; `cargo install cargo-nextest --locked` elsewhere);
# without it, cargo test runs the same tests (no per-test timeout, no timings table).
# The Python extension crate has no Rust tests (it needs libpython to link one).
RUST_TEST_ARGS=(--workspace --exclude contactwave-py --release)
if cargo nextest --version >/dev/null 2>&1; then
    if [ "$QUICK" -eq 1 ]; then
        step "cargo nextest run --workspace --release (quick tier: without the slow tests)"
        cargo nextest run "${RUST_TEST_ARGS[@]}"
    else
        step "cargo nextest run --workspace --release --profile ci --run-ignored all"
        cargo nextest run "${RUST_TEST_ARGS[@]}" --profile ci --run-ignored all
    fi
else
    echo "note: cargo-nextest not found: cargo test instead (no per-test timeout)"
    if [ "$QUICK" -eq 1 ]; then
        step "cargo test --workspace --release --tests (quick tier: without the slow tests)"
        cargo test "${RUST_TEST_ARGS[@]}" --tests
    else
        step "cargo test --workspace --release --tests -- --include-ignored"
        cargo test "${RUST_TEST_ARGS[@]}" --tests -- --include-ignored
    fi
fi

# The library's doc tests: edition 2024 compiles them into one binary. The same package
# selection as the tests, so the same features: the library the tests built serves.
step "cargo test --workspace --exclude contactwave-py --release --doc"
cargo test "${RUST_TEST_ARGS[@]}" --doc

if [ "$QUICK" -eq 1 ]; then
    step "quick tier passed (the full tier: ./scripts/test.sh)"
    exit 0
fi

# The CLI the reference check, the doc commands and the Python tests use: the test build
# made it (target/release/contactwave, for the CLI's integration tests). A separate
# `cargo build -p contactwave-cli` would resolve other dependency features (no
# dev-dependencies) and compile the library again.
if [ ! -x "$TARGET/release/contactwave" ]; then
    echo "error: $TARGET/release/contactwave was not built by the tests" >&2
    exit 1
fi

# Every output of the CLI (reproduce, run, sweep, merge, law, convergence, identify, fit,
# validate) against the values recorded in tests/reference/ (within 1e-9 relative); the
# outputs are kept in target/ci-out for the doc commands and the browser test, and the
# commands run are listed in target/ci-out.json. Re-record only for an intended change,
# with every changed value listed and explained: tests/reference/README.md
CI_OUT=$TARGET/ci-out
step "reference outputs of the CLI (scripts/reference_outputs.py check --keep $CI_OUT)"
"$PYTHON" scripts/reference_outputs.py check --keep "$CI_OUT" --ran "$CI_OUT.json"

# Every contactwave command of README.md and docs/*.md, in a fresh clone; those the
# reference check ran at this commit are not run again
step "commands of the docs (scripts/doc_commands.py --ran $CI_OUT.json)"
"$PYTHON" scripts/doc_commands.py --ran "$CI_OUT.json"

step "wait for the background installs (chromium, Python packages)"
wait_background "chromium" "$CHROMIUM_PID" "$LOGS/chromium.log"
wait_background "Python packages" "$PYTHON_PID" "$LOGS/python.log"
echo "chromium: $(command -v chromium)"
export CONTACTWAVE_REQUIRE_BROWSER=1

# maturin builds crates/contactwave-py with the release profile into the same target
# folder: the library and its dependencies are the ones the tests built (same features).
step "pip install . (maturin: the contactwave wheel, abi3, Python >= 3.9)"
rm -f python/contactwave/_core*.so # a stale `maturin develop` build would shadow the wheel
"$VPY" -m pip install --no-build-isolation --force-reinstall --no-deps . 2>&1 |
    tee "$LOGS/wheel.log"
"$VPY" -c "import contactwave, sys; print('contactwave', contactwave.__version__, 'on Python', sys.version.split()[0])"

# python/tests: API against the CLI's files, Dask LocalCluster, shards and merge, and the
# report.html of the reference check's `reproduce all --quick` in headless Chromium
# (screenshot kept at target/report-screenshot.png; test_plots_browser.py: a run's
# spectrum, a 22-curve sweep, frf.svg and shear_loop.svg as PNG under target/screenshots/)
step "python -m pytest python/tests (timeout 300 s a test)"
CONTACTWAVE_REPORT_DIR="$PWD/$CI_OUT/reproduce" \
    "$VPY" -m pytest -p no:cacheprovider -q --timeout 300 --durations 10 python/tests

# the mesh path from a .geo: the lap joint's mesh regenerated by the gmsh wheel
# (scripts/mesh.py), compared with the committed one, and its example run on it (shortened)
MESH_OUT=$TARGET/ci-mesh
step "a mesh regenerated from its .geo (scripts/mesh.py, gmsh) and run"
rm -rf "$MESH_OUT"
mkdir -p "$MESH_OUT"
"$VPY" scripts/mesh.py --out "$MESH_OUT" examples/solid_2d/mesh/lap_joint/joint.geo
if cmp -s "$MESH_OUT/joint.msh" examples/solid_2d/mesh/lap_joint/joint.msh; then
    echo "joint.msh regenerated: the same bytes as the committed file"
else
    echo "joint.msh regenerated: differs from the committed file (another gmsh build); running it"
fi
sed 's/^duration = .*/duration = 8e-6/' examples/solid_2d/mesh/lap_joint/lap_joint.toml >"$MESH_OUT/lap_joint.toml"
"$TARGET/release/contactwave" run "$MESH_OUT/lap_joint.toml" --out "$MESH_OUT/run" --overwrite

# examples/notebooks/*.ipynb executed with nbclient in a kernel of .venv's Python (any
# failing cell fails; the notebooks are stored without outputs)
step "notebooks (scripts/run_notebooks.py)"
"$VPY" scripts/run_notebooks.py

step "all tests passed"
