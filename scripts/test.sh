#!/usr/bin/env bash
# The one command that runs every test of the workspace on a fresh machine:
#   ./scripts/test.sh
# Steps: formatting, lints (warnings are errors), the whole test suite in release mode (the
# physics tests are heavy), and the library's doc tests. Exits non-zero at the first
# failing step.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

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

step "cargo test --workspace --release"
cargo test --workspace --release

step "cargo test --doc -p contactwave --release"
cargo test --doc -p contactwave --release

# ---------------------------------------------------------------------------------------
# Python (reserved: later issues add the Python bindings and their tests here, e.g.
#   step "python3 -m pytest python/tests"
# No Python step yet.)
# ---------------------------------------------------------------------------------------

step "all tests passed"
