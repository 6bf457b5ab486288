#!/usr/bin/env bash
# Height map → tangent-space normal map, whole process, bumpview against NVIDIA Texture Tools:
# one 4096² 8-bit grey PNG (the shared Rock058 displacement tiled 4 × 4) baked by
#   bumpview bake IN --out OUT.png                       (central differences, wrapped, 8-bit RGB PNG)
#   nvcompress -tonormal -repeat -nomips -rgb IN OUT.dds (Debian's libnvtt-bin 2.0.8)
# alternately RUNS times (default 3) on the same input, then prints each tool's median wall
# time and peak resident memory (GNU time), the ratios, and bumpview's peak memory against the
# size of the output image (4096² × 3 bytes). The machine may be shared: only the ratios of one
# run compare.
#
# Installs what is missing (needs root and Debian's packages): libnvtt-bin (nvcompress), time
# (GNU time), imagemagick (to make the input). `cargo test` needs none of them.
# Usage: scripts/compare-nvcompress.sh   [env: RUNS, CARGO_TARGET_DIR, BUMPVIEW_TEST_ASSETS]
set -euo pipefail

runs=${RUNS:-3}
root=$(cd "$(dirname "$0")/.." && pwd)
assets=${BUMPVIEW_TEST_ASSETS:-$root/../shared/assets}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

install_missing() {
    local missing=()
    command -v nvcompress >/dev/null || missing+=(libnvtt-bin)
    [ -x /usr/bin/time ] || missing+=(time)
    # ImageMagick 6's own binary: a `convert` earlier on PATH may be something else.
    [ -x /usr/bin/convert-im6.q16 ] || missing+=(imagemagick)
    if [ ${#missing[@]} -gt 0 ]; then
        echo "installing ${missing[*]}" >&2
        apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null
    fi
}
install_missing

echo "building bumpview (release)" >&2
(cd "$root" && cargo build --release --no-default-features --quiet)
bumpview=${CARGO_TARGET_DIR:-$root/target}/release/bumpview

input=$work/height.png
displacement=$assets/textures/ambientCG_Rock058/displacement.jpg
[ -f "$displacement" ] || { echo "missing $displacement (set BUMPVIEW_TEST_ASSETS)" >&2; exit 1; }
/usr/bin/convert-im6.q16 -size 4096x4096 "tile:$displacement" -colorspace Gray -depth 8 \
    -define png:color-type=0 "$input"

# Runs a command under GNU time; appends "seconds kilobytes" to the file $1.
timed() {
    local log=$1
    shift
    /usr/bin/time -f "%e %M" -o "$work/time" "$@" >/dev/null 2>"$work/stderr" || {
        cat "$work/stderr" >&2
        exit 1
    }
    cat "$work/time" >>"$log"
}

for ((i = 0; i < runs; i++)); do
    timed "$work/bumpview.times" "$bumpview" bake "$input" --out "$work/normal.png" --force
    timed "$work/nvcompress.times" nvcompress -tonormal -repeat -nomips -rgb "$input" "$work/normal.dds"
done

median() { sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
ours_s=$(cut -d' ' -f1 "$work/bumpview.times" | median)
ours_kb=$(cut -d' ' -f2 "$work/bumpview.times" | median)
theirs_s=$(cut -d' ' -f1 "$work/nvcompress.times" | median)
theirs_kb=$(cut -d' ' -f2 "$work/nvcompress.times" | median)
output_kb=$((4096 * 4096 * 3 / 1024))

awk -v os="$ours_s" -v okb="$ours_kb" -v ob="$(stat -c %s "$work/normal.png")" \
    -v ts="$theirs_s" -v tkb="$theirs_kb" -v tb="$(stat -c %s "$work/normal.dds")" \
    -v out="$output_kb" -v runs="$runs" 'BEGIN {
    printf "%-12s %10s %12s %12s\n", "tool", "wall s", "peak MB", "output MB"
    printf "%-12s %10.3f %12.1f %12.1f\n", "bumpview", os, okb / 1024, ob / 1048576
    printf "%-12s %10.3f %12.1f %12.1f\n", "nvcompress", ts, tkb / 1024, tb / 1048576
    printf "speed: bumpview %.1fx faster (medians of %d runs each, alternating)\n", ts / os, runs
    printf "memory: bumpview peak %.2fx the output image (%d MB), nvcompress %.2fx\n", okb / out, out / 1024, tkb / out
}'
