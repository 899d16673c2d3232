#!/usr/bin/env bash
# Runs each libFuzzer target of a DERMIS_FUZZ build for SECONDS seconds (make fuzz).
#   fuzz/run.sh BUILD_DIR SECONDS [TARGET...]
# New inputs go to BUILD_DIR/fuzz-corpus/<target> (seeded from fuzz/corpus/<target> and
# fuzz/regressions/<target>; the tree is not written), crashes, leaks, timeouts and
# out-of-memory inputs to BUILD_DIR/fuzz-findings/<target>/, the log to
# BUILD_DIR/fuzz-findings/<target>.log. Prints executions and findings per target; exits 1
# when anything was found. A finding is fixed at its root and its input is copied into
# fuzz/regressions/<target>/, which the ctest entry fuzz_replay.<target> replays.
set -uo pipefail
build=${1:?usage: fuzz/run.sh BUILD_DIR SECONDS [TARGET...]}
seconds=${2:?usage: fuzz/run.sh BUILD_DIR SECONDS [TARGET...]}
shift 2
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(scene_parser ply_reader obj_assimp image_texture point_cloud)
src=$(cd "$(dirname "$0")" && pwd)

# Leaks inside OpenImageIO and Assimp are theirs, not findings (fuzz/lsan.supp).
export LSAN_OPTIONS="suppressions=$src/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"

total_findings=0
for t in "${targets[@]}"; do
  corpus="$build/fuzz-corpus/$t" findings="$build/fuzz-findings/$t"
  mkdir -p "$corpus" "$findings"
  dict=()
  [ -f "$src/$t.dict" ] && dict=(-dict="$src/$t.dict")
  # -timeout: an input slower than 10 s is a hang; -rss_limit_mb: 2 GB is unbounded memory;
  # -max_len: inputs up to 8 KB (the seeds are longer; their prefixes are fuzzed).
  "$build/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=8192 -print_final_stats=1 \
    -artifact_prefix="$findings/" "${dict[@]}" "$corpus" "$src/corpus/$t" "$src/regressions/$t" \
    >"$findings.log" 2>&1
  rc=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$findings.log" | grep -o '[0-9]*$' | tail -1)
  found=$(find "$findings" -type f | wc -l)
  total_findings=$((total_findings + found))
  echo "fuzz $t: ${runs:-?} executions in ${seconds} s, $found finding(s), exit $rc (log: $findings.log)"
done
[ "$total_findings" -eq 0 ]
