# lanepf: the two commands are `make demo` and `make test` (see README.md); `make test-all`
# adds the slow tier.
# Every target installs what it needs first (scripts/setup.sh is idempotent).
SHELL := /bin/bash
export PATH := $(HOME)/.cargo/bin:$(CURDIR)/node_modules/.bin:$(PATH)
PORT ?= 8080
WASM_TEST_ENV := CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUNNER=wasm-bindgen-test-runner \
                 CHROMEDRIVER=/usr/bin/chromedriver WASM_BINDGEN_TEST_TIMEOUT=120

.PHONY: demo test test-all test-slow setup pkg types lint lint-rust lint-js test-native test-wasm test-chromium test-browser \
        fuzz-wasm bench bench-browser

## Build everything and serve the demo on http://127.0.0.1:$(PORT)/
demo: pkg
	node scripts/serve.mjs --port $(PORT)

## The fast tier (the README's test command and CI's): formatting, clippy, the JavaScript's types
## and ESLint, native, wasm in headless Chromium, the Node tests, the npm package and every
## end-to-end file in Chromium.
test: setup lint test-native test-wasm pkg test-chromium
	@echo "make test: all suites passed (make test-all also runs Firefox and WebKit)"

## Everything: the fast tier, then the slow one (the cross-browser suite in Firefox and WebKit).
test-all: test test-slow
	@echo "make test-all: all suites passed"

setup:
	bash scripts/setup.sh

pkg:
	bash scripts/setup.sh --no-browser
	bash scripts/build-pkg.sh

## Regenerates src/wasm/types/generated.d.ts (the tracker configs' TypeScript) from the Rust
## types; `cargo test` fails while the committed file is stale.
types:
	LANEPF_BLESS=1 cargo test --lib typegen

## rustfmt and clippy (native; wasm32 with the whole binding and with each of the package's two
## modules alone), then the JavaScript: the demo type-checked against the package's .d.ts
## (tsc, www/tsconfig*.json) and ESLint (eslint.config.js).
lint: lint-rust lint-js

lint-rust:
	cargo fmt --all -- --check
	cargo clippy --all-targets -- -D warnings
	cargo clippy --lib --no-default-features -- -D warnings
	cargo clippy --lib --target wasm32-unknown-unknown -- -D warnings
	cargo clippy --lib --target wasm32-unknown-unknown --no-default-features --features wasm-track -- -D warnings
	cargo clippy --lib --target wasm32-unknown-unknown --no-default-features --features wasm-sim -- -D warnings
	RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --lib

# The demo's types need the generated pkg/web/lanepf.d.ts, hence `pkg` (built once per make run:
# `make test` builds it here, in its lint step, not again later).
lint-js: pkg
	node_modules/.bin/tsc -p www/tsconfig.json
	node_modules/.bin/tsc -p www/tsconfig.worker.json
	node_modules/.bin/eslint www scripts tests pkg/worker pkg/frames pkg/bundler eslint.config.js

test-native:
	cargo test

test-wasm:
	$(WASM_TEST_ENV) cargo test --target wasm32-unknown-unknown --test web

# The Node tests and the end-to-end tests in Chromium (cross-browser.test.mjs in Chromium only).
test-chromium:
	E2E_BROWSERS=chromium node --test tests/node/ tests/e2e/ tests/npm/

# The slow tier: cross-browser.test.mjs in Firefox ESR and WebKitGTK, then the wasm API fuzz runs
# (tracker options near their defaults, then drawn wide: every option's range is checked).
test-slow: setup pkg
	E2E_BROWSERS=firefox,webkit node --test tests/e2e/cross-browser.test.mjs
	node scripts/fuzz-wasm.mjs
	node scripts/fuzz-wasm.mjs --wide

## 100 000 seeded random calls on the wasm package's API: 0 traps, 0 hangs, memory bounded
## (FUZZ_ARGS="--calls N --seed S" to change them).
fuzz-wasm: pkg
	node scripts/fuzz-wasm.mjs $(FUZZ_ARGS)

# All of the Node, npm and end-to-end tests in every browser (needs `make pkg`).
test-browser:
	node --test tests/node/ tests/e2e/ tests/npm/

## Criterion benchmarks (not part of `make test`).
bench:
	cargo bench

## Time every tracker in headless Chromium (ms/frame of Tracker.step).
bench-browser: pkg
	node scripts/bench-browser.mjs
