#!/usr/bin/env bash
# Install a headless browser for the page tests (tests/test_pages.py) where the machine allows it:
# Debian's chromium through apt-get, as root. Never fails: without a browser those tests skip and say so.
cd "$(dirname "$0")/.."
for b in "${MEDIALAXIS_BROWSER:-}" chromium chromium-browser google-chrome; do
  if [ -n "$b" ] && command -v "$b" >/dev/null 2>&1; then exit 0; fi
done
if [ "$(id -u)" != 0 ] || ! command -v apt-get >/dev/null 2>&1; then
  echo "browser.sh: no Chromium and no apt-get as root here; the page rendering test will skip" >&2
  exit 0
fi
export DEBIAN_FRONTEND=noninteractive
if ! timeout 600 apt-get install -y -qq chromium >/dev/null 2>&1; then
  timeout 300 apt-get update -qq >/dev/null 2>&1
  timeout 600 apt-get install -y -qq chromium >/dev/null 2>&1 \
    || echo "browser.sh: installing chromium failed; the page rendering test will skip" >&2
fi
exit 0
