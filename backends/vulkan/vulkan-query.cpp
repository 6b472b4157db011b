// D3D11 queries. OCCLUSION is counted in hardware segments (see QuerySegment): D3D11 lets
// occlusion queries nest and overlap, Vulkan allows one active per command buffer, so each
// Begin/End/submission closes the running segment and opens one shared by the queries still
// active; GetData sums a query's segments. TIMESTAMP writes into a one-query pool. Pools are reset
// on the host, so no reset command has to sit outside a render pass. EVENT and
// TIMESTAMP_DISJOINT only need to know when their batch finished.
#include <cstring>

#include "vulkan-internal.h"

namespace sp::vk {
namespace {

std::shared_ptr<QuerySegment> NewSegment(VulkanDevice* dev, VkQueryType type, const char* call) {
  VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  ci.queryType = type;
  ci.queryCount = 1;
  auto seg = std::make_shared<QuerySegment>();
  seg->dev = dev;
  seg->serial = dev->recordingSerial;
  Check(vkCreateQueryPool(dev->device, &ci, nullptr, &seg->pool), call, "query", "vkCreateQueryPool");
  vkResetQueryPool(dev->device, seg->pool, 0, 1);
  return seg;
}

}  // namespace

QuerySegment::~QuerySegment() {
  VulkanDevice* d = dev;
  VkQueryPool p = pool;
  d->Defer(serial, [d, p] { vkDestroyQueryPool(d->device, p, nullptr); });
}

std::unique_ptr<VkQueryObj> CreateQueryObj(VulkanDevice* dev, Query& query) {
  auto q = std::make_unique<VkQueryObj>();
  q->dev = dev;
  q->type = query.GetDesc().Query;
  return q;
}

VkQueryObj::~VkQueryObj() {
  if (active && dev->ctx) dev->ctx->ForgetQuery(this);
}

void VulkanContext::StartSegment() {
  if (activeQueries_.empty() || segment_) return;
  VkCommandBuffer cmd = Cmd();
  segment_ = NewSegment(dev_, VK_QUERY_TYPE_OCCLUSION, "Begin");
  vkCmdBeginQuery(cmd, segment_->pool, 0, dev_->feat.occlusionPrecise ? VK_QUERY_CONTROL_PRECISE_BIT : 0);
  for (VkQueryObj* q : activeQueries_) q->segments.push_back(segment_);
}

void VulkanContext::StopSegment() {
  if (!segment_) return;
  if (cur_) {
    EndRendering();
    vkCmdEndQuery(cur_->cmd, segment_->pool, 0);
  }
  segment_.reset();
}

void VulkanContext::ForgetQuery(VkQueryObj* q) {
  auto it = std::find(activeQueries_.begin(), activeQueries_.end(), q);
  if (it == activeQueries_.end()) return;
  StopSegment();
  activeQueries_.erase(it);
  q->active = false;
  if (cur_) StartSegment();
}

void VulkanContext::Begin(Query* query) {
  VkQueryObj& q = detail::BackendAs<VkQueryObj>(query);
  q.issued = false;
  q.active = true;
  if (q.type != QUERY_OCCLUSION) return;
  // Segments start outside rendering, so one may cover draws in several render pass instances.
  Cmd();
  StopSegment();
  q.segments.clear();
  activeQueries_.push_back(&q);
  StartSegment();
}

void VulkanContext::End(Query* query) {
  VkQueryObj& q = detail::BackendAs<VkQueryObj>(query);
  switch (q.type) {
    case QUERY_OCCLUSION:
      Cmd();
      StopSegment();
      activeQueries_.erase(std::find(activeQueries_.begin(), activeQueries_.end(), &q));
      StartSegment();
      break;
    case QUERY_TIMESTAMP: {
      if (!cur_) BeginBatch();
      q.segments.clear();
      q.segments.push_back(NewSegment(dev_, VK_QUERY_TYPE_TIMESTAMP, "End"));
      vkCmdWriteTimestamp2(cur_->cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, q.segments.back()->pool, 0);
      break;
    }
    default:
      if (!cur_) BeginBatch();
      break;
  }
  q.active = false;
  q.issued = true;
  q.endSerial = dev_->recordingSerial;
}

bool VulkanContext::GetData(Query* query, void* data, uint32_t size, uint32_t flags) {
  VkQueryObj& q = detail::BackendAs<VkQueryObj>(query);
  if (!q.issued) return false;
  if (q.endSerial >= dev_->recordingSerial) {
    if (flags & ASYNC_GETDATA_DONOTFLUSH) return false;
    Submit();
  }
  if (IsBusy(q.endSerial)) return false;
  if (!data) return true;
  switch (q.type) {
    case QUERY_EVENT: {
      uint32_t done = 1;
      std::memcpy(data, &done, 4);
      break;
    }
    case QUERY_OCCLUSION:
    case QUERY_TIMESTAMP: {
      uint64_t sum = 0;
      for (const auto& seg : q.segments) {
        uint64_t v = 0;
        Check(vkGetQueryPoolResults(dev_->device, seg->pool, 0, 1, sizeof(v), &v, sizeof(v), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
              "GetData", DescribeObject(query), "vkGetQueryPoolResults");
        sum += v;
      }
      std::memcpy(data, &sum, 8);
      break;
    }
    case QUERY_TIMESTAMP_DISJOINT: {
      QUERY_DATA_TIMESTAMP_DISJOINT d;
      d.Frequency = dev_->Info().timestampFrequency;
      d.Disjoint = false;
      std::memcpy(data, &d, sizeof(d));
      break;
    }
  }
  return true;
}

}  // namespace sp::vk
