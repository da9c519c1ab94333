#!/usr/bin/env bash
# Install the outside renderers some tests compare with, where the machine allows it (Debian, as root):
# a headless browser for the page tests (tests/test_pages.py: chromium) and librsvg's rsvg-convert for the
# SVG overlay test (tests/test_output_frames.py: librsvg2-bin). Never fails: without them those tests skip
# and say so.
cd "$(dirname "$0")/.."
wanted=()
have_browser=0
for b in "${MEDIALAXIS_BROWSER:-}" chromium chromium-browser google-chrome; do
  if [ -n "$b" ] && command -v "$b" >/dev/null 2>&1; then have_browser=1; break; fi
done
[ "$have_browser" = 1 ] || wanted+=(chromium)
command -v rsvg-convert >/dev/null 2>&1 || wanted+=(librsvg2-bin)
[ "${#wanted[@]}" = 0 ] && exit 0
if [ "$(id -u)" != 0 ] || ! command -v apt-get >/dev/null 2>&1; then
  echo "browser.sh: no apt-get as root here to install ${wanted[*]}; the tests that need them will skip" >&2
  exit 0
fi
export DEBIAN_FRONTEND=noninteractive
if ! timeout 600 apt-get install -y -qq "${wanted[@]}" >/dev/null 2>&1; then
  timeout 300 apt-get update -qq >/dev/null 2>&1
  timeout 600 apt-get install -y -qq "${wanted[@]}" >/dev/null 2>&1 \
    || echo "browser.sh: installing ${wanted[*]} failed; the tests that need them will skip" >&2
fi
exit 0
