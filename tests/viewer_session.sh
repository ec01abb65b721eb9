#!/usr/bin/env bash
# Drives a GPU stage's viewer (--window) with synthetic input, as a user would; run it inside an X server
# (xvfb-run -a tests/viewer_session.sh EXE DIR STAGE_ARGS...). In DIR it leaves what run_gpu_case.cmake (MODE viewer)
# compares, the screenshots the P key saves:
#   <stage>_view_0000.png  the window as it opened
#   <stage>_view_0001.png  after key 1 (shadows off)
#   <stage>_view_0002.png  after a left drag (orbit), held until a frame was rendered while moving
# then it waits 2 s and Esc closes the window; the stage must exit 0. Every wait gives up after 60 s.
# The viewer runs with --moving-scale 4, and its closing summary (viewer.h) must show that the drag rendered frames
# at a quarter of the size and that the still window rendered nothing (at most 12 frames in all, where a viewer
# that renders all the time renders dozens in those 2 s).
set -euo pipefail
exe=$1 dir=$2
shift 2
stage=$(basename "$exe")
cd "$dir"
rm -f "${stage}"_view_*.png viewer.log
"$exe" "$@" --window --moving-scale 4 > viewer.log 2>&1 &
pid=$!
trap 'kill "$pid" 2>/dev/null || true' EXIT

fail() { echo "viewer session: $*" >&2; cat viewer.log >&2; exit 1; }
wait_for() {   # wait_for FILE: until the viewer saved it (and the file is complete: it is renamed into place)
  for _ in $(seq 600); do
    [ -f "$1" ] && return 0
    kill -0 "$pid" 2>/dev/null || fail "the stage exited before saving $1"
    sleep 0.1
  done
  fail "no $1 after 60 s"
}

# The title shows the frame time once the first frame is on screen.
win=$(timeout 60 xdotool search --sync --onlyvisible --name " ms per frame \| " | head -n1) || fail "no window"
# Keys go to the window under the pointer (no window manager: focus follows the pointer).
xdotool mousemove --window "$win" 20 20
xdotool key p
wait_for "${stage}_view_0000.png"
xdotool key 1 key p
wait_for "${stage}_view_0001.png"
# The drag: the button stays down, and the pointer keeps moving, until the title says a frame was rendered while
# moving ("moving: WxH (1/N)"). A drag begun and ended between two frames (a loaded machine: one frame can take
# longer than the whole gesture) moves the camera but rightly renders no reduced frame, so the test must not end it
# before one was shown.
xdotool mousemove --window "$win" 20 30 mousedown 1
x=20
for _ in $(seq 600); do
  x=$(( x < 70 ? x + 5 : 20 ))
  xdotool mousemove --window "$win" "$x" 32
  xdotool search --name "\| moving: " > /dev/null 2>&1 && break
  kill -0 "$pid" 2>/dev/null || fail "the stage exited during the drag"
  sleep 0.1
done
xdotool mousemove --window "$win" 70 34 mouseup 1
xdotool key p
wait_for "${stage}_view_0002.png"
sleep 2
xdotool key Escape
for _ in $(seq 600); do
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
trap - EXIT
wait "$pid" || fail "the stage exited with $?"
grep -q "shadows off" viewer.log || fail "key 1 did not turn shadows off"
summary=$(grep "viewer: .* frames while moving" viewer.log) || fail "no frame summary when the window closed"
read -r moving full <<< "$(sed -E 's/.*viewer: ([0-9]+) frames while moving .*, ([0-9]+) at full resolution.*/\1 \2/' <<< "$summary")"
[ "$moving" -ge 1 ] || fail "the drag rendered no reduced frame: $summary"
width=640 height=480   # the stages' defaults, unless the arguments say otherwise
args=("$@")
for i in "${!args[@]}"; do
  case "${args[$i]}" in
    --width) width=${args[$((i + 1))]} ;;
    --height) height=${args[$((i + 1))]} ;;
  esac
done
want="at $(((width + 3) / 4))x$(((height + 3) / 4)))"
grep -qF "while moving (median" <<< "$summary" && grep -qF "$want" <<< "$summary" ||
  fail "the moving frames were not a quarter of ${width}x${height} ($want): $summary"
[ $((moving + full)) -le 12 ] || fail "the viewer kept rendering while nothing changed: $summary"
echo "viewer session: $summary"
