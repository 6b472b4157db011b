// Render-target helpers shared by the techniques (technique.h).
#include "technique.h"

namespace sp::tech {

std::vector<Ref<DepthStencilView>> MakeSliceDepthViews(Device& device, Texture2D* texture) {
  const TEXTURE2D_DESC& td = texture->GetDesc();
  std::vector<Ref<DepthStencilView>> views;
  for (uint32_t s = 0; s < td.ArraySize; ++s) {
    DEPTH_STENCIL_VIEW_DESC dd;
    dd.Format = FORMAT_D32_FLOAT;
    if (td.SampleDesc.Count > 1) {
      dd.ViewDimension = DSV_DIMENSION_TEXTURE2DMSARRAY;
      dd.Texture2DMSArray = {s, 1};
    } else {
      dd.ViewDimension = DSV_DIMENSION_TEXTURE2DARRAY;
      dd.Texture2DArray = {0, s, 1};
    }
    views.push_back(device.CreateDepthStencilView(texture, &dd));
  }
  return views;
}

}  // namespace sp::tech
