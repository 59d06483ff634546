#!/usr/bin/env bash
# The design-check study (examples/study_design_check.toml: 8 chains x 41 nodes per
# member, a 200-component JONSWAP sea, RAO-driven platform) on the GPU path and on the
# CPU path, short: wall and CPU time (user + sys of the `cablesim` process, with every
# thread it starts, lavapipe's included; bash's `time`) against the number of members.
# benchmarks/history/BENCHMARKS-2026-12.md, "The design-check study on the GPU path", holds the figures and how
# they were taken.
#
#   bash scripts/study_gpu_speed.sh OUTDIR
#
# Environment (defaults in brackets):
#   MEMBERS    member counts, seeds 1..N of the `design` sea state (may be empty)  [1 10 100]
#   FULL       also the study's own members (its 3 sea states x FULL_SEEDS seeds), 1 = yes  [1]
#   FULL_SEEDS seeds per sea state of that run (10: the study's 30 members)  [10]
#   DURATION   simulated seconds per member                            [2]
#   TRANSIENT  discarded seconds per member (below DURATION)           [0.5]
#   RUNS       what to run: cpu, gpu:f32, gpu:f64                     [cpu gpu:f32 gpu:f64]
#   BIN        the cablesim binary                                     [target/release/cablesim]
# Writes OUTDIR/<run>/ (the study's tables) and appends one row per run to
# OUTDIR/times.md (also printed): members, simulated s, backend, wall s, user s, sys s,
# member-seconds per CPU second, the 1-minute load average before and after.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
out=${1:?usage: study_gpu_speed.sh OUTDIR}
mkdir -p "$out"
out=$(cd "$out" && pwd)
MEMBERS=${MEMBERS-1 10 100}
FULL=${FULL:-1}
FULL_SEEDS=${FULL_SEEDS:-10}
DURATION=${DURATION:-2}
TRANSIENT=${TRANSIENT:-0.5}
RUNS=${RUNS:-cpu gpu:f32 gpu:f64}
BIN=${BIN:-target/release/cablesim}
[ -x "$BIN" ] || { echo "no cablesim binary at $BIN (cargo build --release)" >&2; exit 1; }

# A study file naming the design check: `seeds` seeds of the given sea states.
study_file() { # file seeds sea_states_block
  cat >"$1" <<EOF
# written by scripts/study_gpu_speed.sh
[study]
scenario = "$root/examples/study_design_check.toml"
seed = 320
seeds = $2
duration = $DURATION
transient = $TRANSIENT
sea_states = [
$3
]
channels = ["default"]
EOF
}
design='  { name = "design", hs = 9.0, tp = 13.0, gamma = 2.5, heading = 210.0, current_speed = 0.9, current_heading = 200.0 },'
all3='  { name = "operating", hs = 4.0, tp = 9.0, heading = 180.0, current_speed = 0.5, current_heading = 180.0 },
  { name = "design", hs = 9.0, tp = 13.0, gamma = 2.5, heading = 210.0, current_speed = 0.9, current_heading = 200.0 },
  { name = "survival", hs = 13.0, tp = 15.5, gamma = 3.3, heading = 180.0, current_speed = 1.1, current_heading = 180.0 },'

cases=()
for n in $MEMBERS; do
  study_file "$out/design$n.toml" "$n" "$design"
  cases+=("design$n:$n")
done
if [ "$FULL" = 1 ]; then
  study_file "$out/full$((3 * FULL_SEEDS)).toml" "$FULL_SEEDS" "$all3"
  cases+=("full$((3 * FULL_SEEDS)):$((3 * FULL_SEEDS))")
fi

times="$out/times.md"
[ -f "$times" ] || {
  echo "| study | members | simulated s each | backend | wall s | user s | sys s | member-s per CPU s | CPU s per member-s | load before | load after |"
  echo "|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|"
} >"$times"
for c in "${cases[@]}"; do
  name=${c%%:*}
  n=${c##*:}
  for r in $RUNS; do
    backend=${r%%:*}
    args=(--backend "$backend")
    tag=$backend
    if [ "$backend" = gpu ]; then
      prec=${r##*:}
      args+=(--precision "$prec")
      tag=gpu-$prec
    fi
    d="$out/$name-$tag"
    rm -rf "$d"
    la0=$(cut -d' ' -f1 /proc/loadavg)
    TIMEFORMAT='%R %U %S'
    { time "$BIN" study run "$out/$name.toml" --out "$d" -q "${args[@]}" >"$d.log" 2>&1; } \
      2>"$out/time.txt" ||
      { echo "failed: $name $tag (see $d.log)" >&2; tail -n 5 "$d.log" >&2; exit 1; }
    la1=$(cut -d' ' -f1 /proc/loadavg)
    read -r wall user sys <"$out/time.txt"
    row=$(awk -v n="$n" -v dur="$DURATION" -v w="$wall" -v u="$user" -v s="$sys" \
      -v name="$name" -v tag="$tag" -v a="$la0" -v b="$la1" 'BEGIN {
        cpu = u + s; ms = n * dur;
        printf "| %s | %d | %g | %s | %.2f | %.2f | %.2f | %.1f | %.4f | %s | %s |",
          name, n, dur, tag, w, u, s, ms / cpu, cpu / ms, a, b }')
    echo "$row" | tee -a "$times"
  done
done
