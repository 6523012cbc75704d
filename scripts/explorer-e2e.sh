#!/usr/bin/env bash
# End-to-end check of the explorer in a real X window: start it under Xvfb, drag the "Light x"
# slider with xdotool, take screenshots before and after, and check that the rendered picture
# changed (and did not change without the drag), and that its left side got brighter.
#
#   bash scripts/explorer-e2e.sh            # builds the explorer (release) and runs the check
#
# Environment:
#   OUT=dir           where the screenshots and logs go (default target/explorer-e2e)
#   EXPLORER_BIN=path use this explorer binary instead of building one
#   E2E_DISPLAY=:N    the X display number for Xvfb (default: the first free one from :99)
#
# Needs Xvfb, xdotool and ImageMagick (import, compare, identify), and a Vulkan or GL driver for the window
# (Mesa's lavapipe / llvmpipe work). Run as root, it installs what is missing with apt-get.
set -euo pipefail
cd "$(dirname "$0")/.."

OUT=${OUT:-target/explorer-e2e}
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)

say() { printf '[explorer-e2e] %s\n' "$*"; }
fail() {
  say "FAIL: $*"
  exit 1
}

# --- tools -------------------------------------------------------------------------------------
# `import` and `compare` must be ImageMagick's (some machines put a stand-in `convert` on PATH).
have_tools() {
  command -v Xvfb >/dev/null && command -v xdotool >/dev/null &&
    command -v import >/dev/null && command -v identify >/dev/null &&
    compare -version 2>/dev/null | grep -q ImageMagick &&
    dpkg -s mesa-vulkan-drivers libvulkan1 libxkbcommon-x11-0 libxcursor1 libxi6 libxrandr2 \
      >/dev/null 2>&1
}
if ! have_tools; then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    say "installing xvfb, xdotool, imagemagick and the Mesa/X11 libraries the window needs"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
      xvfb xdotool imagemagick mesa-vulkan-drivers libvulkan1 \
      libxkbcommon-x11-0 libxcursor1 libxi6 libxrandr2 >/dev/null
  else
    fail "need Xvfb, xdotool, ImageMagick, mesa-vulkan-drivers, libvulkan1 and the X11 libraries \
libxkbcommon-x11-0 libxcursor1 libxi6 libxrandr2 (run as root to install them with apt-get)"
  fi
fi

# --- the binary --------------------------------------------------------------------------------
if [ -z "${EXPLORER_BIN:-}" ]; then
  say "building the explorer (release)"
  cargo build --release -p explorer --quiet
  EXPLORER_BIN=target/release/explorer
fi
[ -x "$EXPLORER_BIN" ] || fail "no explorer binary at $EXPLORER_BIN"

# --- Xvfb --------------------------------------------------------------------------------------
if [ -n "${E2E_DISPLAY:-}" ]; then
  DISPLAY_NUM=${E2E_DISPLAY#:}
else
  DISPLAY_NUM=99
  while [ -e "/tmp/.X11-unix/X$DISPLAY_NUM" ] || [ -e "/tmp/.X$DISPLAY_NUM-lock" ]; do
    DISPLAY_NUM=$((DISPLAY_NUM + 1))
  done
fi
export DISPLAY=":$DISPLAY_NUM"

XVFB_PID=""
APP_PID=""
cleanup() {
  [ -n "$APP_PID" ] && kill "$APP_PID" 2>/dev/null || true
  [ -n "$XVFB_PID" ] && kill "$XVFB_PID" 2>/dev/null || true
  wait 2>/dev/null || true
}
trap cleanup EXIT

say "starting Xvfb on $DISPLAY"
Xvfb "$DISPLAY" -screen 0 1280x1024x24 -nolisten tcp >"$OUT/xvfb.log" 2>&1 &
XVFB_PID=$!
for _ in $(seq 50); do
  xdotool getdisplaygeometry >/dev/null 2>&1 && break
  sleep 0.1
done
xdotool getdisplaygeometry >/dev/null 2>&1 || fail "Xvfb did not start (see $OUT/xvfb.log)"

# --- the explorer ------------------------------------------------------------------------------
say "starting $EXPLORER_BIN"
rm -f "$OUT"/*.png
: >"$OUT/explorer.log"
# XDG_RUNTIME_DIR: Mesa's drivers warn without one.
XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$(mktemp -d)} EXPLORER_PRINT_LAYOUT=1 \
  "$EXPLORER_BIN" >"$OUT/explorer.log" 2>&1 &
APP_PID=$!

WINDOW=""
for _ in $(seq 300); do
  kill -0 "$APP_PID" 2>/dev/null || fail "the explorer exited early: $(tail -20 "$OUT/explorer.log")"
  if grep -q '^layout-end' "$OUT/explorer.log"; then
    WINDOW=$(xdotool search --name '^phong explorer$' 2>/dev/null | head -1 || true)
    [ -n "$WINDOW" ] && break
  fi
  sleep 0.2
done
[ -n "$WINDOW" ] || fail "no explorer window with a layout within 60 s (see $OUT/explorer.log)"

# The last layout the app printed: "layout NAME x y w h ppp=P", window-relative physical pixels.
rect() {
  awk -v n="$1" '$1 == "layout" && $2 == n { r = $3 " " $4 " " $5 " " $6 } END { print r }' \
    "$OUT/explorer.log"
}
eval "$(xdotool getwindowgeometry --shell "$WINDOW")" # X, Y, WIDTH, HEIGHT of the window
read -r IX IY IW IH <<<"$(rect image)"
read -r SX SY SW SH <<<"$(rect light_x)"
[ -n "${IW:-}" ] && [ -n "${SW:-}" ] || fail "the layout lacks the image or the slider: $(cat "$OUT/explorer.log")"
CROP="${IW}x${IH}+$((X + IX))+$((Y + IY))"
say "window $WINDOW at $X,$Y ${WIDTH}x$HEIGHT; picture $CROP; slider rail ${SW}x$SH+$((X + SX))+$((Y + SY))"

shot() { # name: full screenshot and the picture's region
  import -window root "$OUT/$1.png"
  import -window root -crop "$CROP" +repage "$OUT/$1-picture.png"
}
changed() { # a b: how many pixels differ (compare exits 1 when they do)
  { compare -metric AE "$OUT/$1-picture.png" "$OUT/$2-picture.png" null: 2>&1 || true; } |
    awk '{print int($1)}'
}

sleep 2 # let the first frames reach the screen
shot before
sleep 1
shot idle
IDLE=$(changed before idle)
say "pixels changed with no input: $IDLE"
[ "$IDLE" -eq 0 ] || fail "the picture changed without any input ($IDLE pixels)"

# Drag the light from the right end of the rail to the left end.
Y_MID=$((Y + SY + SH / 2))
X_FROM=$((X + SX + SW * 9 / 10))
X_TO=$((X + SX + SW / 20))
say "dragging Light x from $X_FROM to $X_TO at y=$Y_MID"
xdotool mousemove "$X_FROM" "$Y_MID"
sleep 0.3
xdotool mousedown 1
for step in 1 2 3 4 5 6 7 8; do
  xdotool mousemove $((X_FROM + (X_TO - X_FROM) * step / 8)) "$Y_MID"
  sleep 0.1
done
sleep 0.3
xdotool mouseup 1
sleep 0.5
# Move the pointer off the controls so no hover highlight remains, then let it repaint.
xdotool mousemove $((X + WIDTH - 5)) $((Y + HEIGHT - 5))
sleep 2
shot after

TOTAL=$((IW * IH))
CHANGED=$(changed before after)
say "pixels changed in the picture after the drag: $CHANGED of $TOTAL"
# The light swings from one side of the sphere to the other: much of the lit side changes.
[ "$CHANGED" -gt $((TOTAL / 50)) ] || fail "the picture barely changed ($CHANGED pixels)"
# And the right way: the light went to the left, so the picture's left third got brighter.
brightness() { identify -format '%[fx:mean]' "$OUT/$1-picture.png[$((IW / 3))x$IH+0+0]"; }
LEFT_BEFORE=$(brightness before)
LEFT_AFTER=$(brightness after)
say "mean brightness of the picture's left third: $LEFT_BEFORE before, $LEFT_AFTER after"
awk -v a="$LEFT_BEFORE" -v b="$LEFT_AFTER" 'BEGIN { exit !(b > a + 0.05) }' ||
  fail "the left of the picture did not get brighter with the light on the left"
say "PASS: screenshots in $OUT (before.png, after.png, *-picture.png)"
