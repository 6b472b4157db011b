// Immutable state objects: sampler, rasterizer, depth-stencil and blend, with D3D11's
// description structs, enum values and defaults (those of the CD3D11_*_DESC(D3D11_DEFAULT)
// helpers, so a default-constructed desc is what D3D11 uses when no state is bound).
#pragma once
#include <cfloat>
#include <sp/rhi/common.h>

namespace sp {

// D3D11_FILTER: bit 7 = comparison, bits 8-9 = reduction (min/max), low bits = min/mag/mip.
enum FILTER : uint32_t {
  FILTER_MIN_MAG_MIP_POINT = 0x0,
  FILTER_MIN_MAG_POINT_MIP_LINEAR = 0x1,
  FILTER_MIN_POINT_MAG_LINEAR_MIP_POINT = 0x4,
  FILTER_MIN_POINT_MAG_MIP_LINEAR = 0x5,
  FILTER_MIN_LINEAR_MAG_MIP_POINT = 0x10,
  FILTER_MIN_LINEAR_MAG_POINT_MIP_LINEAR = 0x11,
  FILTER_MIN_MAG_LINEAR_MIP_POINT = 0x14,
  FILTER_MIN_MAG_MIP_LINEAR = 0x15,
  FILTER_ANISOTROPIC = 0x55,
  FILTER_COMPARISON_MIN_MAG_MIP_POINT = 0x80,
  FILTER_COMPARISON_MIN_MAG_POINT_MIP_LINEAR = 0x81,
  FILTER_COMPARISON_MIN_POINT_MAG_LINEAR_MIP_POINT = 0x84,
  FILTER_COMPARISON_MIN_POINT_MAG_MIP_LINEAR = 0x85,
  FILTER_COMPARISON_MIN_LINEAR_MAG_MIP_POINT = 0x90,
  FILTER_COMPARISON_MIN_LINEAR_MAG_POINT_MIP_LINEAR = 0x91,
  FILTER_COMPARISON_MIN_MAG_LINEAR_MIP_POINT = 0x94,
  FILTER_COMPARISON_MIN_MAG_MIP_LINEAR = 0x95,
  FILTER_COMPARISON_ANISOTROPIC = 0xd5,
  FILTER_MINIMUM_MIN_MAG_MIP_POINT = 0x100,
  FILTER_MINIMUM_MIN_MAG_MIP_LINEAR = 0x115,
  FILTER_MAXIMUM_MIN_MAG_MIP_POINT = 0x180,
  FILTER_MAXIMUM_MIN_MAG_MIP_LINEAR = 0x195,
};

// Decoding helpers (D3D11_DECODE_*).
inline bool FilterIsComparison(FILTER f) { return (f & 0x180) == 0x80; }
inline bool FilterIsAnisotropic(FILTER f) { return (f & 0x40) != 0; }
inline bool FilterMinLinear(FILTER f) { return (f >> 4) & 1; }
inline bool FilterMagLinear(FILTER f) { return (f >> 2) & 1; }
inline bool FilterMipLinear(FILTER f) { return f & 1; }
inline uint32_t FilterReduction(FILTER f) { return (f >> 7) & 3; }  // 0 std, 1 cmp, 2 min, 3 max

enum TEXTURE_ADDRESS_MODE : uint32_t {
  TEXTURE_ADDRESS_WRAP = 1,
  TEXTURE_ADDRESS_MIRROR = 2,
  TEXTURE_ADDRESS_CLAMP = 3,
  TEXTURE_ADDRESS_BORDER = 4,
  TEXTURE_ADDRESS_MIRROR_ONCE = 5,
};

enum COMPARISON_FUNC : uint32_t {
  COMPARISON_NEVER = 1,
  COMPARISON_LESS = 2,
  COMPARISON_EQUAL = 3,
  COMPARISON_LESS_EQUAL = 4,
  COMPARISON_GREATER = 5,
  COMPARISON_NOT_EQUAL = 6,
  COMPARISON_GREATER_EQUAL = 7,
  COMPARISON_ALWAYS = 8,
};

struct SAMPLER_DESC {
  FILTER Filter = FILTER_MIN_MAG_MIP_LINEAR;
  TEXTURE_ADDRESS_MODE AddressU = TEXTURE_ADDRESS_CLAMP;
  TEXTURE_ADDRESS_MODE AddressV = TEXTURE_ADDRESS_CLAMP;
  TEXTURE_ADDRESS_MODE AddressW = TEXTURE_ADDRESS_CLAMP;
  float MipLODBias = 0.0f;
  uint32_t MaxAnisotropy = 1;
  COMPARISON_FUNC ComparisonFunc = COMPARISON_NEVER;
  float BorderColor[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  float MinLOD = -FLT_MAX;
  float MaxLOD = FLT_MAX;
};

enum FILL_MODE : uint32_t { FILL_WIREFRAME = 2, FILL_SOLID = 3 };
enum CULL_MODE : uint32_t { CULL_NONE = 1, CULL_FRONT = 2, CULL_BACK = 3 };

struct RASTERIZER_DESC {
  FILL_MODE FillMode = FILL_SOLID;
  CULL_MODE CullMode = CULL_BACK;
  bool FrontCounterClockwise = false;
  int32_t DepthBias = 0;
  float DepthBiasClamp = 0.0f;
  float SlopeScaledDepthBias = 0.0f;
  bool DepthClipEnable = true;
  bool ScissorEnable = false;
  bool MultisampleEnable = false;
  bool AntialiasedLineEnable = false;
};

enum DEPTH_WRITE_MASK : uint32_t { DEPTH_WRITE_MASK_ZERO = 0, DEPTH_WRITE_MASK_ALL = 1 };

enum STENCIL_OP : uint32_t {
  STENCIL_OP_KEEP = 1,
  STENCIL_OP_ZERO = 2,
  STENCIL_OP_REPLACE = 3,
  STENCIL_OP_INCR_SAT = 4,
  STENCIL_OP_DECR_SAT = 5,
  STENCIL_OP_INVERT = 6,
  STENCIL_OP_INCR = 7,
  STENCIL_OP_DECR = 8,
};

struct DEPTH_STENCILOP_DESC {
  STENCIL_OP StencilFailOp = STENCIL_OP_KEEP;
  STENCIL_OP StencilDepthFailOp = STENCIL_OP_KEEP;
  STENCIL_OP StencilPassOp = STENCIL_OP_KEEP;
  COMPARISON_FUNC StencilFunc = COMPARISON_ALWAYS;
};

struct DEPTH_STENCIL_DESC {
  bool DepthEnable = true;
  DEPTH_WRITE_MASK DepthWriteMask = DEPTH_WRITE_MASK_ALL;
  COMPARISON_FUNC DepthFunc = COMPARISON_LESS;
  bool StencilEnable = false;
  uint8_t StencilReadMask = 0xff;
  uint8_t StencilWriteMask = 0xff;
  DEPTH_STENCILOP_DESC FrontFace;
  DEPTH_STENCILOP_DESC BackFace;
};

enum BLEND : uint32_t {
  BLEND_ZERO = 1,
  BLEND_ONE = 2,
  BLEND_SRC_COLOR = 3,
  BLEND_INV_SRC_COLOR = 4,
  BLEND_SRC_ALPHA = 5,
  BLEND_INV_SRC_ALPHA = 6,
  BLEND_DEST_ALPHA = 7,
  BLEND_INV_DEST_ALPHA = 8,
  BLEND_DEST_COLOR = 9,
  BLEND_INV_DEST_COLOR = 10,
  BLEND_SRC_ALPHA_SAT = 11,
  BLEND_BLEND_FACTOR = 14,
  BLEND_INV_BLEND_FACTOR = 15,
  BLEND_SRC1_COLOR = 16,
  BLEND_INV_SRC1_COLOR = 17,
  BLEND_SRC1_ALPHA = 18,
  BLEND_INV_SRC1_ALPHA = 19,
};

enum BLEND_OP : uint32_t {
  BLEND_OP_ADD = 1,
  BLEND_OP_SUBTRACT = 2,
  BLEND_OP_REV_SUBTRACT = 3,
  BLEND_OP_MIN = 4,
  BLEND_OP_MAX = 5,
};

enum COLOR_WRITE_ENABLE : uint8_t {
  COLOR_WRITE_ENABLE_RED = 1,
  COLOR_WRITE_ENABLE_GREEN = 2,
  COLOR_WRITE_ENABLE_BLUE = 4,
  COLOR_WRITE_ENABLE_ALPHA = 8,
  COLOR_WRITE_ENABLE_ALL = 15,
};

struct RENDER_TARGET_BLEND_DESC {
  bool BlendEnable = false;
  BLEND SrcBlend = BLEND_ONE;
  BLEND DestBlend = BLEND_ZERO;
  BLEND_OP BlendOp = BLEND_OP_ADD;
  BLEND SrcBlendAlpha = BLEND_ONE;
  BLEND DestBlendAlpha = BLEND_ZERO;
  BLEND_OP BlendOpAlpha = BLEND_OP_ADD;
  uint8_t RenderTargetWriteMask = COLOR_WRITE_ENABLE_ALL;
};

inline constexpr uint32_t SIMULTANEOUS_RENDER_TARGET_COUNT = 8;

struct BLEND_DESC {
  bool AlphaToCoverageEnable = false;
  bool IndependentBlendEnable = false;  // false: RenderTarget[0] applies to all targets
  RENDER_TARGET_BLEND_DESC RenderTarget[SIMULTANEOUS_RENDER_TARGET_COUNT];
};

class SamplerState : public Object {
 public:
  const SAMPLER_DESC& GetDesc() const { return desc_; }
  void GetDesc(SAMPLER_DESC* desc) const { *desc = desc_; }  // D3D11's shape
  const char* TypeName() const override { return "SamplerState"; }

 protected:
  friend class Device;
  SamplerState(Device* device, const SAMPLER_DESC& desc) : Object(device), desc_(desc) {}

 private:
  SAMPLER_DESC desc_;
};

class RasterizerState : public Object {
 public:
  const RASTERIZER_DESC& GetDesc() const { return desc_; }
  void GetDesc(RASTERIZER_DESC* desc) const { *desc = desc_; }  // D3D11's shape
  const char* TypeName() const override { return "RasterizerState"; }

 protected:
  friend class Device;
  RasterizerState(Device* device, const RASTERIZER_DESC& desc) : Object(device), desc_(desc) {}

 private:
  RASTERIZER_DESC desc_;
};

class DepthStencilState : public Object {
 public:
  const DEPTH_STENCIL_DESC& GetDesc() const { return desc_; }
  void GetDesc(DEPTH_STENCIL_DESC* desc) const { *desc = desc_; }  // D3D11's shape
  const char* TypeName() const override { return "DepthStencilState"; }

 protected:
  friend class Device;
  DepthStencilState(Device* device, const DEPTH_STENCIL_DESC& desc) : Object(device), desc_(desc) {}

 private:
  DEPTH_STENCIL_DESC desc_;
};

class BlendState : public Object {
 public:
  const BLEND_DESC& GetDesc() const { return desc_; }
  void GetDesc(BLEND_DESC* desc) const { *desc = desc_; }  // D3D11's shape
  const char* TypeName() const override { return "BlendState"; }

 protected:
  friend class Device;
  BlendState(Device* device, const BLEND_DESC& desc) : Object(device), desc_(desc) {}

 private:
  BLEND_DESC desc_;
};

}  // namespace sp
