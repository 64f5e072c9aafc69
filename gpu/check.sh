#!/usr/bin/env bash
# The GPU backend's check on a machine with an NVIDIA GPU (docs/performance.md section 2a):
# its tests against the CPU, the 2D examples it runs on both backends (receivers and
# summaries compared), and the bench lines. Needs a `contactwave` binary and the library's
# test binary built with `--features gpu` (the release build of `cargo test -p contactwave
# --features gpu --lib --no-run`), in BIN.
#   gpu/check.sh BIN OUTDIR          (QUICK=1: the tests and the examples, no bench lines)
set -uo pipefail
bin="$1"; out="$2"
cd "$(dirname "${BASH_SOURCE[0]}")/.."
nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader
lib=$(find /usr/local /opt /usr/lib -name 'libnvrtc.so*' 2>/dev/null | head -1)
[ -n "$lib" ] && export LD_LIBRARY_PATH="$(dirname "$lib"):${LD_LIBRARY_PATH:-}"
echo "NVRTC: $lib"
"$bin/tests" gpu_ --nocapture --test-threads 1 2>&1 | tee "$out/tests.log"
for name in plate_crack lamb_delamination sh_friction interface_reduction; do
  sed '/^\[model\]/a backend = "gpu"' "examples/solid_2d/$name.toml" > "/tmp/${name}_gpu.toml"
  for b in gpu cpu; do
    f="/tmp/${name}_gpu.toml"; [ $b = cpu ] && f="examples/solid_2d/$name.toml"
    s=$(date +%s%N)
    "$bin/contactwave" run "$f" --out "/tmp/out_${name}_$b" > "$out/run_${name}_$b.log" 2>&1
    echo "$name $b: exit $?, $(( ($(date +%s%N) - s) / 1000000 )) ms wall"
  done
  cp "/tmp/out_${name}_gpu/summary.json" "$out/summary_${name}_gpu.json"
  python3 - "$name" <<'PY'
import csv, json, sys
name = sys.argv[1]
def table(b):
    with open(f"/tmp/out_{name}_{b}/receivers.csv") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    return rows[0], [[float(x) for x in r] for r in rows[1:]]
(hg, g), (hc, c) = table("gpu"), table("cpu")
assert hg == hc, (hg, hc)
worst = 0.0
for j in range(1, len(hg)):
    scale = max(abs(r[j]) for r in c) or 1.0
    worst = max(worst, max(abs(a[j] - b[j]) for a, b in zip(g, c)) / scale)
print(f"{name}: receivers.csv max |gpu - cpu| / max |cpu| over {len(hg) - 1} traces = {worst:.2e}")
sg, sc = (json.load(open(f"/tmp/out_{name}_{b}/summary.json")) for b in ("gpu", "cpu"))
for k in ("energy_input", "energy_solid", "energy_absorbed", "energy_cracks", "energy_closure_error"):
    if k in sc: print(f"  {k}: gpu {sg[k]:.6e} cpu {sc[k]:.6e}")
for k, v in sc.items():
    if isinstance(v, float) and k.endswith(("_A2_over_A1", "A2_over_A1")):
        print(f"  {k}: gpu {sg[k]:.6e} cpu {v:.6e}")
PY
done
[ -n "${QUICK:-}" ] && exit 0
bench() { "$bin/contactwave" bench --runs 1 --points 2 --tribobrake-runs 0 "$@" 2>&1 | grep "2D solid"; }
for b in gpu cpu; do bench --solid-2d-us 20 --backend $b; done
# larger meshes of the same plate (element sizes 0.125 and 0.0625 mm: 4 and 16 times the nodes)
for h in 0.125e-3 0.0625e-3; do
  for b in gpu cpu; do bench --solid-2d-us 1 --solid-2d-element-size $h --backend $b; done
done
# the numpy baseline on this machine's CPU (copied next to the binaries)
[ -f "$bin/elastic2d_numpy.py" ] && python3 "$bin/elastic2d_numpy.py" 1 2>&1 | tail -1
