#!/usr/bin/env bash
# CPU time of every compiler run of a build, per unit (benchmarks/history/BENCHMARKS-2026-12.md, "Test build"):
#
#   UNIT_LOG=/tmp/units.log RUSTC_WRAPPER=$PWD/scripts/rustc_time.sh cargo test --release --no-run
#
# Cargo calls this with the compiler and its arguments; it runs them under
# /usr/bin/time and appends "crate kind user sys" (seconds) to $UNIT_LOG (kind: lib,
# bin, proc-macro, or test for a test harness). The linker runs inside rustc, so a
# binary's line includes its link. Build scripts' own runs are not rustc and are not
# in the log. Sum a log with: awk '{s += $3 + $4} END {print s}' /tmp/units.log
rustc="$1"
shift
name=-
kind=lib
prev=
for a in "$@"; do
  case "$prev" in
    --crate-name) name=$a ;;
    --crate-type) kind=$a ;;
  esac
  [ "$a" = --test ] && kind=test
  prev=$a
done
# Cargo's own queries (`rustc -vV`, `--print`) are not units.
if [ "$name" = - ] || [ "$name" = ___ ]; then exec "$rustc" "$@"; fi
t=$(mktemp)
/usr/bin/time -f "%U %S" -o "$t" "$rustc" "$@"
rc=$?
echo "$name $kind $(tail -n 1 "$t")" >> "${UNIT_LOG:-/tmp/units.log}"
rm -f "$t"
exit $rc
