#!/usr/bin/env bash
# The measurements behind docs/techniques.md (issue "Techniques I"): bias, PCF, focusing and
# cascades on the scenes the literature's claims are about, on both backends.
#   eval/experiments/techniques-i.sh [OUT_DIR] [WxH] [FRAMES]
# Writes OUT_DIR/<experiment>.json per experiment and OUT_DIR/report/index.html.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
OUT="${1:-$ROOT/out/techniques-i}"
SIZE="${2:-640x360}"
FRAMES="${3:-8}"
SP="$ROOT/shadowport"
mkdir -p "$OUT"
bench() { local name="$1"; shift; "$SP" bench --backend both --size "$SIZE" --frames "$FRAMES" --out "$OUT/$name.json" "$@"; }

# 1. Four PSSM cascades against one focused map of the same total texel count (4 x 1024^2 = 2048^2),
#    and the naive scene-fitted map.
bench cascades-vs-single --scene terrain-city,ShadowColumns,canyon-city --technique csm \
  --param cascades=1,4 --param resolution=1024,2048
bench basic --scene terrain-city,ShadowColumns,canyon-city,dueling-frusta,grazing-light,contact,overlapping-occluders,distant-occluder \
  --technique basic
# 2. Stabilization against shimmering along the slow pan.
bench stabilize --scene terrain-city,ShadowColumns,canyon-city --technique csm --param stabilize=0,1
# 3. Acne on the grazing-light scene with a 7x7 kernel: constant bias swept until the acne goes,
#    against the receiver-plane bias (no constant bias).
bench bias-const --scene grazing-light --technique csm --param filter=box --param kernel=7 --param bias=const \
  --param depth_bias=100,10000,100000,300000,1000000,1500000,2000000,3000000,10000000 --param slope_bias=0
bench bias-receiver-plane --scene grazing-light --technique csm --param filter=box --param kernel=7 \
  --param bias=receiver-plane,slope,normal --param depth_bias=0,100 --param slope_bias=0,2
# 4. Blend band between cascades.
bench blend --scene terrain-city,ShadowColumns --technique csm --param blend=0,0.1,0.2 --param filter=box --param kernel=5
# 5. Filters, split schemes, selection, storage, fit and focus on the three main scenes.
bench filters --scene terrain-city,ShadowColumns,canyon-city --technique csm \
  --param filter=hw2x2,box,gauss,gathercmp,poisson --param kernel=5
bench splits --scene terrain-city,ShadowColumns,canyon-city --technique csm --param split=uniform,log,pssm
bench layout --scene terrain-city,ShadowColumns,canyon-city --technique csm \
  --param select=interval,map --param storage=array,atlas
bench fit --scene terrain-city,ShadowColumns,canyon-city --technique csm --param fit=scene,cascade --param focus=scene,receivers
# 6. The failure scenes with the default cascades.
bench failure-scenes --scene dueling-frusta,grazing-light,contact,overlapping-occluders,distant-occluder --technique csm

"$SP" report "$OUT"/*.json --out "$OUT/report" --title "Techniques I: bias, PCF, cascades"

# 7. The seam a blend band removes: one frame at 1280x720 with and without the band, cropped at
#    the split (two cascades, the first a tenth of the range at 512^2, 2x2 PCF, so the change of
#    resolution at the split shows).
for b in 0 0.4; do
  "$SP" render --backend vulkan --technique csm --scene ShadowColumns --size 1280x720 --param blend=$b --param cascades=2 \
    --param split=manual --param splits=0.1 --param resolution=512 --param filter=hw2x2 --out "$OUT/seam-blend-$b.png"
done
/usr/bin/python3 "$ROOT/eval/experiments/seam_crop.py" "$OUT/seam-blend-0.png" "$OUT/seam-blend-0.4.png" "$OUT/seam-crop.png" --size 90 --at-seam
