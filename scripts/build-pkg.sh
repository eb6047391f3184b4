#!/usr/bin/env bash
# Builds the npm package in pkg/ from the crate: two release wasm32 builds of the one crate, each
# through wasm-bindgen for the `web` target (plain ES modules) and wasm-opt -O3:
#   pkg/web/  the main module (`lanepf`): Camera, Tracker, Calibrator (feature `wasm-track`);
#   pkg/sim/  the simulator's module (`lanepf/sim`): Scene, TestRoad, scenarios() (`wasm-sim`),
#             loaded separately so that a page that only tracks does not carry the simulator.
# Those are the only generated parts: the other entries (pkg/bundler/, pkg/worker/,
# pkg/frames/), package.json and README.md are committed sources that import ../web/.
set -euo pipefail
cd "$(dirname "$0")/.."

wasm=target/wasm32-unknown-unknown/release/lanepf.wasm
# Features the Rust wasm32 target emits by default, and SIMD (128-bit), which .cargo/config.toml
# turns on for wasm32; wasm-opt must accept them all.
features=(--enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext
          --enable-mutable-globals --enable-reference-types --enable-multivalue --enable-simd)

# build FEATURE OUT NAME: one module, from the crate built with only FEATURE of the binding.
build() {
  local feature=$1 out=$2 name=$3
  cargo build --lib --release --target wasm32-unknown-unknown --no-default-features --features "$feature"
  rm -rf "$out"
  wasm-bindgen --target web --out-dir "$out" --out-name "$name" "$wasm"
  # Core's float formatting (core::num::flt2dec, 24 kB raw, 10 kB gzip -9 of the main module)
  # stays out of both modules: numbers in messages are written by lanepf::num_text. The function
  # names are still in the module here (wasm-opt drops them below).
  if grep -aq 'flt2dec' "$out/${name}_bg.wasm"; then
    echo "[build-pkg] $out: core's float formatting is linked in: an f64 or f32 reaches a message" \
      "through {}, {:?}, {:e} or {:.N} (write it with lanepf::num_text::{Num, Fixed, Exp}), or" \
      "f64::clamp has bounds that are not constants (use lanepf::math::clamp)" >&2
    exit 1
  fi
  # The producers and target_features custom sections are for tools, not for the browser.
  # Functions in the order of their names (after -O3; it moves code, changes none): a module's
  # functions side by side compress better, -2.6 kB gzip -9 of the main module. --converge
  # repeats -O3's passes until the module stops shrinking: -0.6 kB gzip -9 more; and
  # --merge-similar-functions makes one function of those that differ only in constants:
  # -0.9 kB (2026-11-28; the same speed in Chromium, RESULTS.md, *Package*).
  node_modules/.bin/wasm-opt -O3 --merge-similar-functions --converge --reorder-functions-by-name --strip-producers --strip-target-features "${features[@]}" \
    "$out/${name}_bg.wasm" -o "$out/${name}_bg.wasm"
  rm -f "$out/.gitignore"
  ls -l "$out/${name}_bg.wasm" | awk '{printf "[build-pkg] %s: %d bytes\n", $9, $5}'
}

build wasm-sim pkg/sim lanepf_sim
if grep -q 'class Tracker\b' pkg/sim/lanepf_sim.d.ts; then
  echo "[build-pkg] pkg/sim/lanepf_sim.d.ts declares Tracker: the simulator's module must not" >&2
  exit 1
fi
build wasm-track pkg/web lanepf
if grep -Eq 'class (Scene|TestRoad)\b' pkg/web/lanepf.d.ts; then
  echo "[build-pkg] pkg/web/lanepf.d.ts declares the simulator: it belongs in pkg/sim" >&2
  exit 1
fi
# Issue 21's budget: the main module (the one a page that tracks loads) at most 250 kB gzip -9
# (RESULTS.md, *Package*, has what each change cost and how the last overrun was won back).
zipped=$(gzip -9 -c pkg/web/lanepf_bg.wasm | wc -c)
if [ "$zipped" -gt 250000 ]; then
  echo "[build-pkg] pkg/web/lanepf_bg.wasm is $zipped bytes gzip -9, over the 250 000 budget" >&2
  exit 1
fi
echo "[build-pkg] pkg/web/lanepf_bg.wasm: $zipped bytes gzip -9 (budget 250 000)"
out=pkg/web
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
# What builds before the committed bundler entry generated the `bundler` target there.
rm -f pkg/bundler/lanepf.js pkg/bundler/lanepf.d.ts pkg/bundler/lanepf_bg.js pkg/bundler/lanepf_bg.wasm \
      pkg/bundler/lanepf_bg.wasm.d.ts
