"""Shared fixtures: the repository root, the CLI binary, a cheap base scenario."""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

#: A cheap scenario (3 cycles, 32 samples per period): a sweep point costs well under 1 ms.
CHEAP = {
    "medium": {"material": "pmma"},
    "interface": {"static_pressure": 0.1e6},
    "incident": {"frequency": 1e6, "cycles": 3, "xi": 0.35},
    "solver": {"samples_per_period": 32},
}

CHEAP_TOML = """
[medium]
material = "pmma"
[interface]
static_pressure = 0.1e6
[incident]
frequency = 1e6
cycles = 3
xi = 0.35
[solver]
samples_per_period = 32
"""


@pytest.fixture(scope="session")
def root() -> Path:
    return ROOT


@pytest.fixture(scope="session")
def cli() -> Path:
    """target/release/contactwave (built if missing; CONTACTWAVE_CLI overrides)."""
    exe = os.environ.get("CONTACTWAVE_CLI")
    if exe:
        return Path(exe)
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    exe = target / "release" / "contactwave"
    if not exe.exists():
        subprocess.run(
            ["cargo", "build", "--release", "-p", "contactwave-cli"], cwd=ROOT, check=True
        )
    return exe


def run_cli(cli: Path, *args, cwd=None) -> subprocess.CompletedProcess:
    p = subprocess.run(
        [str(cli), *map(str, args)], cwd=cwd or ROOT, capture_output=True, text=True
    )
    assert p.returncode == 0, p.stderr
    return p
