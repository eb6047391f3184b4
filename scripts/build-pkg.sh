#!/usr/bin/env bash
# Builds the npm package in pkg/ from the crate: a release wasm32 build, wasm-bindgen for the
# `web` target (plain ES modules, the demo) and the `bundler` target (Vite, webpack), then
# wasm-opt -O3 on both. The committed pkg/package.json and pkg/README.md are kept as they are.
set -euo pipefail
cd "$(dirname "$0")/.."

wasm=target/wasm32-unknown-unknown/release/lanepf.wasm
cargo build --lib --release --target wasm32-unknown-unknown
# Features the Rust wasm32 target emits by default, and SIMD (128-bit), which .cargo/config.toml
# turns on for wasm32; wasm-opt must accept them all.
features=(--enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext
          --enable-mutable-globals --enable-reference-types --enable-multivalue --enable-simd)
for target in web bundler; do
  out=pkg/$target
  rm -rf "$out"
  wasm-bindgen --target "$target" --out-dir "$out" --out-name lanepf "$wasm"
  node_modules/.bin/wasm-opt -O3 "${features[@]}" "$out/lanepf_bg.wasm" -o "$out/lanepf_bg.wasm"
  rm -f "$out/.gitignore"
done
ls -l pkg/web/lanepf_bg.wasm | awk '{printf "[build-pkg] pkg/web/lanepf_bg.wasm: %d bytes\n", $5}'
