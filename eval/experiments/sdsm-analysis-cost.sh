#!/usr/bin/env bash
# Issue 16: the SDSM analysis passes timed against one read of the camera depth (the limit), both
# backends, 640x360 and 1280x720, medians of 20 frames after 3 warm-up frames (the first frame,
# where Mesa compiles, is its own column). Prints Markdown tables; about a minute on 2 cores.
#   eval/experiments/sdsm-analysis-cost.sh [FRAMES] [SIZES]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
SP="${SHADOWPORT:-$ROOT/build/bin/shadowport}"
"$SP" sdsm-cost --backend both --size "${2:-640x360,1280x720}" --frames "${1:-20}" --warmup 3
