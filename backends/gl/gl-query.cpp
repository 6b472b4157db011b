// Queries. EVENT and TIMESTAMP_DISJOINT are fences; TIMESTAMP is glQueryCounter (nanoseconds).
// OCCLUSION uses GL_SAMPLES_PASSED, of which GL allows one active query while D3D11 lets
// occlusion queries overlap: the context runs one GL query per stretch of commands between
// Begin/End calls ("segments"), and a D3D query adds up the segments it was active for.
#include <algorithm>
#include <cstring>

#include "gl-context.h"

namespace sp::gl {

struct GLQuerySegment {
  GLuint name = 0;
  ~GLQuerySegment() { glDeleteQueries(1, &name); }
};

namespace {

bool FenceSignaled(GLsync fence, uint32_t flags) {
  GLenum r = glClientWaitSync(fence, (flags & ASYNC_GETDATA_DONOTFLUSH) ? 0 : GL_SYNC_FLUSH_COMMANDS_BIT, 0);
  return r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED;
}

}  // namespace

GLQuery::~GLQuery() {
  dev->MakeCurrent();
  if (GLContext* ctx = dev->context()) {
    auto& active = ctx->activeOcclusion;
    if (std::find(active.begin(), active.end(), this) != active.end()) {
      active.erase(std::remove(active.begin(), active.end(), this), active.end());
      ctx->SplitOcclusionSegment();
    }
  }
  segments.clear();
  if (name) glDeleteQueries(1, &name);
  if (fence) glDeleteSync(fence);
}

std::unique_ptr<detail::BackendObject> CreateGLQuery(GLDevice& dev, Query& query) {
  auto q = std::make_unique<GLQuery>();
  q->dev = &dev;
  q->type = query.GetDesc().Query;
  if (q->type == QUERY_TIMESTAMP) glCreateQueries(GL_TIMESTAMP, 1, &q->name);
  return q;
}

void GLContext::SplitOcclusionSegment() {
  if (currentSegment) glEndQuery(GL_SAMPLES_PASSED);
  currentSegment.reset();
  if (activeOcclusion.empty()) return;
  currentSegment = std::make_shared<GLQuerySegment>();
  glCreateQueries(GL_SAMPLES_PASSED, 1, &currentSegment->name);
  glBeginQuery(GL_SAMPLES_PASSED, currentSegment->name);
  for (GLQuery* q : activeOcclusion) q->segments.push_back(currentSegment);
}

void GLContext::Begin(Query* query) {
  dev_.MakeCurrent();
  GLQuery& q = detail::BackendAs<GLQuery>(query);
  q.ended = false;
  if (q.type == QUERY_OCCLUSION) {
    q.segments.clear();
    activeOcclusion.push_back(&q);
    SplitOcclusionSegment();
  }
}

void GLContext::End(Query* query) {
  dev_.MakeCurrent();
  GLQuery& q = detail::BackendAs<GLQuery>(query);
  switch (q.type) {
    case QUERY_OCCLUSION:
      activeOcclusion.erase(std::remove(activeOcclusion.begin(), activeOcclusion.end(), &q), activeOcclusion.end());
      SplitOcclusionSegment();
      break;
    case QUERY_TIMESTAMP:
      glQueryCounter(q.name, GL_TIMESTAMP);
      break;
    default:
      if (q.fence) glDeleteSync(q.fence);
      q.fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
      break;
  }
  q.ended = true;
}

bool GLContext::GetData(Query* query, void* data, uint32_t size, uint32_t flags) {
  dev_.MakeCurrent();
  GLQuery& q = detail::BackendAs<GLQuery>(query);
  if (!q.ended) return false;
  switch (q.type) {
    case QUERY_EVENT: {
      if (!FenceSignaled(q.fence, flags)) return false;
      const uint32_t done = 1;  // BOOL TRUE
      if (data) std::memcpy(data, &done, sizeof(done));
      return true;
    }
    case QUERY_TIMESTAMP_DISJOINT: {
      if (!FenceSignaled(q.fence, flags)) return false;
      QUERY_DATA_TIMESTAMP_DISJOINT d;
      d.Frequency = dev_.info().timestampFrequency;
      d.Disjoint = false;  // GL_TIMESTAMP is one monotonic clock
      if (data) std::memcpy(data, &d, sizeof(d));
      return true;
    }
    case QUERY_TIMESTAMP: {
      GLint available = 0;
      glGetQueryObjectiv(q.name, GL_QUERY_RESULT_AVAILABLE, &available);
      if (!available) {
        if (!(flags & ASYNC_GETDATA_DONOTFLUSH)) glFlush();
        return false;
      }
      GLuint64 t = 0;
      glGetQueryObjectui64v(q.name, GL_QUERY_RESULT, &t);
      if (data) std::memcpy(data, &t, sizeof(t));
      return true;
    }
    case QUERY_OCCLUSION: {
      uint64_t samples = 0;
      for (const auto& seg : q.segments) {
        GLint available = 0;
        glGetQueryObjectiv(seg->name, GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available) {
          if (!(flags & ASYNC_GETDATA_DONOTFLUSH)) glFlush();
          return false;
        }
        GLuint64 n = 0;
        glGetQueryObjectui64v(seg->name, GL_QUERY_RESULT, &n);
        samples += n;
      }
      if (data) std::memcpy(data, &samples, sizeof(samples));
      return true;
    }
  }
  return false;
}

}  // namespace sp::gl
