// GPU time per named pass, from D3D11 timestamp queries: one TIMESTAMP_DISJOINT query brackets a
// frame, a pair of TIMESTAMP queries brackets each pass and the whole frame. Results arrive some
// frames later, as on any GPU; the timer keeps at most kMaxFramesInFlight frames unread and waits
// for the oldest when a new frame would exceed that (an application's frame latency limit).
//
// Offered to techniques through FrameInputs::timer (null when nobody measures), so a technique
// times its own passes: `GpuTimer::Scope s(frame.timer, ctx, "shadow");`. A pass name used several
// times in a frame (a cascade loop) sums. The renderer times "lit"; `total` is the whole frame.
#pragma once
#include <deque>
#include <map>
#include <sp/rhi/rhi.h>
#include <string>
#include <vector>

namespace sp::tech {

// Milliseconds per pass name, plus "total" for the frame.
using FrameTimes = std::map<std::string, double>;

class GpuTimer {
 public:
  static constexpr size_t kMaxFramesInFlight = 3;

  explicit GpuTimer(Device& device);

  void BeginFrame(DeviceContext& ctx);
  void EndFrame(DeviceContext& ctx);
  // Between BeginFrame and EndFrame; passes may follow each other but not nest under one name.
  void Begin(DeviceContext& ctx, const std::string& pass);
  void End(DeviceContext& ctx, const std::string& pass);

  // Frames whose queries have completed, oldest first, each returned once. wait = true blocks until
  // every ended frame is read (after the last frame of a measurement). Frames the driver reports as
  // disjoint (clock changed mid-frame) are dropped and counted in DisjointFrames().
  std::vector<FrameTimes> Collect(DeviceContext& ctx, bool wait);
  uint64_t DisjointFrames() const { return disjoint_; }

  // Times one pass for the lifetime of the scope; does nothing when timer is null.
  class Scope {
   public:
    Scope(GpuTimer* timer, DeviceContext& ctx, std::string pass);
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    GpuTimer* timer_;
    DeviceContext& ctx_;
    std::string pass_;
  };

 private:
  struct Pass {
    std::string name;
    Ref<Query> begin, end;
  };
  struct Frame {
    Ref<Query> disjoint, begin, end;
    std::vector<Pass> passes;
  };
  Ref<Query> Timestamp();
  void Recycle(Frame& f);
  bool Read(DeviceContext& ctx, Frame& f, bool wait, FrameTimes* out);

  Device& device_;
  bool inFrame_ = false;
  Frame current_;
  std::deque<Frame> pending_;
  std::vector<FrameTimes> ready_;
  std::vector<Ref<Query>> freeTimestamps_, freeDisjoint_;
  uint64_t disjoint_ = 0;
};

}  // namespace sp::tech
