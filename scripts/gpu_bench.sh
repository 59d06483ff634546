#!/usr/bin/env bash
# The GPU benchmark in one command, for a session that is lent a real GPU for a few
# minutes: builds the `gpu_vs_cpu` bench, says which adapter wgpu picks, and prints
# node-steps/s for the fused and two-pass kernels in f32 and f64 (and the CPU path on
# all cores, for scale) from 1 to 100,000 cables of 51 nodes. Output goes to stdout and,
# when $OUT is set (the device tool's output folder), to $OUT/gpu_bench.md too.
#
#   bash scripts/gpu_bench.sh                 # full table, a few minutes on a GPU
#   CABLES=1,100 BENCH_SECONDS=0.2 bash scripts/gpu_bench.sh   # a quick look
set -euo pipefail
cd "$(dirname "$0")/.."

CABLES=${CABLES:-1,10,100,1000,10000,100000}
SECONDS_PER=${BENCH_SECONDS:-0.5}
REPEATS=${REPEATS:-2}
PATHS=${PATHS:-gpu32,gpu64,gpu32tp,gpu64tp,cpu}
dest=${OUT:-}

echo "== machine"
nproc || true
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv 2>/dev/null || echo "no nvidia-smi"
command -v vulkaninfo >/dev/null && vulkaninfo --summary 2>/dev/null | grep -E 'deviceName|driverName|apiVersion' || true

echo "== build"
# Build first so that the timing runs are not disturbed by the compiler.
cargo bench --bench gpu_vs_cpu --no-run 2>&1 | tail -n 3

echo "== run (cables $CABLES, paths $PATHS)"
run() {
  cargo bench --bench gpu_vs_cpu -- --cables "$CABLES" --paths "$PATHS" \
    --seconds "$SECONDS_PER" --repeats "$REPEATS"
}
if [ -n "$dest" ]; then
  mkdir -p "$dest"
  run 2>&1 | tee "$dest/gpu_bench.md"
else
  run
fi
