#!/usr/bin/env bash
# Installs Debian's headless Chromium for the report test (tests/test_report.py), if missing.
# Needs root (CI runs as root); does nothing when chromium is already there.
set -euo pipefail
if command -v chromium >/dev/null 2>&1 || command -v chromium-browser >/dev/null 2>&1; then
  exit 0
fi
if [ "$(id -u)" != 0 ]; then
  echo "install-browser: chromium is missing and this is not root; the report test will be skipped" >&2
  exit 0
fi
export DEBIAN_FRONTEND=noninteractive
# another apt (unattended upgrades at boot) may hold the dpkg or lists lock: wait for it, don't fail
lock=(-o DPkg::Lock::Timeout=600 -o Acquire::Retries=3)
retry() {
  for i in $(seq 1 30); do
    "$@" && return 0
    echo "install-browser: apt is busy or failed; retrying in 20 s ($i/30)" >&2
    sleep 20
  done
  return 1
}
retry apt-get "${lock[@]}" update -qq >/dev/null
retry apt-get "${lock[@]}" install -y -qq --no-install-recommends chromium fonts-dejavu-core >/dev/null
command -v chromium
