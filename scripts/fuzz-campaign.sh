#!/usr/bin/env bash
# A long fuzzing campaign, by hand: every proptest fuzz target (tests/fuzz.rs,
# tests/fuzz_accessors.rs, tests/fuzz_loaders.rs) with many more cases than CI runs, built
# with optimisations, one target at a time so a failure names its target.
#
# Usage: scripts/fuzz-campaign.sh [CASES] [TARGET...]
#   CASES   cases per proptest target (default 100000; CI runs 256)
#   TARGET  test files to run (default: fuzz fuzz_accessors fuzz_loaders)
# Environment: BUMPVIEW_FUZZ_SEED=N fixes proptest's RNG (PROPTEST_RNG_SEED) to replay a run.
#
# A failing input is shrunk by proptest and kept in tests/<target>.proptest-regressions,
# which CI replays first on every run: commit that file with the fix. Each target runs under
# a memory limit (ulimit -v, 8 GiB by default, BUMPVIEW_FUZZ_MEMORY_KIB to change it), so an
# input that allocates without bound fails as an allocation error instead of taking the
# machine. Prints each target's wall time and the cases it ran.
set -euo pipefail
cd "$(dirname "$0")/.."
cases=${1:-100000}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(fuzz fuzz_accessors fuzz_loaders)
memory=${BUMPVIEW_FUZZ_MEMORY_KIB:-8388608}
if [ -n "${BUMPVIEW_FUZZ_SEED:-}" ]; then
  export PROPTEST_RNG_SEED=$BUMPVIEW_FUZZ_SEED
fi
cargo build --release --no-default-features --tests --quiet
failed=0
for target in "${targets[@]}"; do
  started=$(date +%s)
  echo "== $target: $cases cases per property"
  if ! (ulimit -v "$memory"; BUMPVIEW_FUZZ_CASES=$cases cargo test --release --no-default-features --quiet \
    --test "$target"); then
    echo "== $target FAILED (shrunk input in tests/$target.proptest-regressions)"
    failed=$((failed + 1))
  fi
  echo "== $target: $(($(date +%s) - started)) s"
done
echo "== $((${#targets[@]} - failed)) passed, $failed failed"
[ "$failed" -eq 0 ]
