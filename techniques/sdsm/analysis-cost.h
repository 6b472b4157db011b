// Sample Distribution Shadow Maps: the time of each analysis pass against the physical limit of
// reading the camera depth once (issue 16). One measurement runs, on one device, per frame: the
// limit passes (shaders-hlsl/sdsm/read-limit.hlsl), an empty dispatch, then every analysis pass
// separately, then the whole analysis as the technique runs it, each bracketed by its own
// timestamp pair. A synthetic depth buffer stands in for a camera pre-pass: a ground plane seen
// from 20 m up with rows of pillars and sky above the horizon, so partitions, histogram and
// bounds see a scene-like distribution, and the run needs no scene or renderer.
#pragma once
#include <sp/rhi/rhi.h>
#include <string>
#include <vector>

#include "sdsm/depth-analysis.h"

namespace sp::tech::sdsm {

struct PassCost {
  std::string name;
  double medianMs = 0;  // over the measured frames (after warm-up)
  double firstMs = 0;   // the first frame's time (Mesa compiles shader variants on first use)
};

struct AnalysisCost {
  uint32_t width = 0, height = 0, frames = 0;
  double createMs = 0;            // CPU time to create the analysis' shaders (HLSL -> SPIR-V/GLSL -> JIT)
  double limitMs = 0;             // the faster of the two limit passes, medians
  std::vector<PassCost> passes;   // in run order; sums as extra rows
  const PassCost* find(const std::string& name) const;
};

// frames: measured frames after `warmup` unmeasured ones (at least 1 each); both >= 1. Throws
// std::invalid_argument naming the parameter otherwise.
AnalysisCost MeasureAnalysisCost(Device& device, uint32_t width, uint32_t height, uint32_t frames, uint32_t warmup);

// Markdown rows: pass | median ms | ratio to the limit | first frame ms, with "reduction +
// histogram" and "whole analysis" rows.
std::string FormatAnalysisCost(const AnalysisCost& cost, const std::string& backend);

// The synthetic camera depth (device depth, 1 = sky) of MeasureAnalysisCost and the frame it was
// made with.
std::vector<float> SyntheticCameraDepth(uint32_t width, uint32_t height, AnalysisFrame* frame);

}  // namespace sp::tech::sdsm
