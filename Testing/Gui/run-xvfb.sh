#!/usr/bin/env bash
# Runs a command on its own Xvfb display with Mesa's software OpenGL
# (llvmpipe), with a time limit, and returns the command's exit status:
#
#   Testing/Gui/run-xvfb.sh [--timeout SECONDS] command args...
#
# Xvfb picks a free display itself (-displayfd), so parallel runs (CTest -j,
# other users of xvfb-run) do not race for :99 as `xvfb-run -a` can.
set -euo pipefail

timeout_s=300
if [ "${1:-}" = "--timeout" ]; then timeout_s=$2; shift 2; fi
if [ $# -eq 0 ]; then echo "usage: $0 [--timeout S] command args..." >&2; exit 2; fi
command -v Xvfb >/dev/null || { echo "run-xvfb.sh: Xvfb not found (apt-get install xvfb)" >&2; exit 2; }

tmp=$(mktemp -d)
xvfb_pid=""
cleanup() {
  if [ -n "$xvfb_pid" ]; then kill "$xvfb_pid" 2>/dev/null || true; wait "$xvfb_pid" 2>/dev/null || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT

# Xvfb writes the display number it chose to fd 3, once it accepts clients.
exec 3>"$tmp/display"
Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp -noreset >"$tmp/xvfb.log" 2>&1 &
xvfb_pid=$!
exec 3>&-
for _ in $(seq 100); do
  [ -s "$tmp/display" ] && break
  kill -0 "$xvfb_pid" 2>/dev/null || { cat "$tmp/xvfb.log" >&2; echo "run-xvfb.sh: Xvfb failed" >&2; exit 2; }
  sleep 0.1
done
[ -s "$tmp/display" ] || { echo "run-xvfb.sh: Xvfb did not start" >&2; exit 2; }

export DISPLAY=":$(tr -d '[:space:]' <"$tmp/display")"
export LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$tmp}"
status=0
timeout --kill-after=10 "$timeout_s" "$@" || status=$?
if [ "$status" -eq 124 ]; then echo "run-xvfb.sh: timed out after ${timeout_s}s: $*" >&2; fi
exit "$status"
