#!/usr/bin/env bash
# Proves the README's two commands on a fresh machine: makes a throw-away Debian bookworm root
# with debootstrap, gives it only what the README says a user has (Debian with git, make and curl;
# Rust by rustup, stable toolchain; Node.js and npm), clones the project into it at a commit and
# runs, as root inside it with chroot: `make pkg` (the build step of `make demo`), a look at the
# page `make demo` serves, `make setup` (make test's own set-up) and `make test`; with --all
# also the rest of `make test-all` (`make test-slow`). Prints each step's time and a summary;
# exits non-zero when a step fails.
#
#   sudo scripts/fresh-check.sh [--commit REV] [--all] [--keep] [--dir PARENT] [--reuse ROOT]
#     --commit REV   what to clone (default HEAD; committed work only)
#     --all          also run the slow tier, `make test-slow` (make test-all = test + test-slow)
#     --keep         keep the root afterwards (it is deleted otherwise)
#     --dir PARENT   where to make the root (default /var/tmp; needs ~12 GB)
#     --reuse ROOT   a root kept with --keep: skip making it, clone anew, run the make steps (for
#                    debugging: what an earlier run installed is still there, so it is not fresh)
#
# Needs root (debootstrap, mount, chroot) and the Debian and Rust registries. Installs
# debootstrap from apt when missing. The checkout sits at /work/lanepf in the root with
# ../shared (this checkout's ../shared) bound read-only beside it, as the tests expect.
# From this machine the root also gets what its network needs to reach the registries: its
# /etc/resolv.conf, the CA certificates in /usr/local/share/ca-certificates and the CA and proxy
# variables of the environment. Rust comes from rustup-init (static.rust-lang.org); Node.js is
# copied from this machine (/usr/bin/node and /usr/lib/node_modules/npm).
set -euo pipefail
{ # (read whole before it runs: editing the file during a run does not change the run)
here=$(cd "$(dirname "$0")/.." && pwd)

commit=HEAD all=0 keep=0 parent=/var/tmp reuse=
while [ $# -gt 0 ]; do
  case "$1" in
    --commit) commit=$2; shift 2 ;;
    --all) all=1; shift ;;
    --keep) keep=1; shift ;;
    --dir) parent=$2; shift 2 ;;
    --reuse) reuse=$(cd "$2" && pwd); keep=1; shift 2 ;;
    -h|--help) sed -n '2,24p' "$0"; exit 0 ;;
    *) echo "fresh-check: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done

say() { printf '[fresh-check %s] %s\n' "$(date +%H:%M:%S)" "$*"; }
die() { say "ERROR: $*" >&2; exit 1; }

[ "$(id -u)" = 0 ] || die "needs root (debootstrap, mount and chroot): run it with sudo"
sha=$(git -C "$here" rev-parse --verify "$commit^{commit}") || die "no commit $commit"
shared=$(cd "$here/.." && pwd)/shared
[ -d "$shared/data" ] || die "no $shared/data: the tests read ../shared/data"
[ -x /usr/bin/node ] && [ -d /usr/lib/node_modules/npm ] || die "no Node.js in /usr/bin/node and /usr/lib/node_modules/npm to copy"
if [ -n "$(git -C "$here" status --porcelain --untracked-files=no)" ]; then
  say "note: the working tree has uncommitted changes; the check clones commit ${sha:0:12} without them"
fi

if ! command -v debootstrap >/dev/null; then
  say "installing debootstrap from apt"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap >/dev/null \
    || { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap >/dev/null; }
fi

if [ -n "$reuse" ]; then
  root=$reuse
  [ -x "$root/root/.cargo/bin/cargo" ] || die "$root is not a root kept by fresh-check --keep"
  awk -v r="$root/" 'index($2, r) == 1 { found = 1 } END { exit !found }' /proc/mounts \
    && die "$root is in use (mounts under it)"
else
  mkdir -p "$parent"
  root=$(mktemp -d "$parent/lanepf-fresh.XXXXXX")
  chmod 755 "$root" # a root's / (apt's _apt user reads under it)
fi
log=$root.log
: > "$log"
say "root $root${reuse:+ (reused: not fresh)}, log $log, commit ${sha:0:12}"

# Clean-up on any exit: stop what still runs in the root, unmount, delete (unless --keep).
cleanup() {
  local rc=$?
  set +e
  local pids
  for pass in TERM KILL; do
    pids=$(for p in /proc/[0-9]*; do
      [ "$(readlink "$p/root" 2>/dev/null)" = "$root" ] && echo "${p#/proc/}"
    done)
    [ -z "$pids" ] && break
    kill -s "$pass" $pids 2>/dev/null
    sleep 2
  done
  # Deepest mount points first.
  for m in $(awk -v r="$root/" 'index($2, r) == 1 { print $2 }' /proc/mounts | sort -r); do
    umount "$m" 2>/dev/null || umount -l "$m"
  done
  if awk -v r="$root/" 'index($2, r) == 1 { found = 1 } END { exit !found }' /proc/mounts; then
    say "WARNING: mounts under $root remain; the root is NOT deleted" >&2
  elif [ "$keep" = 1 ]; then
    say "kept the root: $root (delete it with: rm -rf --one-file-system $root)"
  else
    rm -rf --one-file-system "$root"
  fi
  exit $rc
}
trap cleanup EXIT
trap 'exit 130' INT TERM

times=()
# step NAME COMMAND...: runs COMMAND, output to the log, and records its time; stops on failure.
step() {
  local name=$1; shift
  say "$name ..."
  local t0=$SECONDS rc=0
  "$@" >> "$log" 2>&1 || rc=$?
  local dt=$((SECONDS - t0))
  times+=("$(printf '%-44s %4dm%02ds  %s' "$name" $((dt / 60)) $((dt % 60)) "$([ $rc = 0 ] && echo ok || echo "FAILED ($rc)")")")
  say "$name: $((dt / 60))m$((dt % 60))s, $([ $rc = 0 ] && echo ok || echo "FAILED ($rc)")"
  if [ $rc != 0 ]; then
    tail -n 60 "$log" | sed 's/^/    | /'
    summary
    exit $rc
  fi
}
summary() {
  echo
  echo "fresh-check of lanepf ${sha:0:12} ($(git -C "$here" log -1 --format=%s "$sha" | cut -c1-70)) on $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores${reuse:+, REUSED root (not fresh)}"
  printf '  %s\n' "${times[@]}"
  echo "  log: $log"
}

# The environment inside: a login as root, plus this machine's network settings.
inside_env=(HOME=/root USER=root LOGNAME=root SHELL=/bin/bash LANG=C.UTF-8 TERM=dumb CI="${CI:-}"
  PATH=/root/.cargo/bin:/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin)
for v in NODE_EXTRA_CA_CERTS SSL_CERT_FILE SSL_CERT_DIR CURL_CA_BUNDLE GIT_SSL_CAINFO \
         http_proxy https_proxy no_proxy HTTP_PROXY HTTPS_PROXY NO_PROXY; do
  [ -n "${!v:-}" ] && inside_env+=("$v=${!v}")
done
inside() { chroot "$root" /usr/bin/env -i "${inside_env[@]}" /bin/bash -c "$1"; }

make_root() {
  debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian
}
mount_all() {
  mount -t proc proc "$root/proc"
  mount -t sysfs sysfs "$root/sys"
  mount --bind /dev "$root/dev"
  mount --bind /dev/pts "$root/dev/pts"
  mount -t tmpfs -o mode=1777,size=2g shm "$root/dev/shm"
  mkdir -p "$root/work/shared" "$root/work/lanepf"
  mount --bind "$shared" "$root/work/shared"
  mount -o remount,bind,ro "$root/work/shared"
}
# What a user of a fresh Debian 12 has before following the README: the usual apt sources,
# git, make and curl (with which rustup is installed).
base_packages() {
  cp /etc/resolv.conf "$root/etc/resolv.conf"
  if compgen -G '/usr/local/share/ca-certificates/*.crt' >/dev/null; then
    mkdir -p "$root/usr/local/share/ca-certificates"
    cp /usr/local/share/ca-certificates/*.crt "$root/usr/local/share/ca-certificates/"
  fi
  cat > "$root/etc/apt/sources.list" <<'EOF'
deb http://deb.debian.org/debian bookworm main
deb http://deb.debian.org/debian bookworm-updates main
deb http://deb.debian.org/debian-security bookworm-security main
EOF
  inside 'export DEBIAN_FRONTEND=noninteractive; apt-get update -qq && apt-get install -y -qq ca-certificates curl git make >/dev/null'
}
# Rust as https://rustup.rs installs it (rustup-init, default profile, stable).
install_rust() {
  inside 'set -e; curl --proto =https --tlsv1.2 -sSf -o /tmp/rustup-init https://static.rust-lang.org/rustup/dist/x86_64-unknown-linux-gnu/rustup-init
    chmod +x /tmp/rustup-init && /tmp/rustup-init -y --no-modify-path --default-toolchain stable && rm /tmp/rustup-init
    cargo --version && rustc --version'
}
# Node.js and npm, copied from this machine.
copy_node() {
  mkdir -p "$root/usr/lib/node_modules"
  cp -a /usr/bin/node "$root/usr/bin/node"
  cp -a /usr/lib/node_modules/npm "$root/usr/lib/node_modules/npm"
  ln -sf ../lib/node_modules/npm/bin/npm-cli.js "$root/usr/bin/npm"
  ln -sf ../lib/node_modules/npm/bin/npx-cli.js "$root/usr/bin/npx"
  inside 'node --version && npm --version'
}
clone() {
  rm -rf --one-file-system "$root/work/lanepf"
  git clone -q --no-hardlinks "$here" "$root/work/lanepf"
  git -C "$root/work/lanepf" checkout -q --detach "$sha"
  git -C "$root/work/lanepf" log -1 --oneline
}
# `make demo` = `make pkg`, then the server: start it, fetch the page and the package, stop it.
demo_serves() {
  inside 'cd /work/lanepf && { PORT=18080 setsid make demo > /tmp/demo.log 2>&1 & }; pid=$!
    for i in $(seq 180); do curl -sf -o /dev/null http://127.0.0.1:18080/ && break; sleep 1; done
    curl -sf http://127.0.0.1:18080/ | grep -qi "<html" && curl -sf -o /dev/null http://127.0.0.1:18080/pkg/web/lanepf_bg.wasm
    ok=$?; kill -- -$pid; cat /tmp/demo.log; exit $ok'
}

[ -n "$reuse" ] || step "debootstrap (minbase bookworm)" make_root
step "mounts" mount_all
if [ -z "$reuse" ]; then
  step "base: apt sources, git, make, curl" base_packages
  step "Rust: rustup-init, stable" install_rust
  step "Node.js and npm (copied)" copy_node
fi
step "clone ${sha:0:12}" clone
step "make pkg (make demo's build)" inside 'cd /work/lanepf && make pkg'
step "make demo serves the page" demo_serves
step "make setup (make test's set-up)" inside 'cd /work/lanepf && make setup'
step "make test" inside 'cd /work/lanepf && make test'
[ "$all" = 1 ] && step "make test-slow (the rest of make test-all)" inside 'cd /work/lanepf && make test-slow'
summary
echo "fresh-check: PASSED"
exit 0
}
