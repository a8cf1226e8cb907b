#!/usr/bin/env bash
# Installs penumbra's build and test dependencies from Debian 12's packages.
# Idempotent: packages already present are not touched, and apt is not run at
# all when nothing is missing. Needs root (or sudo) only when it installs.
# With --web-tests (`make test` passes it) it also installs what the web
# viewer's end-to-end test needs: Chromium, node and npm, and playwright-core
# from npm into tests/web/node_modules (npm ci, only when that is missing or
# older than tests/web/package-lock.json). With --clang it also installs clang
# 14 and its sanitizer and libFuzzer runtimes (scripts/sanitize.sh, fuzz.sh).
set -euo pipefail

web_tests=false
clang=false
for arg in "$@"; do
  [ "$arg" = "--web-tests" ] && web_tests=true
  [ "$arg" = "--clang" ] && clang=true
done

packages=(
  build-essential cmake ninja-build pkg-config
  libtbb-dev libglm-dev nlohmann-json3-dev libcli11-dev libfmt-dev
  zlib1g-dev libpng-dev libopenexr-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcpp-httplib-dev libjpeg-dev libhwy-dev
  pybind11-dev python3-dev python3-numpy python3-pytest python3-setuptools
)
# scripts/sanitize.sh and fuzz.sh: clang with its ASan, UBSan and libFuzzer runtimes.
$clang && packages+=(clang-14 libclang-rt-14-dev)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
# node may come from another source than Debian (which splits out npm), so
# the web test's tools are checked by command, not by package. They are
# best-effort: without them the web test skips with a message.
web_missing=()
if $web_tests; then
  [ -x /usr/bin/chromium ] || web_missing+=(chromium)
  command -v node > /dev/null || web_missing+=(nodejs)
  command -v npm > /dev/null || web_missing+=(npm)
fi

if [ ${#missing[@]} -eq 0 ] && [ ${#web_missing[@]} -eq 0 ]; then
  apt_needed=false
else
  apt_needed=true
fi

if $apt_needed; then
  if [ "$(id -u)" -eq 0 ]; then
    sudo=()
  elif command -v sudo >/dev/null 2>&1; then
    sudo=(sudo)
  else
    echo "install-deps: missing packages (${missing[*]} ${web_missing[*]}) and not root; install them as root" >&2
    [ ${#missing[@]} -eq 0 ] || exit 1
    sudo=(false)
  fi
  export DEBIAN_FRONTEND=noninteractive
  if [ ${#missing[@]} -gt 0 ]; then
    echo "install-deps: installing ${missing[*]}" >&2
    "${sudo[@]}" apt-get update -qq
    "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
  fi
  if [ ${#web_missing[@]} -gt 0 ]; then
    echo "install-deps: installing ${web_missing[*]} (for the web viewer test)" >&2
    { [ ${#missing[@]} -gt 0 ] || "${sudo[@]}" apt-get update -qq; } &&
      "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${web_missing[@]}" ||
      echo "install-deps: could not install ${web_missing[*]}; the web viewer test will skip" >&2
  fi
fi

if $web_tests && command -v npm > /dev/null; then
  web_dir="$(cd "$(dirname "$0")/.." && pwd)/tests/web"
  if [ ! -f "$web_dir/node_modules/.package-lock.json" ] ||
     [ "$web_dir/package-lock.json" -nt "$web_dir/node_modules/.package-lock.json" ]; then
    echo "install-deps: npm ci in tests/web (playwright-core)" >&2
    (cd "$web_dir" && npm ci --no-audit --no-fund --loglevel=error) ||
      echo "install-deps: npm ci failed; the web viewer test will skip" >&2
  fi
fi
