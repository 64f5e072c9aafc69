#!/usr/bin/env python3
"""Execute every notebook of examples/notebooks/ with nbclient; any failing cell fails.

    python scripts/run_notebooks.py [NOTEBOOK ...]

Run with the Python of the environment where `contactwave` is installed (CI: .venv, with
nbclient, nbformat, ipykernel, matplotlib and tqdm; scripts/test.sh). The kernel is that
same Python: a kernelspec naming `sys.executable` is installed into a temporary folder,
so a `python3` kernel registered elsewhere on the machine cannot run the notebooks with
another interpreter. Each notebook runs in its own folder (as Jupyter does; figures through
the kernel's inline backend, no display needed); the committed notebooks must carry no outputs (they are
stored clean: docs/python.md), and the executed copies are written to
target/notebooks/ for inspection. Exits 1 naming the notebook and the failing cell.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
KERNEL = "contactwave-notebooks"
#: Each cell's limit, s (the tutorial's slowest cell takes well under a minute).
CELL_TIMEOUT = 600


def main(argv: list[str]) -> int:
    try:
        import nbformat
        from ipykernel.kernelspec import install
        from nbclient import NotebookClient
        from nbclient.exceptions import CellExecutionError
    except ImportError as e:
        print(
            f"error: {e.name} is missing: pip install nbclient nbformat ipykernel matplotlib "
            "tqdm (or pip install \".[test]\")",
            file=sys.stderr,
        )
        return 2
    paths = [Path(p) for p in argv] or sorted((ROOT / "examples" / "notebooks").glob("*.ipynb"))
    if not paths:
        print("error: no notebook in examples/notebooks/", file=sys.stderr)
        return 2
    out_dir = ROOT / "target" / "notebooks"
    out_dir.mkdir(parents=True, exist_ok=True)
    failed = 0
    with tempfile.TemporaryDirectory() as prefix:
        # a kernelspec whose argv is this interpreter, found first on JUPYTER_PATH
        install(kernel_name=KERNEL, display_name="contactwave (CI)", prefix=prefix)
        os.environ["JUPYTER_PATH"] = os.pathsep.join(
            [str(Path(prefix) / "share" / "jupyter"), os.environ.get("JUPYTER_PATH", "")]
        )
        for path in paths:
            nb = nbformat.read(path, as_version=4)
            stored = [
                i for i, c in enumerate(nb.cells)
                if c.cell_type == "code" and (c.get("outputs") or c.get("execution_count"))
            ]
            if stored:
                print(
                    f"error: {path}: cells {stored} carry outputs; the notebooks are stored "
                    "without them (Jupyter: Edit > Clear outputs of all cells; or "
                    "`jupyter nbconvert --clear-output --inplace`)",
                    file=sys.stderr,
                )
                failed += 1
                continue
            client = NotebookClient(
                nb,
                kernel_name=KERNEL,
                timeout=CELL_TIMEOUT,
                resources={"metadata": {"path": str(path.resolve().parent)}},
            )
            start = time.perf_counter()
            try:
                client.execute()
            except CellExecutionError as e:
                print(f"error: {path}: a cell failed:\n{e}", file=sys.stderr)
                failed += 1
                continue
            finally:
                nbformat.write(nb, out_dir / path.name)
            print(f"{path}: {len(nb.cells)} cells ran in {time.perf_counter() - start:.1f} s "
                  f"(executed copy: {out_dir / path.name})")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
