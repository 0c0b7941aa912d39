#!/usr/bin/env bash
# Builds the libFuzzer harnesses with clang (ASan + UBSan) and runs each for
# SECONDS (default 20). A finding fails the script and leaves the crashing
# input in build-fuzz/findings/. Nightly-length run: scripts/fuzz.sh 3600
# FUZZ_SEED (default 1) fixes libFuzzer's seed, so a short CI run explores
# the same inputs each time and does not fail at random; FUZZ_SEED=0 picks a
# new seed per run (nightly: explore further).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
seed=${FUZZ_SEED:-1}
build=${FUZZ_BUILD:-build-fuzz}
if [[ ! -f $build/build.ninja ]]; then
  CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DASBUILT_FUZZ=ON -DASBUILT_BUILD_TESTS=OFF -DASBUILT_BUILD_BENCH=OFF -DASBUILT_WITH_TORCH=OFF >/dev/null
fi
targets=$(cd fuzz && ls *_fuzz.cc | sed 's/_fuzz.cc$//')
cmake --build "$build" -j "$(nproc)" --target $(for t in $targets; do printf 'fuzz_%s ' "$t"; done)
mkdir -p "$build/findings"
status=0
for t in $targets; do
  work="$build/corpus/$t"
  mkdir -p "$work"
  echo "fuzz: $t for ${seconds}s" >&2
  if ! "$build/fuzz/fuzz_$t" -max_total_time="$seconds" -max_len=65536 -timeout=10 -seed="$seed" \
      -artifact_prefix="$build/findings/${t}-" -print_final_stats=1 \
      "$work" "fuzz/corpus/$t" > "$build/fuzz_$t.log" 2>&1; then
    echo "fuzz: $t FOUND A PROBLEM — see $build/fuzz_$t.log and $build/findings/" >&2
    tail -30 "$build/fuzz_$t.log" >&2
    status=1
  else
    grep -E 'stat::number_of_executed_units' "$build/fuzz_$t.log" | sed "s/^/fuzz: $t /" >&2 || true
  fi
done
exit $status
