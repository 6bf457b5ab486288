#!/usr/bin/env bash
# Peak memory of `bumpview bake --to-height` against the need it states.
#
# For each side (default 4096 and 16384) it writes two normal maps — a flat 8-bit grey map
# (128 everywhere: the small-file, huge-image case) and an RGB 8-bit normal map baked by
# `bumpview bake` from a smooth height map — and integrates each with `--border wrap` and
# `--border clamp` under `/usr/bin/time -v`. Printed per run: the maximum resident set size
# (MiB and MiB per megatexel, 1 megatexel = 2^20 texels), the need `bake --to-height` states
# (the documented formula, see src/bake/to_height.rs) and the wall time.
#
# Usage: scripts/bake-memory.sh [SIDE...]
#   BUMPVIEW=path/to/bumpview  the binary (default: target/release/bumpview, built with
#                              `cargo build --release --no-default-features` when missing).
# Needs python3 (to write the inputs) and GNU time (`apt-get install -y time`).
set -euo pipefail
cd "$(dirname "$0")/.."
sides=("$@")
[ ${#sides[@]} -gt 0 ] || sides=(4096 16384)
bin=${BUMPVIEW:-target/release/bumpview}
if [ ! -x "$bin" ]; then
    cargo build --release --no-default-features --bin bumpview
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Writes an 8-bit grey PNG of side² texels: constant 128 (flat) or a smooth height map
# h = 64 + 63·sin(4 periods across)/2 + 63·sin(3 periods down)/2 (no wrap-around cliffs).
write_grey() {
    python3 - "$1" "$2" "$3" <<'EOF'
import math, struct, sys, zlib
path, side, kind = sys.argv[1], int(sys.argv[2]), sys.argv[3]
def chunk(tag, data):
    return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))
across = bytes(int(31.5 * (1 + math.sin(2 * math.pi * 4 * x / side))) for x in range(side))
compress = zlib.compressobj(1)
with open(path, "wb") as out:
    out.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", side, side, 8, 0, 0, 0, 0)))
    data = bytearray()
    for y in range(side):
        if kind == "flat":
            row = bytes([128]) * side
        else:
            down = int(31.5 * (1 + math.sin(2 * math.pi * 3 * y / side))) + 64
            row = across.translate(bytes((i + down) & 255 for i in range(256)))
        data += compress.compress(b"\x00" + row)
        if len(data) > 1 << 20:
            out.write(chunk(b"IDAT", bytes(data)))
            data = bytearray()
    data += compress.flush()
    out.write(chunk(b"IDAT", bytes(data)) + chunk(b"IEND", b""))
EOF
}

printf '%-28s %-6s %10s %10s %10s %8s\n' input border "RSS MiB" "MiB/Mtx" "need MiB" seconds
for side in "${sides[@]}"; do
    write_grey "$work/grey-$side.png" "$side" flat
    write_grey "$work/height-$side.png" "$side" bumps
    "$bin" bake "$work/height-$side.png" --out "$work/rgb-$side.png" >/dev/null
    rm "$work/height-$side.png"
    for input in grey rgb; do
        bytes_per_texel=$([ $input = grey ] && echo 1 || echo 3)
        file_bytes=$(stat -c %s "$work/$input-$side.png")
        for border in wrap clamp; do
            packed_per_texel=$([ $border = wrap ] && echo 8 || echo 16)
            column=$([ $border = wrap ] && echo "$side" || echo $((2 * side)))
            texels=$((side * side))
            packed=$((packed_per_texel * texels))
            reading=$((bytes_per_texel * texels + (file_bytes > packed ? file_bytes : packed)))
            solving=$((packed + 4 * 32 * column * 8))
            need=$(( (reading > solving ? reading : solving) ))
            /usr/bin/time -v "$bin" bake --to-height "$work/$input-$side.png" --out "$work/out.png" \
                --border "$border" --max-memory 100000 >/dev/null 2>"$work/time.txt" || {
                cat "$work/time.txt"
                exit 1
            }
            rss_kib=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$work/time.txt")
            wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {print $2}' "$work/time.txt")
            awk -v name="$input-$side.png" -v border="$border" -v kib="$rss_kib" -v need="$need" \
                -v texels="$texels" -v wall="$wall" 'BEGIN {
                    n = split(wall, t, ":"); seconds = 0; for (i = 1; i <= n; i++) seconds = seconds * 60 + t[i]
                    mib = kib / 1024; mtx = texels / 1048576
                    printf "%-28s %-6s %10.0f %10.2f %10.0f %8.1f\n", name, border, mib, mib / mtx, need / 1048576, seconds
                }'
        done
    done
    rm "$work"/*-"$side".png
done
