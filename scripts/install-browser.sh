#!/usr/bin/env bash
# Installs what the browser and glTF tests use, if missing: Debian's headless Chromium (the report's
# page and viewer, tests/export/test_report.py, tests/export/test_viewer.py) and the Khronos glTF validator (the
# gltf-validator npm package, global, for tests/export/test_gltf.py; needs node and npm, installed from
# Debian when missing). Needs root (CI runs as root); does nothing for what is already there.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
# another apt (unattended upgrades at boot) may hold the dpkg or lists lock: wait for it, don't fail
lock=(-o DPkg::Lock::Timeout=600 -o Acquire::Retries=3)
retry() {
  for i in $(seq 1 30); do
    "$@" && return 0
    echo "install-browser: $1 is busy or failed; retrying in 20 s ($i/30)" >&2
    sleep 20
  done
  return 1
}
need=()
if ! command -v chromium >/dev/null 2>&1 && ! command -v chromium-browser >/dev/null 2>&1; then
  need+=(chromium fonts-dejavu-core)
fi
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  need+=(nodejs npm)
fi
if [ ${#need[@]} -gt 0 ]; then
  if [ "$(id -u)" != 0 ]; then
    echo "install-browser: ${need[*]} missing and this is not root; the tests that need them will be skipped" >&2
    exit 0
  fi
  retry apt-get "${lock[@]}" update -qq >/dev/null
  retry apt-get "${lock[@]}" install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi
if ! NODE_PATH="$(npm root -g)" node -e "require('gltf-validator')" >/dev/null 2>&1; then
  if [ "$(id -u)" != 0 ]; then
    echo "install-browser: gltf-validator missing and this is not root; the validator test will be skipped" >&2
    exit 0
  fi
  retry npm install -g --no-audit --no-fund --loglevel=error gltf-validator@2.0.0-dev.3.10 >/dev/null
fi
command -v chromium || command -v chromium-browser
