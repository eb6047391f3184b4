#!/usr/bin/env bash
# Installs everything lanepf's build, demo and tests need, on a Debian machine with Rust (rustup)
# and Node/npm. Idempotent: each step checks first and does nothing when already done.
#   scripts/setup.sh          everything (wasm target, wasm-bindgen CLI, npm tools, Chromium, Firefox,
#                             WebKitGTK's WebDriver, Xvfb and ffmpeg)
#   scripts/setup.sh --no-browser   skip the browsers (enough for `make demo`)
set -euo pipefail
cd "$(dirname "$0")/.."

want_browser=1
[ "${1:-}" = "--no-browser" ] && want_browser=0

say() { printf '[setup] %s\n' "$*"; }
die() { printf '[setup] ERROR: %s\n' "$*" >&2; exit 1; }

command -v cargo >/dev/null || die "cargo not found: install Rust with rustup (https://rustup.rs) first"
command -v rustup >/dev/null || die "rustup not found: lanepf needs rustup to add the wasm32 target"
command -v npm >/dev/null || die "npm not found: install Node.js 18+ and npm first"

# apt-get install PACKAGES... as root; otherwise stops with the command to run with sudo.
apt_install() {
  if [ "$(id -u)" != 0 ]; then
    die "missing Debian packages: $*; installing them needs root. Run:
    sudo apt-get update && sudo apt-get install -y --no-install-recommends $*
then run this command again."
  fi
  say "installing $* from apt"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "$@" >/dev/null
}

# 0. A C compiler and the C library's files: cargo links with `cc`, which rustup does not bring.
{ command -v cc >/dev/null && compgen -G '/usr/lib/*/crt1.o' >/dev/null; } || apt_install gcc libc6-dev

# 1. Rust pieces: the wasm32 target, rustfmt and clippy.
if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
  say "adding the wasm32-unknown-unknown target"
  rustup target add wasm32-unknown-unknown
fi
for comp in rustfmt clippy; do
  if ! rustup component list --installed 2>/dev/null | grep -q "^$comp"; then
    say "adding rustup component $comp"
    rustup component add "$comp"
  fi
done

# 2. wasm-bindgen CLI, exactly the version Cargo.lock pins (the CLI and the library must agree).
wb_version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock)
[ -n "$wb_version" ] || die "cannot read the wasm-bindgen version from Cargo.lock"
have=$(wasm-bindgen --version 2>/dev/null | awk '{print $2}' || true)
if [ "$have" != "$wb_version" ] || ! command -v wasm-bindgen-test-runner >/dev/null; then
  say "installing wasm-bindgen-cli $wb_version (about 3 minutes; not --locked, see ../shared/TOOLCHAIN.md)"
  cargo install wasm-bindgen-cli --version "$wb_version"
fi

# 3. npm tools: binaryen (wasm-opt 132; Debian's is too old), playwright-core and puppeteer-core
#    (no browser download), and what the npm package's test builds its fixture apps with:
#    Vite (and vite-plugin-wasm), webpack 5 and TypeScript (which also type-checks the demo, with
#    ESLint, its @eslint/js rules and globals, in `make lint`).
if [ ! -x node_modules/.bin/wasm-opt ] || [ ! -d node_modules/playwright-core ] \
   || [ ! -d node_modules/puppeteer-core ] || [ ! -d node_modules/vite ] || [ ! -d node_modules/webpack ] \
   || [ ! -d node_modules/typescript ] || [ ! -d node_modules/vite-plugin-wasm ] \
   || [ ! -d node_modules/eslint ] || [ ! -d node_modules/@eslint/js ] || [ ! -d node_modules/globals ] \
   || [ package.json -nt node_modules/.package-lock.json ]; then
  say "installing npm dev tools (binaryen, playwright-core, puppeteer-core, vite, webpack, typescript, eslint)"
  if [ -f package-lock.json ]; then npm ci --no-audit --no-fund; else npm install --no-audit --no-fund; fi
fi

# 4. Chromium and chromedriver from Debian, for the wasm tests and the end-to-end tests;
#    Debian's Firefox ESR for the cross-browser end-to-end suite (driven over WebDriver BiDi by
#    puppeteer-core, so no geckodriver and no browser download); and WebKitGTK's WebDriver
#    (webkit2gtk-driver: WebKitWebDriver, and MiniBrowser in libwebkit2gtk-4.1-0) with Xvfb for
#    the same suite in WebKit, Safari's engine. WebKitGTK has no headless mode, so it draws on
#    Xvfb. Without its recommends (ImageMagick, Ghostscript, GStreamer's libav and bad plugins,
#    ~80 packages the tests do not use): 44 packages, 45 MB, about 10 s here.
if [ "$want_browser" = 1 ]; then
  missing=()
  { [ -x /usr/bin/chromium ] && [ -x /usr/bin/chromedriver ]; } || missing+=(chromium chromium-driver)
  [ -x /usr/bin/firefox-esr ] || missing+=(firefox-esr)
  missing_lean=()
  { [ -x /usr/bin/WebKitWebDriver ] && compgen -G '/usr/lib/*/webkit2gtk-4.1/MiniBrowser' >/dev/null; } \
    || missing_lean+=(webkit2gtk-driver)
  [ -x /usr/bin/Xvfb ] || missing_lean+=(xvfb)
  # ffmpeg and ffprobe make the small test videos of tests/node/demux.test.mjs and
  # tests/e2e/webcodecs.test.mjs (H.264, VP8, VP9, AV1, HEVC, MPEG-4) at test time.
  { [ -x /usr/bin/ffmpeg ] && [ -x /usr/bin/ffprobe ]; } || missing_lean+=(ffmpeg)
  if [ "${#missing[@]}" -gt 0 ] || [ "${#missing_lean[@]}" -gt 0 ]; then
    if [ "$(id -u)" != 0 ]; then
      die "missing Debian packages: ${missing[*]} ${missing_lean[*]}; installing them needs root. Run:
    sudo apt-get update && sudo apt-get install -y ${missing[*]} && sudo apt-get install -y --no-install-recommends ${missing_lean[*]}
then run this command again."
    fi
    say "installing ${missing[*]} ${missing_lean[*]} from apt (about a minute)"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    [ "${#missing[@]}" -eq 0 ] || apt-get install -y -qq "${missing[@]}" >/dev/null
    [ "${#missing_lean[@]}" -eq 0 ] || apt-get install -y -qq --no-install-recommends "${missing_lean[@]}" >/dev/null
  fi
fi
say "ready"
