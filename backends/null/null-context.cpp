// The null immediate context: the core has validated and resolved every call; nothing reaches a
// GPU. Only Map is real, because its contract (writable memory of the subresource's size, kept
// between maps) is what the core's Map/Unmap validation and the code around it can observe.
#include <cstring>

#include "null-internal.h"

namespace sp::null {
namespace {

class NullContext final : public detail::ContextBackend {
 public:
  void Draw(const detail::PipelineState&, uint32_t, const detail::DrawArgs&) override {}
  void Dispatch(const detail::PipelineState&, uint32_t, uint32_t, uint32_t, uint32_t, Buffer*, uint32_t) override {}
  void ClearRenderTargetView(RenderTargetView*, const float[4]) override {}
  void ClearDepthStencilView(DepthStencilView*, uint32_t, float, uint8_t) override {}
  void ClearUnorderedAccessView(UnorderedAccessView*, const detail::UavClearValue&) override {}
  // Copies into a staging resource are dropped too: its memory keeps what the CPU wrote, so a
  // readback shows zeros rather than anything resembling a GPU's result.
  void CopyResource(Resource*, Resource*) override {}
  void CopySubresourceRegion(Resource*, const detail::Subresource&, uint32_t, uint32_t, uint32_t, Resource*, const detail::Subresource&, const BOX&) override {}
  void UpdateSubresource(Resource*, const detail::Subresource&, const BOX&, const void*, uint32_t, uint32_t) override {}
  void GenerateMips(ShaderResourceView*) override {}
  void ResolveSubresource(Resource*, const detail::Subresource&, Resource*, const detail::Subresource&, FORMAT) override {}
  void CopyStructureCount(Buffer*, uint32_t, UnorderedAccessView*) override {}
  void SetUavCounter(UnorderedAccessView*, uint32_t) override {}

  bool Map(Resource* r, const detail::Subresource& at, MAP, uint32_t, MAPPED_SUBRESOURCE* out) override {
    NullResource& data = detail::BackendAs<NullResource>(r);
    std::vector<uint8_t>& block = data.subresources[at.index];
    if (r->GetType() == RESOURCE_DIMENSION_BUFFER) {
      block.resize(at.width);
      out->RowPitch = out->DepthPitch = at.width;
    } else {
      const TextureShape& s = static_cast<Texture*>(r)->Shape();
      out->RowPitch = at.width * GetFormatInfo(s.format).bytesPerElement;
      out->DepthPitch = out->RowPitch * at.height;
      block.resize(size_t(out->DepthPitch) * at.depth);
    }
    out->pData = block.data();
    return true;  // no GPU ever holds the resource, so MAP_FLAG_DO_NOT_WAIT never has to wait
  }
  void Unmap(Resource*, const detail::Subresource&) override {}

  void Begin(Query*) override {}
  void End(Query*) override {}
  // Results are ready at once (there is no GPU to wait for) and empty: no samples passed and every
  // timestamp is 0, so every pass measures 0 ms, which is what a device that does no work takes.
  // Disjoint stays false: reporting it would make timing code drop the frame, and code under test
  // (GPU timers) could then not be checked for its bookkeeping on a null device.
  bool GetData(Query* query, void* data, uint32_t size, uint32_t) override {
    if (!data) return true;
    std::memset(data, 0, size);
    switch (query->GetDesc().Query) {
      case QUERY_EVENT: {
        const int32_t done = 1;  // BOOL TRUE
        std::memcpy(data, &done, sizeof(done));
        break;
      }
      case QUERY_TIMESTAMP_DISJOINT: {
        QUERY_DATA_TIMESTAMP_DISJOINT dj;
        dj.Frequency = query->GetDevice()->Info().timestampFrequency;
        dj.Disjoint = false;
        std::memcpy(data, &dj, sizeof(dj));
        break;
      }
      default: break;
    }
    return true;
  }
  void Flush() override {}
  void WaitIdle() override {}
};

}  // namespace

std::unique_ptr<detail::ContextBackend> CreateNullContext() { return std::make_unique<NullContext>(); }

}  // namespace sp::null
