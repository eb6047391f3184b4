# lanepf: the two commands are `make demo` and `make test` (see README.md).
# Every target installs what it needs first (scripts/setup.sh is idempotent).
SHELL := /bin/bash
export PATH := $(HOME)/.cargo/bin:$(CURDIR)/node_modules/.bin:$(PATH)
PORT ?= 8080
WASM_TEST_ENV := CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUNNER=wasm-bindgen-test-runner \
                 CHROMEDRIVER=/usr/bin/chromedriver WASM_BINDGEN_TEST_TIMEOUT=120

.PHONY: demo test setup pkg lint test-native test-wasm test-browser bench bench-browser

## Build everything and serve the demo on http://127.0.0.1:$(PORT)/
demo: pkg
	node scripts/serve.mjs --port $(PORT)

## Run every test: formatting, clippy, native, wasm in headless Chromium, browser end-to-end.
test: setup lint test-native test-wasm pkg test-browser
	@echo "make test: all suites passed"

setup:
	bash scripts/setup.sh

pkg:
	bash scripts/setup.sh --no-browser
	bash scripts/build-pkg.sh

lint:
	cargo fmt --all -- --check
	cargo clippy --all-targets -- -D warnings
	cargo clippy --lib --target wasm32-unknown-unknown -- -D warnings

test-native:
	cargo test

test-wasm:
	$(WASM_TEST_ENV) cargo test --target wasm32-unknown-unknown --test web

test-browser:
	node --test tests/node/ tests/e2e/ tests/npm/

## Criterion benchmarks (not part of `make test`).
bench:
	cargo bench

## Time every tracker in headless Chromium (ms/frame of Tracker.step).
bench-browser: pkg
	node scripts/bench-browser.mjs
