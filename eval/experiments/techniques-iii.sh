#!/usr/bin/env bash
# The measurements behind docs/techniques.md, part III (issue "Techniques III"): the perspective
# warps PSM, LiSPSM and TSM, alone and cascaded, against basic, csm and sdsm at equal shadow-map
# memory (4 Mi texels: one 2048^2 map, or four 1024^2 cascades), over the angle gamma between the
# view and the light (0: light from behind the viewer, 90: overhead, 180: towards the viewer,
# duelling frusta); then the warps' own parameters and their two depth modes.
#   eval/experiments/techniques-iii.sh [OUT_DIR] [WxH] [FRAMES]
# Tables and charts: eval/experiments/techniques_iii_tables.py OUT_DIR > tables.md
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
OUT="${1:-$ROOT/out/techniques-iii}"
SIZE="${2:-640x360}"
FRAMES="${3:-8}"
SP="$ROOT/shadowport"
mkdir -p "$OUT"
bench() { local name="$1"; shift; "$SP" bench --backend both --size "$SIZE" --frames "$FRAMES" --out "$OUT/$name.json" "$@"; }
SCENES=terrain-city,ShadowColumns
GAMMAS="${GAMMAS:-0,15,30,45,60,75,90,105,120,135,150,165,180}"

# 1. The angle sweep at equal memory.
bench sweep --scene $SCENES --light-gamma $GAMMAS \
  --technique basic:resolution=2048,csm:cascades=4:resolution=1024,sdsm:cascades=4:resolution=1024,psm:resolution=2048,lispsm:resolution=2048,tsm:resolution=2048,lispsm:cascades=4:resolution=1024,tsm:cascades=4:resolution=1024
# 2. Depth: biasing in warped space against storing light-space linear depth.
bench depth --scene $SCENES --light-gamma 30,60,90,120 --technique psm,lispsm,tsm --param depth=warped,linear
# 3. Receiver-plane bias against the slope bias of each depth mode, with a 3x3 box filter.
bench bias --scene $SCENES --light-gamma 45,90,135 --technique psm:filter=box,lispsm:filter=box,tsm:filter=box \
  --param depth=warped,linear --param receiver_plane=0,1
# 4. Each warp's parameter trading near against far quality.
bench psm-slide --scene $SCENES --light-gamma 45,90,135 --technique psm --param slide_back=0.1,0.3,1,3
bench lispsm-n --scene $SCENES --light-gamma 45,90,135 --technique lispsm --param n_scale=0.5,1,2,4
bench tsm-focus --scene $SCENES --light-gamma 45,90,135 --technique tsm --param focus=0.6,0.7,0.8,0.9

"$SP" report "$OUT"/*.json --out "$OUT/report" --title "Techniques III: perspective warps"
/usr/bin/python3 "$ROOT/eval/experiments/techniques_iii_tables.py" "$OUT" > "$OUT/tables.md"
echo "tables: $OUT/tables.md, charts: $OUT/gamma-*.png"
