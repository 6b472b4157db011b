#!/usr/bin/env bash
# The measurements behind docs/techniques.md, part II (issue "Techniques II"): sample distribution
# shadow maps against hand-tuned PSSM, the analysis cost, cost growth with scene size, the
# partition schemes on their failure case, and light bleeding of the moment filters.
#   eval/experiments/techniques-ii.sh [OUT_DIR] [WxH] [FRAMES]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
OUT="${1:-$ROOT/out/techniques-ii}"
SIZE="${2:-640x360}"
FRAMES="${3:-8}"
SP="$ROOT/shadowport"
mkdir -p "$OUT"
bench() { local name="$1"; shift; "$SP" bench --backend both --size "$SIZE" --frames "$FRAMES" --out "$OUT/$name.json" "$@"; }
MAIN=terrain-city,canyon-city,ShadowColumns

# 1. PSSM hand-tuned over lambda, then SDSM (log, tight frusta, GPU-driven) with the same cascade
#    count and resolution; tight=0 isolates what the tight light-space frusta add.
bench pssm --scene $MAIN --technique csm --param cascades=4 --param resolution=1024 --param lambda=0.5,0.75,0.9,0.97
bench sdsm --scene $MAIN --technique sdsm --param cascades=4 --param resolution=1024 --param partition=log --param tight=0,1
# 2. Culling modes and temporal options.
bench sdsm-cull --scene $MAIN --technique sdsm --param cull=conservative,readback,latent,gpu
bench sdsm-quantize --scene $MAIN --technique sdsm --param quantize=0,1
# 3. Cost growth with scene size: PSSM against SDSM with culling (a) conservative, (b) readback, (d) GPU.
for t in 10000 100000 1000000 2500000; do
  bench growth-csm-$t --scene terrain-city --triangles $t --technique csm --frames 4
  bench growth-sdsm-$t --scene terrain-city --triangles $t --technique sdsm --param cull=conservative,readback,gpu --frames 4
done
# 4. Partition schemes: k-means on the distant-occluder case, adaptive-log against log across the gap.
bench partitions --scene distant-occluder,terrain-city --technique sdsm --param partition=log,adaptive-log,kmeans
# 5. Light bleeding of the filtering family on stacked occluders, in cascades and in SDSM.
#    bleed=0 shows the raw leak of each method; the default bleed shows it after the reduction.
bench bleeding --scene overlapping-occluders --technique csm --param filter=hw2x2,vsm,evsm2,evsm4,esm,msm --param blur=0.04
bench bleeding-raw --scene overlapping-occluders --technique csm --param filter=vsm,evsm2,evsm4,esm,msm --param blur=0.04 --param bleed=0
bench bleeding-sdsm --scene overlapping-occluders --technique sdsm --param filter=vsm,evsm4,msm --param blur=0.04
bench msaa --scene overlapping-occluders,ShadowColumns --technique csm --param filter=evsm4 --param msaa=1,4

"$SP" report "$OUT"/*.json --out "$OUT/report" --title "Techniques II: SDSM, moment filters, GPU culling"
