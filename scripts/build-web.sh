#!/usr/bin/env bash
# Builds the web version of the viewer into web/dist/ (docs/web.md): the release build for
# wasm32-unknown-unknown, then wasm-bindgen (from crates.io, the exact version in Cargo.lock,
# installed once into target/web-tools) and the page. Any static server can host web/dist/.
# Prints the wasm's size, raw and gzip.
set -euo pipefail
cd "$(dirname "$0")/.."

if command -v rustup >/dev/null && ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
  rustup target add wasm32-unknown-unknown
fi

# The wasm-bindgen CLI must be the version of the wasm-bindgen crate the build links.
version=$(awk '$0 == "name = \"wasm-bindgen\"" { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock)
tools=target/web-tools
# Without TLS (default features off): the CLI's test runner downloads, the bindgen does not.
# Its own lock file first; where the registry lacks a version it locks, the newest compatible.
if ! "$tools/bin/wasm-bindgen" --version 2>/dev/null | grep -qx "wasm-bindgen $version"; then
  install=(cargo install wasm-bindgen-cli --version "$version" --no-default-features --root "$tools")
  "${install[@]}" --locked || "${install[@]}"
fi

cargo build --release --target wasm32-unknown-unknown --bin bumpview
rm -rf web/dist
"$tools/bin/wasm-bindgen" --target web --no-typescript --out-dir web/dist \
  target/wasm32-unknown-unknown/release/bumpview.wasm
cp web/index.html web/dist/index.html

wasm=web/dist/bumpview_bg.wasm
raw=$(stat -c %s "$wasm")
gz=$(gzip -9 -c "$wasm" | wc -c)
echo "web/dist/: bumpview_bg.wasm $raw bytes ($(( raw / 1024 / 1024 )) MiB), gzip -9 $gz bytes ($(( gz / 1024 / 1024 )) MiB)"
