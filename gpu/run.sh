#!/usr/bin/env bash
# The GPU prototype of the 2D bulk step (gpu/sem2d.cu): build with nvcc for the GPU at
# hand and run its check (GPU step against the CPU step) and throughput table. Needs an
# NVIDIA GPU and CUDA's nvcc; nothing in the Rust build, the tests or CI uses it.
#   gpu/run.sh [OUTDIR]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")"
out="${1:-/tmp}"
nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader || true
nvcc -O3 -arch=native -o "$out/sem2d" sem2d.cu
"$out/sem2d"
