#!/usr/bin/env bash
# The GPU benchmark in one command, for a session that is lent a real GPU for a few
# minutes: builds the `gpu_vs_cpu` bench, says which adapter wgpu picks, and prints
# node-steps/s for the fused and two-pass kernels in f32 and f64 (and the CPU path on
# all cores, for scale) from 1 to 100,000 cables of 51 nodes. Then a fleet of BUOYS
# moored free buoys (three lines of 21 nodes each; default 1000; BUOYS=0 skips it) on
# every path, beside the same lines with fixed fairleads, and what a free body costs
# per step in line nodes. Then the design-check
# study on both paths (scripts/study_gpu_speed.sh: 1 to 1000 members of STUDY_DURATION
# simulated seconds, f32 and f64, and the study's own 30 members compared with the CPU
# run; STUDY=0 skips it). Output goes to stdout and, when $OUT is set (the device tool's
# output folder), to $OUT/gpu_bench.md and $OUT/study/{times.md,compare.txt} too.
#
#   bash scripts/gpu_bench.sh                 # full table, a few minutes on a GPU
#   CABLES=1,100 BENCH_SECONDS=0.2 STUDY_MEMBERS="1 30" bash scripts/gpu_bench.sh   # a quick look
set -euo pipefail
cd "$(dirname "$0")/.."

CABLES=${CABLES:-1,10,100,1000,10000,100000}
SECONDS_PER=${BENCH_SECONDS:-0.5}
REPEATS=${REPEATS:-2}
PATHS=${PATHS:-gpu32,gpu64,gpu32tp,gpu64tp,cpu}
STUDY=${STUDY:-1}
BUOYS=${BUOYS:-1000}
STUDY_MEMBERS=${STUDY_MEMBERS:-1 10 100 1000}
STUDY_DURATION=${STUDY_DURATION:-2}
dest=${OUT:-}

echo "== machine"
nproc || true
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv 2>/dev/null || echo "no nvidia-smi"
command -v vulkaninfo >/dev/null && vulkaninfo --summary 2>/dev/null | grep -E 'deviceName|driverName|apiVersion' || true

echo "== build"
# Build first so that the timing runs are not disturbed by the compiler.
cargo bench --bench gpu_vs_cpu --no-run 2>&1 | tail -n 3
if [ "$STUDY" = 1 ]; then
  cargo build --release --bin cablesim 2>&1 | tail -n 1
fi

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

if [ "$BUOYS" != 0 ]; then
  echo "== $BUOYS moored free buoys (paths $PATHS)"
  buoys() {
    cargo bench --bench gpu_vs_cpu -- --buoys "$BUOYS" --paths "$PATHS" \
      --seconds "$SECONDS_PER" --repeats "$REPEATS"
  }
  if [ -n "$dest" ]; then
    buoys 2>&1 | tee "$dest/gpu_bench_buoys.md"
  else
    buoys
  fi
fi

if [ "$STUDY" = 1 ]; then
  echo "== design-check study (members of $STUDY_DURATION s: $STUDY_MEMBERS, and the study's 30)"
  sdir=${dest:-target}/study
  rm -rf "$sdir"
  MEMBERS="$STUDY_MEMBERS" FULL=1 DURATION="$STUDY_DURATION" TRANSIENT=0.5 \
    RUNS="cpu gpu:f32 gpu:f64" bash scripts/study_gpu_speed.sh "$sdir"
  if command -v python3 >/dev/null; then
    for p in f64 f32; do
      echo "== the 30 members, GPU $p against CPU"
      python3 scripts/compare_study_tables.py "$sdir/full30-cpu" "$sdir/full30-gpu-$p"
    done 2>&1 | tee "$sdir/compare.txt"
  fi
  # Only the timings and the comparison come back; the study folders are large.
  if [ -n "$dest" ]; then
    find "$sdir" -mindepth 1 -maxdepth 1 ! -name times.md ! -name compare.txt -exec rm -rf {} +
  fi
fi
