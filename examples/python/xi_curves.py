"""Thesis chapter 3: harmonic ratios A1/A_inc and A2/A_inc against the load ratio xi for
unilateral contact (examples/unilateral.toml) and for the RCCM adhesive interface
(examples/rccm_0.82MPa.toml with xi swept instead of the amplitude).

    python examples/python/xi_curves.py                 # writes xi_curves.png
    python examples/python/xi_curves.py --points 47 --out results/xi_curves.png
    python examples/python/xi_curves.py --dask          # same curves on a Dask LocalCluster

matplotlib is imported only to plot; without it the curves are printed as a table.
"""

import argparse
import time
from pathlib import Path

import numpy as np

import contactwave as cw

EXAMPLES = Path(__file__).resolve().parents[1]

CASES = {
    "unilateral": EXAMPLES / "unilateral.toml",
    "RCCM (C_N = 2e13 Pa/m, w = 0.1 J/m^2)": EXAMPLES / "rccm_0.82MPa.toml",
}


def curves(points: int, executor=None):
    xi = np.linspace(0.05, 1.2, points)
    out = {}
    for label, base in CASES.items():
        t0 = time.perf_counter()
        res = cw.sweep(base, {"incident.xi": xi}, executor=executor, as_frame=False)
        print(f"{label}: {points} points in {time.perf_counter() - t0:.2f} s")
        out[label] = res
    return xi, out


def plot(xi, results, path: Path) -> bool:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return False
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharex=True)
    for label, r in results.items():
        axes[0].plot(xi, r["A1_over_Ainc"], ".-", label=label)
        axes[1].plot(xi, r["A2_over_Ainc"], ".-", label=label)
    axes[0].set_ylabel("A1 / A_inc")
    axes[1].set_ylabel("A2 / A_inc")
    for ax in axes:
        ax.set_xlabel("load ratio xi")
        ax.grid(alpha=0.3)
    axes[1].legend(fontsize="small")
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=150)
    return True


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=47, help="load ratios in [0.05, 1.2]")
    ap.add_argument("--out", type=Path, default=Path("xi_curves.png"), help="PNG to write")
    ap.add_argument("--dask", action="store_true", help="run on a 2-worker Dask LocalCluster")
    args = ap.parse_args()
    if args.dask:
        from dask.distributed import Client, LocalCluster

        with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as c:
            xi, results = curves(args.points, executor=c)
    else:
        xi, results = curves(args.points)
    for label, r in results.items():
        k = int(np.nanargmax(r["A2_over_Ainc"]))
        print(f"{label}: max A2/A_inc = {r['A2_over_Ainc'][k]:.4f} at xi = {xi[k]:.3f}")
    if plot(xi, results, args.out):
        print(f"wrote {args.out}")
    else:
        print("matplotlib is not installed: no plot (pip install matplotlib)")
        print("xi        " + "  ".join(f"{lab[:12]:>12} A1 {lab[:12]:>12} A2" for lab in results))
        for i, x in enumerate(xi):
            row = "  ".join(
                f"{r['A1_over_Ainc'][i]:15.6f} {r['A2_over_Ainc'][i]:15.6f}" for r in results.values()
            )
            print(f"{x:8.4f}  {row}")


if __name__ == "__main__":
    main()
