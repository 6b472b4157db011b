#include <sp/tech/gpu-timer.h>

#include <stdexcept>

namespace sp::tech {

GpuTimer::GpuTimer(Device& device) : device_(device) {}

Ref<Query> GpuTimer::Timestamp() {
  if (!freeTimestamps_.empty()) {
    Ref<Query> q = std::move(freeTimestamps_.back());
    freeTimestamps_.pop_back();
    return q;
  }
  QUERY_DESC d;
  d.Query = QUERY_TIMESTAMP;
  return device_.CreateQuery(d);
}

void GpuTimer::BeginFrame(DeviceContext& ctx) {
  if (inFrame_) throw std::logic_error("GpuTimer::BeginFrame: the previous frame was not ended");
  // Bound the frames in flight the way an application's swap chain would: wait for the oldest.
  while (pending_.size() >= kMaxFramesInFlight) {
    FrameTimes t;
    Frame f = std::move(pending_.front());
    pending_.pop_front();
    if (Read(ctx, f, true, &t)) ready_.push_back(std::move(t));
    Recycle(f);
  }
  current_ = Frame{};
  if (!freeDisjoint_.empty()) {
    current_.disjoint = std::move(freeDisjoint_.back());
    freeDisjoint_.pop_back();
  } else {
    QUERY_DESC d;
    d.Query = QUERY_TIMESTAMP_DISJOINT;
    current_.disjoint = device_.CreateQuery(d);
  }
  current_.begin = Timestamp();
  current_.end = Timestamp();
  ctx.Begin(current_.disjoint.get());
  ctx.End(current_.begin.get());
  inFrame_ = true;
}

void GpuTimer::EndFrame(DeviceContext& ctx) {
  if (!inFrame_) throw std::logic_error("GpuTimer::EndFrame without BeginFrame");
  for (const Pass& p : current_.passes)
    if (!p.end) throw std::logic_error("GpuTimer: pass '" + p.name + "' was not ended");
  ctx.End(current_.end.get());
  ctx.End(current_.disjoint.get());
  pending_.push_back(std::move(current_));
  inFrame_ = false;
}

void GpuTimer::Begin(DeviceContext& ctx, const std::string& pass) {
  if (!inFrame_) throw std::logic_error("GpuTimer::Begin('" + pass + "') outside a frame");
  for (const Pass& p : current_.passes)
    if (p.name == pass && !p.end) throw std::logic_error("GpuTimer: pass '" + pass + "' is already running");
  Pass p;
  p.name = pass;
  p.begin = Timestamp();
  ctx.End(p.begin.get());
  current_.passes.push_back(std::move(p));
}

void GpuTimer::End(DeviceContext& ctx, const std::string& pass) {
  for (auto it = current_.passes.rbegin(); it != current_.passes.rend(); ++it) {
    if (it->name != pass || it->end) continue;
    it->end = Timestamp();
    ctx.End(it->end.get());
    return;
  }
  throw std::logic_error("GpuTimer::End('" + pass + "') without Begin");
}

void GpuTimer::Recycle(Frame& f) {
  freeDisjoint_.push_back(std::move(f.disjoint));
  freeTimestamps_.push_back(std::move(f.begin));
  freeTimestamps_.push_back(std::move(f.end));
  for (Pass& p : f.passes) {
    freeTimestamps_.push_back(std::move(p.begin));
    freeTimestamps_.push_back(std::move(p.end));
  }
}

// Reads one frame; false when not yet complete (wait = false) or disjoint.
bool GpuTimer::Read(DeviceContext& ctx, Frame& f, bool wait, FrameTimes* out) {
  QUERY_DATA_TIMESTAMP_DISJOINT dj;
  while (!ctx.GetData(f.disjoint.get(), &dj, sizeof(dj), 0))
    if (!wait) return false;
  // The disjoint query completes with its frame, so every timestamp inside is available now.
  auto read = [&](Query* q) {
    uint64_t v = 0;
    while (!ctx.GetData(q, &v, sizeof(v), 0)) {
    }
    return v;
  };
  if (dj.Disjoint || dj.Frequency == 0) {
    ++disjoint_;
    return false;
  }
  double toMs = 1000.0 / double(dj.Frequency);
  auto span = [&](Query* a, Query* b) {
    uint64_t t0 = read(a), t1 = read(b);
    return t1 >= t0 ? double(t1 - t0) * toMs : 0.0;
  };
  FrameTimes t;
  t["total"] = span(f.begin.get(), f.end.get());
  for (const Pass& p : f.passes) t[p.name] += span(p.begin.get(), p.end.get());
  *out = std::move(t);
  return true;
}

std::vector<FrameTimes> GpuTimer::Collect(DeviceContext& ctx, bool wait) {
  while (!pending_.empty()) {
    FrameTimes t;
    Frame& f = pending_.front();
    QUERY_DATA_TIMESTAMP_DISJOINT probe;
    if (!wait && !ctx.GetData(f.disjoint.get(), &probe, sizeof(probe), 0)) break;
    if (Read(ctx, f, true, &t)) ready_.push_back(std::move(t));
    Recycle(f);
    pending_.pop_front();
  }
  std::vector<FrameTimes> out = std::move(ready_);
  ready_.clear();
  return out;
}

GpuTimer::Scope::Scope(GpuTimer* timer, DeviceContext& ctx, std::string pass) : timer_(timer), ctx_(ctx), pass_(std::move(pass)) {
  if (timer_) timer_->Begin(ctx_, pass_);
}

GpuTimer::Scope::~Scope() {
  if (timer_) timer_->End(ctx_, pass_);
}

}  // namespace sp::tech
