#!/usr/bin/env bash
# The measurements behind docs/techniques.md, "Local lights" (issue "Techniques IV: point and spot
# lights", first part): the cube technique's two storages (planar window depth in a depth cube with
# hardware comparison; radial distance in an R32_FLOAT cube compared in the shader) at three face
# resolutions, for each point light of the point-light-room, on both backends against the Embree
# reference traced from that point light; and the same on the cube-seam scene.
#   eval/experiments/techniques-iv.sh [OUT_DIR] [WxH] [FRAMES]
# Writes OUT_DIR/<experiment>.json and prints the tables (techniques_iv_tables.py).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
OUT="${1:-$ROOT/out/techniques-iv}"
SIZE="${2:-640x360}"
FRAMES="${3:-8}"
SP="$ROOT/shadowport"
mkdir -p "$OUT"
bench() { local name="$1"; shift; "$SP" bench --backend both --size "$SIZE" --frames "$FRAMES" --out "$OUT/$name.json" "$@"; }

# 1. Storage and resolution, each point light of the room (light 0: 12 m range under the ceiling,
#    light 1: 7 m, low beside the shelf), along the room's walk.
bench cube-storage --scene point-light-room --path walk --technique cube --param storage=depth,radial \
  --param resolution=256,512,1024 --param light=0,1
# 2. The seam scene: every occluder's shadow crosses a cube-face edge (static camera).
bench cube-seam --scene cube-seam --technique cube --param storage=depth,radial --param resolution=256,512,1024

/usr/bin/python3 "$ROOT/eval/experiments/techniques_iv_tables.py" "$OUT"
