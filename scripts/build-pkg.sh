#!/usr/bin/env bash
# Builds the npm package in pkg/ from the crate: a release wasm32 build, wasm-bindgen for the
# `web` target (plain ES modules, the demo) into pkg/web/, then wasm-opt -O3. That is the only
# generated part: the other entries (pkg/bundler/, pkg/worker/, pkg/frames/), package.json and
# README.md are committed sources that import ../web/, so the tarball has one wasm file.
set -euo pipefail
cd "$(dirname "$0")/.."

wasm=target/wasm32-unknown-unknown/release/lanepf.wasm
cargo build --lib --release --target wasm32-unknown-unknown
# Features the Rust wasm32 target emits by default, and SIMD (128-bit), which .cargo/config.toml
# turns on for wasm32; wasm-opt must accept them all.
features=(--enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext
          --enable-mutable-globals --enable-reference-types --enable-multivalue --enable-simd)
out=pkg/web
rm -rf "$out"
wasm-bindgen --target web --out-dir "$out" --out-name lanepf "$wasm"
# The Tracker class takes its id as a type parameter, so that `new Tracker('lee-cpf', config)`
# checks config against lee-cpf's options (TrackerConfig<Id>, src/wasm/types/generated.d.ts):
# wasm-bindgen declares no generic classes, so the one line is added here, and the build fails if
# wasm-bindgen's declaration ever changes shape.
dts="$out/lanepf.d.ts"
if [ "$(grep -c '^export class Tracker {$' "$dts")" != 1 ]; then
  echo "[build-pkg] $dts: no single 'export class Tracker {' line to make generic" >&2
  exit 1
fi
sed -i 's/^export class Tracker {$/export class Tracker<Id extends TrackerId = TrackerId> {/' "$dts"
# The producers and target_features custom sections are for tools, not for the browser.
node_modules/.bin/wasm-opt -O3 --strip-producers --strip-target-features "${features[@]}" \
  "$out/lanepf_bg.wasm" -o "$out/lanepf_bg.wasm"
rm -f "$out/.gitignore"
# What builds before the committed bundler entry generated the `bundler` target there.
rm -f pkg/bundler/lanepf.js pkg/bundler/lanepf.d.ts pkg/bundler/lanepf_bg.js pkg/bundler/lanepf_bg.wasm \
      pkg/bundler/lanepf_bg.wasm.d.ts
ls -l pkg/web/lanepf_bg.wasm | awk '{printf "[build-pkg] pkg/web/lanepf_bg.wasm: %d bytes\n", $5}'
