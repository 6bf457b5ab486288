#!/usr/bin/env bash
# Every row of the frame table in docs/benchmarks.md in one run: `bumpview render --frames N`
# per scene (each draws the frame and the adapter's floor alternately in one process, so the
# ratio is the number to read on a loaded machine) and one Markdown row per scene: frame, floor,
# ratio. Displacement on the CPU and on the GPU at a range of edge lengths (its frame time
# against pixels per edge). The last row is LEAN's frame against the renormalised box mips'
# frame (the ratio of the two rows' ratios, each to its own floor).
#
# Usage: scripts/frames.sh [FRAMES]        (default 30)
#   BUMPVIEW_BIN=path/to/bumpview          the binary (default: target/release/bumpview, built
#                                          with `cargo build --release --bin bumpview` when missing)
#   BUMPVIEW_TEST_ASSETS=dir               the third-party assets (default: ../shared/assets);
#                                          glTF models missing there print a "missing" row
# Runs on the Vulkan adapter wgpu picks (WGPU_BACKEND=vulkan for lavapipe).
set -euo pipefail
# Paths given in the environment are taken from where the script was started.
absolute() { [ -z "$1" ] || realpath -m "$1"; }
bin=$(absolute "${BUMPVIEW_BIN:-}")
assets=$(absolute "${BUMPVIEW_TEST_ASSETS:-}")
cd "$(dirname "$0")/.."
frames=${1:-30}
if [ -z "$bin" ]; then
    bin=${CARGO_TARGET_DIR:-target}/release/bumpview
    [ -x "$bin" ] || cargo build --release --bin bumpview
fi
assets=${assets:-../shared/assets}

declare -A ratio_of
# Times one scene: row NAME KEY [ARGS...]; prints a Markdown row, keeps the ratio under KEY.
row() {
    local name=$1 key=$2
    shift 2
    local line
    if ! line=$("$bin" render --frames "$frames" "$@" 2>/dev/null); then
        printf '| %s | failed: bumpview render --frames %s %s | | |\n' "$name" "$frames" "$*"
        return
    fi
    # line: frame <ms> ms, floor <ms> ms, ratio <r>
    read -r _ frame _ _ floor _ _ ratio <<<"${line//,/}"
    ratio_of[$key]=$ratio
    printf '| %s | %s ms | %s ms | %s |\n' "$name" "$frame" "$floor" "$ratio"
}

# Times a glTF model from the assets: model NAME FOLDER FILE.
model() {
    local path="$assets/gltf/$2/glTF/$3"
    if [ -f "$path" ]; then
        row "$1" "$2" "$path"
    else
        printf '| %s | missing: %s | | |\n' "$1" "$path"
    fi
}

echo "| scene | frame | floor | ratio |"
echo "|---|---|---|---|"
row "built-in, defaults (renormalised box mips)" box
row "built-in, \`--interactive\`" interactive --interactive
row "built-in, \`--mip-filter lean\`" lean --mip-filter lean
row "built-in, \`--parallax occlusion --parallax-depth 0.04 --parallax-layers 8,8\`" occlusion8 \
    --parallax occlusion --parallax-depth 0.04 --parallax-layers 8,8
row "built-in, \`--parallax occlusion --parallax-depth 0.04\` (layers 8–32 by the view angle)" occlusion \
    --parallax occlusion --parallax-depth 0.04
row "built-in, \`--displacement 5\` (CPU, 6.6 M triangles)" cpu5 --displacement 5
for px in 2 3 4 6 8 12; do
    row "built-in, \`--displacement gpu --pixels-per-edge $px\`" "gpu$px" --displacement gpu --pixels-per-edge "$px"
done
row "built-in, \`--displacement gpu --turning 0.5\` (tessellated every frame)" gputurning \
    --displacement gpu --turning 0.5
model "DamagedHelmet (glTF, PBR)" DamagedHelmet DamagedHelmet.gltf
model "StainedGlassLamp (glTF, PBR, many materials)" StainedGlassLamp StainedGlassLamp.gltf
model "WaterBottle (glTF, PBR)" WaterBottle WaterBottle.gltf
if [ -n "${ratio_of[lean]:-}" ] && [ -n "${ratio_of[box]:-}" ]; then
    awk -v lean="${ratio_of[lean]}" -v box="${ratio_of[box]}" \
        'BEGIN { printf "| LEAN against box mips (ratio of the two ratios) | | | %.2f |\n", lean / box }'
fi
