#!/usr/bin/env bash
# The measurements behind docs/soft-shadows.md (issue 15: wide PCF kernels, PCSS, hybrid min/max
# plane shadow maps), on both backends:
#  1. the lit pass's GPU time and the secondary map's build ("hpsm" pass) against the filter's
#     width, basic and csm, accel=none|minmax|hpsm, with the fractions each lookup was decided by
#     (min/max, plane, filtered); timed with hpsm_counters=0, fractions from a second, counted run;
#  2. (from part 1's pictures and metrics) whether acceleration changes any pixel;
#  3. the flat-receiver claim: planes against min/max on large floors under low suns;
#  4. hpsm_eps and hpsm_block sweeps;
#  5. PCSS against the area-light reference (--light-size) next to fixed kernels and hw2x2, on the
#     default scene and on overlapping occluders at different depths; the penumbra-only error on
#     stacked-planks (a high plank crossing over a low one: PCSS's one average blocker depth) against
#     single-plank (the low plank alone): part "5b"; the same pixels near the crossing alone (the
#     scenes' "crossing" region, and "far" as the control): penumbra MAE and light bleeding into
#     the umbra (bench results' metrics.regions): part "5c".
#   eval/experiments/techniques-v.sh [OUT_DIR] [WxH] [FRAMES]
# PARTS="1 3" runs only those parts (default: all); SCENES, TECHS, KERNELS (filter=... suffixes) and
# SUNS (pcss light_size values) override part 1's lists, e.g. for a quick run.
# A combination a technique refuses (an hpsm_block the min/max baseline cannot take, a kernel too
# wide for its filter) is recorded as OUT_DIR/<experiment>.refused and shown as such in the tables.
# Writes OUT_DIR/<experiment>.json and prints the tables (techniques_v_tables.py).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
OUT="${1:-$ROOT/out/techniques-v}"
SIZE="${2:-640x360}"
FRAMES="${3:-8}"
PARTS="${PARTS:-1 3 4 5 5b 5c}"
SCENES="${SCENES:-default,terrain-city,grazing-light}"
part() { [[ " $PARTS " == *" $1 "* ]]; }
SP="$ROOT/shadowport"
mkdir -p "$OUT"
# The CLI refuses an option given twice: a --frames among the caller's options replaces FRAMES.
bench() {
  local name="$1"; shift
  local frames=(--frames "$FRAMES")
  [[ " $* " == *" --frames "* ]] && frames=()
  "$SP" bench "$@" --backend both --size "$SIZE" "${frames[@]}" --out "$OUT/$name.json"
}
# Like bench, but a refusal (bad combination, exit status != 0 before any run) is kept as a note
# instead of stopping the script.
try_bench() {
  local name="$1"; shift
  rm -f "$OUT/$name.refused"
  if ! bench "$name" "$@" 2> "$OUT/$name.err"; then
    { grep 'error:' "$OUT/$name.err" || grep -v '^bench: ' "$OUT/$name.err"; } | tail -n 3 > "$OUT/$name.refused"
    echo "techniques-v: $name refused: $(cat "$OUT/$name.refused")" >&2
    rm -f "$OUT/$name.json"
  fi
}

KERNELS="${KERNELS:-box:kernel=3 box:kernel=7 box:kernel=15 gathercmp:kernel=15 gathercmp:kernel=31}"
SUNS="${SUNS:-0.53 3}"
TECHS="${TECHS:-basic csm}"
# 1. Speed against width: every kernel and accel of a technique in one bench (one reference, one
#    start-up), timed with hpsm_counters=0, then one counted frame for the fractions (the
#    counters' atomics would distort the timing). pcss runs one bench per accel and sun, so that a
#    refused combination loses only its own runs.
if part 1; then
  for t in $TECHS; do
    list=""
    for k in $KERNELS; do list="${list:+$list,}$t:filter=$k"; done
    bench "speed-$t" --scene "$SCENES" --technique "$list" --param accel=none,minmax,hpsm --param hpsm_counters=0
    bench "frac-$t" --frames 1 --scene "$SCENES" --technique "$list" --param accel=minmax,hpsm --param hpsm_counters=1
    for s in $SUNS; do
      for a in none minmax hpsm; do
        try_bench "speed-$t-pcss$s-$a" --scene "$SCENES" --technique "$t:filter=pcss:light_size=$s:accel=$a" --param hpsm_counters=0
        if [[ $a != none && -f "$OUT/speed-$t-pcss$s-$a.json" ]]; then
          try_bench "frac-$t-pcss$s-$a" --frames 1 --scene "$SCENES" --technique "$t:filter=pcss:light_size=$s:accel=$a"
        fi
      done
    done
  done
fi

# 1b. basic's default slope_bias (2) lets a wide kernel shadow its own lit receiver in part, so few
#     footprints are uniform; the same with a slope bias raised with the kernel (counted, 2 frames).
part 1 && bench biased --frames 2 --scene "$SCENES" --technique basic:filter=box:kernel=7:slope_bias=6,basic:filter=box:kernel=15:slope_bias=12 \
  --param accel=none,minmax,hpsm

# 3. Large floors under low suns: grazing-light (its own sun, 3 degrees above the floor) and the
#    default scene as it is (41 degrees) and with its sun turned to the view direction
#    (--light-gamma 0: 22 degrees above the ground, as the default camera looks 22 degrees down).
part 3 && bench lowsun --frames 1 --scene default,grazing-light --technique basic:filter=box:kernel=3,basic:filter=box:kernel=7 --param accel=hpsm,minmax
part 3 && bench lowsun-gamma --frames 1 --scene default --light-gamma 0 --technique basic:filter=box:kernel=3,basic:filter=box:kernel=7 --param accel=hpsm,minmax

# 4. Sweeps on the default scene, basic box 7 (fractions and times from one counted run).
part 4 && bench sweep-eps --scene default --technique basic:filter=box:kernel=7:accel=hpsm --param hpsm_eps=1e-7,1e-6,1e-5,1e-4,1e-3
# minmax's level must be a power of two at least as wide as the footprint (8 for box 7): it refuses 2 and 4.
part 4 && bench sweep-block --scene default --technique basic:filter=box:kernel=7:accel=hpsm --param hpsm_block=2,4,8,16
part 4 && bench sweep-block-minmax --scene default --technique basic:filter=box:kernel=7:accel=minmax --param hpsm_block=8,16

# 5. PCSS against the area light. pcss gets --light-size as its light_size (bench::MatchLightSize).
if part 5; then
  for s in 0.53 3; do
    try_bench "pcss-sun$s" --light-size "$s" --scene default,overlapping-occluders \
      --technique basic,basic:filter=box:kernel=7,basic:filter=box:kernel=15,basic:filter=gathercmp:kernel=15,basic:filter=gathercmp:kernel=31,basic:filter=pcss,csm:filter=pcss,csm:filter=gathercmp:kernel=15
    # basic has only slope-scaled bias, under which a wide kernel shadows its own receiver in part;
    # csm with receiver-plane bias shows the kernels without that error.
    rp=""
    for f in hw2x2 box:kernel=7 box:kernel=15 gathercmp:kernel=15 gathercmp:kernel=31 pcss; do rp="${rp:+$rp,}csm:bias=receiver-plane:filter=$f"; done
    try_bench "pcss-rp-sun$s" --light-size "$s" --scene default,overlapping-occluders --technique "$rp"
  done
fi
# 5b. Two blocker depths over one penumbra (3-degree sun, 2 frames): the same techniques on the
#     two planks and on the low plank alone; compare their penumbra MAE. pcss_max_kernel 31 too:
#     the high plank's penumbra is wider than the default 15 texels allow.
part 5b && try_bench "pcss-planks-sun3" --frames 2 --light-size 3 --scene stacked-planks,single-plank \
  --technique basic:filter=pcss,csm:bias=receiver-plane:filter=pcss,csm:bias=receiver-plane:filter=pcss:pcss_max_kernel=31,csm:bias=receiver-plane:filter=gathercmp:kernel=15,csm:bias=receiver-plane:filter=hw2x2
# 5c. The blocker-average failure where it can happen (scene::Scene::regions of both plank
#     scenes, laid out from their geometry in scene/procedural/close-scenes.cpp): fixed kernels,
#     PCSS with the default clamp, with 31, and with 31 and the densest blocker search.
rp=""
for f in hw2x2 gathercmp:kernel=15 gathercmp:kernel=31 pcss pcss:pcss_max_kernel=31 pcss:pcss_max_kernel=31:pcss_search=16; do
  rp="${rp:+$rp,}csm:bias=receiver-plane:filter=$f"
done
part 5c && try_bench "planks-regions-sun3" --frames 2 --light-size 3 --scene stacked-planks,single-plank --technique "$rp"

/usr/bin/python3 "$ROOT/eval/experiments/techniques_v_tables.py" "$OUT"
