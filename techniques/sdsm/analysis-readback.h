// Sample Distribution Shadow Maps: getting the analysis results to the CPU (for shadow matrices
// fitted to the analysed bounds), in the three ways a D3D11 renderer can:
//   None    nothing is read; the technique fits conservative bounds (FrustumSliceBounds) and
//           relies on GPU-side use of the results (culling);
//   Stall   copy into a staging buffer and Map(READ) it at once: this frame's results, at the price
//           of waiting for the GPU to finish the analysis (a pipeline bubble each frame);
//   Latent  a ring of `latency` + 1 staging buffers: each frame copies into the next one and maps
//           the one written `latency` frames earlier, which the GPU has normally finished, so the
//           map does not wait; the results are `latency` frames old.
#pragma once
#include <optional>
#include <sp/rhi/rhi.h>
#include <vector>

#include "sdsm/analysis-frame.h"

namespace sp::tech::sdsm {

enum class ReadbackMode { None, Stall, Latent };

class AnalysisReadback {
 public:
  // latency: frames between a capture and its results in Latent mode (>= 1; ignored otherwise).
  // bytes: the size of the buffers captured (the analysis results by default).
  AnalysisReadback(Device& device, ReadbackMode mode, uint32_t latency = 2, uint32_t bytes = kResultBytes);

  // Once per frame, after the passes that write `source`: copies it and, per mode, makes older or
  // current results available through Latest().
  void Capture(DeviceContext& ctx, Buffer* source);

  // The newest results read so far (none in None mode, and in Latent mode for the first
  // `latency` captures).
  const std::optional<AnalysisResults>& Latest() const { return latest_; }
  // Its raw words (bytes / 4 of them); empty when there is none.
  const std::vector<uint32_t>& LatestWords() const { return latestWords_; }
  // Capture number (0 = the first Capture) the latest results come from; -1 when none.
  int64_t LatestCapture() const { return latestCapture_; }
  int64_t Captures() const { return captures_; }
  ReadbackMode mode() const { return mode_; }
  uint32_t latency() const { return latency_; }

 private:
  void Read(DeviceContext& ctx, Buffer* staging, int64_t capture);

  Device& device_;
  ReadbackMode mode_;
  uint32_t latency_, bytes_;
  std::vector<Ref<Buffer>> ring_;
  int64_t captures_ = 0, latestCapture_ = -1;
  std::optional<AnalysisResults> latest_;
  std::vector<uint32_t> latestWords_;
};

}  // namespace sp::tech::sdsm
