#include "sdsm/analysis-readback.h"

#include <cstring>
#include <stdexcept>

namespace sp::tech::sdsm {

AnalysisReadback::AnalysisReadback(Device& device, ReadbackMode mode, uint32_t latency, uint32_t bytes)
    : device_(device), mode_(mode), latency_(mode == ReadbackMode::Latent ? latency : 0), bytes_(bytes) {
  if (mode == ReadbackMode::Latent && latency < 1) throw std::invalid_argument("AnalysisReadback: Latent mode needs a latency of at least 1 frame");
  if (bytes < kResultBytes || bytes % 4 != 0) throw std::invalid_argument("AnalysisReadback: bytes must be a multiple of 4, at least kResultBytes");
  size_t slots = mode == ReadbackMode::None ? 0 : mode == ReadbackMode::Stall ? 1 : latency_ + 1;
  for (size_t i = 0; i < slots; ++i) {
    BUFFER_DESC d;
    d.ByteWidth = bytes;
    d.Usage = USAGE_STAGING;
    d.CPUAccessFlags = CPU_ACCESS_READ;
    ring_.push_back(device.CreateBuffer(d));
    ring_.back()->SetDebugName("sdsm analysis readback " + std::to_string(i));
  }
}

void AnalysisReadback::Read(DeviceContext& ctx, Buffer* staging, int64_t capture) {
  MAPPED_SUBRESOURCE m;
  ctx.Map(staging, 0, MAP_READ, 0, &m);
  latestWords_.resize(bytes_ / 4);
  std::memcpy(latestWords_.data(), m.pData, bytes_);
  ctx.Unmap(staging, 0);
  latest_ = DecodeResults(latestWords_.data());
  latestCapture_ = capture;
}

void AnalysisReadback::Capture(DeviceContext& ctx, Buffer* source) {
  if (source->GetDesc().ByteWidth != bytes_) throw std::invalid_argument("AnalysisReadback::Capture: source size differs from the readback size");
  int64_t capture = captures_++;
  if (mode_ == ReadbackMode::None) return;
  Buffer* slot = ring_[size_t(capture % int64_t(ring_.size()))].get();
  ctx.CopyResource(slot, source);
  if (mode_ == ReadbackMode::Stall) {
    Read(ctx, slot, capture);
    return;
  }
  // The slot written `latency` captures ago is the one after this one in the ring.
  int64_t old = capture - int64_t(latency_);
  if (old >= 0) Read(ctx, ring_[size_t(old % int64_t(ring_.size()))].get(), old);
}

}  // namespace sp::tech::sdsm
