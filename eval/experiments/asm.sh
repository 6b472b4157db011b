#!/usr/bin/env bash
# The measurements behind docs/techniques.md "Adaptive shadow maps" (issue 14), on both backends:
#  1. equal memory: asm (readback, gpu, gpu with mark=visible) against basic 2048^2, csm 4 x 1024^2
#     and sdsm 4 x 1024^2 (16 MiB of depth each) on the default scene's slow pan and on a close-up;
#  2. the paper's figures on the close-up: effective resolution reached (pages per level), memory,
#     the lit pass's cost against basic 2048^2 (the paper: 73-91 %), and each refinement step's
#     GPU time (analysis, compaction by append buffer or prefix sum, readback or allocation,
#     pages) with the sun turning, so that every frame refines;
#  3. stability where it fails: a camera cut (frames to converge after it), a fast pan (refinement
#     lagging), a moving light (everything invalidated every frame) and a pool too small for the
#     view (unserved pages), each with iterations 1 and 4, readback and gpu; and the pan with a
#     clipmap of levels around the camera.
#   eval/experiments/asm.sh [OUT_DIR] [WxH] [FRAMES]
# PARTS="1 3" runs only those parts (default: all). Writes OUT_DIR/<experiment>.json, the camera
# paths it flies (OUT_DIR/paths/*.json) and prints the tables (asm_tables.py).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
OUT="${1:-$ROOT/out/asm}"
SIZE="${2:-320x180}"
FRAMES="${3:-16}"
PARTS="${PARTS:-1 2 3}"
part() { [[ " $PARTS " == *" $1 "* ]]; }
SP="$ROOT/shadowport"
mkdir -p "$OUT/paths"
bench() {
  local name="$1"; shift
  local frames=(--frames "$FRAMES")
  [[ " $* " == *" --frames "* ]] && frames=()
  "$SP" bench "$@" --backend both --size "$SIZE" "${frames[@]}" --out "$OUT/$name.json"
}

# Camera paths on the default scene (docs/techniques.md shows where): A looks at the stacked boxes'
# shadow from 4 m, B at the sphere's; "cut" holds A, jumps to B between frames FRAMES/2-1 and
# FRAMES/2 (repeated keys make the spline's tangents zero on both sides, so the camera is still
# before and after), "pan" turns 90 degrees about A over the path, "sun" holds A while the sun
# turns 20 degrees.
/usr/bin/python3 - "$OUT/paths" "$FRAMES" <<'PY'
import json, math, sys
out, frames = sys.argv[1], int(sys.argv[2])
A = ([-1.0, 1.6, 3.5], [-4.0, 0.2, 0.5])
B = ([7.5, 1.8, 2.0], [4.5, 0.3, -1.2])
lens = {"fov_y_degrees": 60.0, "near": 0.1, "far": 60.0, "up": [0, 1, 0]}
def save(name, keys):
    json.dump({"format": "shadowport-camera-path", "version": 1, "name": name, "lens": lens, "keys": keys},
              open(f"{out}/{name}.json", "w"), indent=1)
def key(t, cam, light=None):
    k = {"t": t, "position": cam[0], "target": cam[1]}
    if light: k["light_direction"] = light
    return k
save("close-up", [key(0.0, A), key(1.0, A)])
# The cut lies between the frames at t = (F/2 - 1)/(F - 1) and (F/2)/(F - 1).
a, b = (frames // 2 - 1) / (frames - 1), (frames // 2) / (frames - 1)
e = (b - a) / 10
save("cut", [key(0.0, A), key(a + e, A), key(a + 2 * e, A), key(b - 2 * e, B), key(b - e, B), key(1.0, B)])
pos, tgt = A
look = [tgt[i] - pos[i] for i in range(3)]
pan = []
for i in range(17):
    yaw = math.radians(90.0 * i / 16)
    c, s = math.cos(yaw), math.sin(yaw)
    pan.append(key(i / 16, (pos, [pos[0] + c * look[0] + s * look[2], tgt[1], pos[2] - s * look[0] + c * look[2]])))
save("pan", pan)
sun = []
d0 = [-0.55, -0.65, -0.5]
for i in range(9):
    yaw = math.radians(20.0 * i / 8)
    c, s = math.cos(yaw), math.sin(yaw)
    d = [c * d0[0] + s * d0[2], d0[1], -s * d0[0] + c * d0[2]]
    n = math.sqrt(sum(x * x for x in d))
    sun.append(key(i / 8, A, [x / n for x in d]))
save("sun", sun)
PY

ASM="asm,asm:allocation=gpu,asm:allocation=gpu:mark=visible"
EQUAL="basic:resolution=2048,csm:resolution=1024:cascades=4,sdsm:resolution=1024:cascades=4"
# 1. Equal memory, the default view (slow pan) and the close-up.
if part 1; then
  bench equal-default --frames 6 --scene default --technique "$ASM,$EQUAL"
  bench equal-close --frames 6 --scene default --path "$OUT/paths/close-up.json" --technique "$ASM,$EQUAL"
fi
# 2. Effective resolution against what the close-up reaches, and the steps' costs.
if part 2; then
  # At 640x360 (or SIZE2): the lit pass at 320x180 takes 2-5 ms here, too little to compare.
  SIZE="${SIZE2:-640x360}" bench resolution --frames 8 --scene default --path "$OUT/paths/close-up.json" --technique "asm,asm:allocation=gpu" \
    --param effective_resolution=4096,16384,65536,131072
  SIZE="${SIZE2:-640x360}" bench resolution-basic --frames 8 --scene default --path "$OUT/paths/close-up.json" --technique "basic:resolution=2048"
  # The paper's compaction (prefix sum) against the append buffer, on the sun path (every frame
  # refines from scratch, so every step runs every frame), marking every visible sample.
  SIZE="${SIZE2:-640x360}" bench compaction --frames 8 --scene default --path "$OUT/paths/sun.json" --param compaction=append,prefix \
    --technique "asm:mark=visible:iterations=1,asm:allocation=gpu:mark=visible:iterations=1"
fi
# 3. Failure cases: iterations 1 and 4; the small pool holds 36 pages of 64 texels (21 pinned at 3
#    resident levels), marking every visible sample, against 256.
if part 3; then
  for path in cut pan sun; do
    bench "$path" --scene default --path "$OUT/paths/$path.json" --technique "asm,asm:allocation=gpu" --param iterations=1,4
  done
  bench small-pool --scene default --path "$OUT/paths/pan.json" --param pool_pages=6,16 \
    --technique "asm:resident_levels=3:mark=visible:page_size=64,asm:allocation=gpu:resident_levels=3:mark=visible:page_size=64"
  # A clipmap of levels around the camera: 4 or 8 pages per level against none, on the pan.
  bench clipmap --scene default --path "$OUT/paths/pan.json" --param clipmap=0,4,8 \
    --technique "asm:mark=visible:page_size=64,asm:allocation=gpu:mark=visible:page_size=64"
fi
/usr/bin/python3 "$ROOT/eval/experiments/asm_tables.py" "$OUT"
