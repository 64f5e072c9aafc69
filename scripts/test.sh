#!/usr/bin/env bash
# The one command that runs every test of the workspace on a fresh machine (what CI runs):
#   ./scripts/test.sh
# Steps: formatting, lints (warnings are errors; also for the library without its default
# features, which must not depend on plotters or argmin), the whole test suite in release
# mode (the physics tests are heavy; doc tests of the library included, run once), the
# tests marked slow (`#[ignore = "slow: full tier"]`), every output of the release CLI
# against tests/reference/ (values within 1e-9), and the Python package's tests. Exits
# non-zero at the first failing step.
#
# The quick tier, for the edit loop:
#   ./scripts/test.sh --quick
# formatting, both lints, the dependency check, and `cargo test --workspace --release`
# (unit, integration, physics, property and doc tests, the determinism test) without the
# tests marked slow; no reference outputs, no Python, no browser. About 1 minute on 2 cores
# once built (56 s measured; 2.4 min when a test file was edited): README.md.
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

step() {
    printf '\n==> %s\n' "$*"
}

# ---------------------------------------------------------------------------------------
# Toolchain components
# ---------------------------------------------------------------------------------------
if command -v rustup >/dev/null 2>&1; then
    step "rustup component add rustfmt clippy"
    rustup component add rustfmt clippy
fi

# ---------------------------------------------------------------------------------------
# Rust
# ---------------------------------------------------------------------------------------
step "cargo fmt --all -- --check"
cargo fmt --all -- --check

step "cargo clippy --all-targets -- -D warnings"
cargo clippy --all-targets -- -D warnings

# The library without its optional parts (features plot, identify, reproduce, hdf5): the
# solvers alone must build, lint clean and pull in neither plotters nor argmin (hdf5-pure,
# pure Rust, stays: measured records are read from HDF5 and MAT v7.3 files).
step "cargo clippy -p contactwave --no-default-features --all-targets -- -D warnings"
cargo clippy -p contactwave --no-default-features --all-targets -- -D warnings

step "cargo tree -p contactwave --no-default-features -e normal (no plotters, no argmin)"
if cargo tree -p contactwave --no-default-features -e normal | grep -E 'plotters|argmin'; then
    echo "error: contactwave without default features depends on plotters or argmin" >&2
    exit 1
fi

# Unit, integration, physics, property and doc tests (the library's doc tests run here,
# once); the tests marked `#[ignore = "slow: full tier"]` (more than about 20 s each on
# 2 cores: the identifications) only in the full tier.
if [ "$QUICK" -eq 1 ]; then
    step "cargo test --workspace --release (quick tier: without the slow tests)"
    cargo test --workspace --release
    step "quick tier passed (the full tier: ./scripts/test.sh)"
    exit 0
fi

step "cargo test --workspace --release -- --include-ignored (with the slow tests)"
cargo test --workspace --release -- --include-ignored

# ---------------------------------------------------------------------------------------
# Python: the `contactwave` package (crates/contactwave-py + python/), built with maturin
# into a virtual environment at .venv (ignored by git), then its pytest suite
# (python/tests: API against the CLI's files, Dask LocalCluster, shards and merge, and
# report.html of `contactwave reproduce all` in headless Chromium: screenshot of the first
# screen kept at target/report-screenshot.png; test_plots_browser.py: a run's spectrum, a
# 22-curve sweep, frf.svg and shear_loop.svg as PNG under target/screenshots/), then the
# notebooks of examples/notebooks/ (scripts/run_notebooks.py).
# ---------------------------------------------------------------------------------------
PYTHON=${PYTHON:-python3}
# playwright: drives the system Chromium for the report test (no browser download)
# xarray, h5py: Result.to_xarray() and the HDF5 result files (python/tests/test_frames.py)
# matplotlib, tqdm: the .plot() helpers and sweep progress bars (test_plot.py,
# test_progress.py); nbclient, nbformat, ipykernel: the notebooks (scripts/run_notebooks.py)
PY_DEPS=(maturin numpy pandas xarray h5py "dask[distributed]" pytest playwright
    matplotlib tqdm nbclient nbformat ipykernel)

# Headless Chromium for python/tests/test_report_browser.py (report.html renders, no
# console error, no request leaves the file); Debian's package, installed if missing.
step "chromium (Debian package) for the report browser test"
if ! command -v chromium >/dev/null 2>&1; then
    SUDO=""
    if [ "$(id -u)" -ne 0 ]; then
        SUDO=sudo
    fi
    $SUDO apt-get update
    $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y chromium
fi
echo "chromium: $(command -v chromium)"
export CONTACTWAVE_REQUIRE_BROWSER=1

step "python virtual environment (.venv)"
if [ ! -x .venv/bin/python ] || ! .venv/bin/python -m pip --version >/dev/null 2>&1; then
    rm -rf .venv
    if ! "$PYTHON" -m venv .venv; then
        # python3-venv (ensurepip) missing: try virtualenv, installed for the user if needed
        rm -rf .venv
        if ! "$PYTHON" -m virtualenv --version >/dev/null 2>&1; then
            "$PYTHON" -m pip install --user virtualenv ||
                "$PYTHON" -m pip install --user --break-system-packages virtualenv
        fi
        "$PYTHON" -m virtualenv .venv
    fi
fi
VPY=.venv/bin/python

step "pip install ${PY_DEPS[*]}"
"$VPY" -m pip install --upgrade pip
"$VPY" -m pip install "${PY_DEPS[@]}"

step "cargo build --release -p contactwave-cli (the CLI the Python tests compare with)"
cargo build --release -p contactwave-cli

# Every output of the CLI (reproduce, run, sweep, merge, law, convergence, identify, fit,
# validate) against the values recorded in tests/reference/ (within 1e-9 relative; about
# three minutes on 2 cores); re-record only for an intended change, with every changed
# value listed and explained: tests/reference/README.md
step "reference outputs of the CLI (scripts/reference_outputs.py check)"
"$VPY" scripts/reference_outputs.py check

# Every contactwave command of README.md and docs/*.md, in a fresh clone (3 to 5 minutes)
step "commands of the docs (scripts/doc_commands.py)"
"$VPY" scripts/doc_commands.py

step "pip install . (maturin: the contactwave wheel, abi3, Python >= 3.9)"
rm -f python/contactwave/_core*.so  # a stale `maturin develop` build would shadow the wheel
"$VPY" -m pip install --no-build-isolation --force-reinstall --no-deps .
"$VPY" -c "import contactwave, sys; print('contactwave', contactwave.__version__, 'on Python', sys.version.split()[0])"

step "python -m pytest python/tests"
"$VPY" -m pytest -p no:cacheprovider -q python/tests

# examples/notebooks/*.ipynb executed with nbclient in a kernel of .venv's Python (any
# failing cell fails; the notebooks are stored without outputs; about 10 s)
step "notebooks (scripts/run_notebooks.py)"
"$VPY" scripts/run_notebooks.py

step "all tests passed"
