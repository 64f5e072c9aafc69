#!/usr/bin/env bash
# The GPU backend's check on a machine with an NVIDIA GPU (docs/performance.md section 2a):
# its tests against the CPU, the reference case on both backends, and the bench lines.
# Needs a `contactwave` binary and the library's test binary built with `--features gpu`
# (the release build of `cargo test -p contactwave --features gpu --lib --no-run`), in BIN.
#   gpu/check.sh BIN OUTDIR
set -uo pipefail
bin="$1"; out="$2"
cd "$(dirname "${BASH_SOURCE[0]}")/.."
nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader
lib=$(find /usr/local /opt /usr/lib -name 'libnvrtc.so*' 2>/dev/null | head -1)
[ -n "$lib" ] && export LD_LIBRARY_PATH="$(dirname "$lib"):${LD_LIBRARY_PATH:-}"
echo "NVRTC: $lib"
"$bin/tests" gpu_ --nocapture --test-threads 1 2>&1 | tee "$out/tests.log"
sed 's/^sides = "free"/sides = "free"\nbackend = "gpu"/' examples/solid_2d/plate_crack.toml > /tmp/gpu.toml
for b in gpu cpu; do
  f=/tmp/gpu.toml; [ $b = cpu ] && f=examples/solid_2d/plate_crack.toml
  s=$(date +%s%N)
  "$bin/contactwave" run "$f" --out "/tmp/out_$b" > "$out/run_$b.log" 2>&1; echo "run $b: exit $?"
  echo "run $b: $(( ($(date +%s%N) - s) / 1000000 )) ms wall"
  cp "/tmp/out_$b/summary.json" "$out/summary_$b.json"
done
python3 - <<'PY'
import csv, json
def table(b):
    with open(f"/tmp/out_{b}/receivers.csv") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    return rows[0], [[float(x) for x in r] for r in rows[1:]]
(hg, g), (hc, c) = table("gpu"), table("cpu")
assert hg == hc, (hg, hc)
for j, name in enumerate(hg[1:], 1):
    scale = max(abs(r[j]) for r in c)
    diff = max(abs(a[j] - b[j]) for a, b in zip(g, c))
    print(f"receivers.csv {name}: max |gpu - cpu| / max |cpu| = {diff / scale:.2e}")
sg, sc = (json.load(open(f"/tmp/out_{b}/summary.json")) for b in ("gpu", "cpu"))
def walk(a, b, path=""):
    if isinstance(a, dict):
        for k in a: walk(a[k], b.get(k), f"{path}.{k}")
    elif isinstance(a, (int, float)) and isinstance(b, (int, float)) and b:
        if abs(a - b) > 1e-6 * abs(b): print(f"summary{path}: gpu {a!r} cpu {b!r}")
walk(sg, sc)
print("summary compared")
PY
bench() { "$bin/contactwave" bench --runs 1 --points 2 --tribobrake-runs 0 "$@" 2>&1 | grep "2D solid"; }
for b in gpu cpu; do bench --solid-2d-us 20 --backend $b; done
# larger meshes of the same plate (element sizes 0.125 and 0.0625 mm: 4 and 16 times the nodes)
for h in 0.125e-3 0.0625e-3; do
  for b in gpu cpu; do bench --solid-2d-us 1 --solid-2d-element-size $h --backend $b; done
done
