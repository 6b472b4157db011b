// Cascaded shadow maps in the style of the DirectX SDK's CascadedShadowMaps11: every cascade is a
// tile of one wide depth texture (the atlas), the pixel shader picks the cascade by the pixel's
// view-space depth (interval selection) and filters with 3x3 PCF from SampleCmpLevelZero.
// Shader Model 4 targets (vs_4_0, ps_4_0), as D3D11-era code compiled them.

#define MAX_CASCADES 4

cbuffer cbFrame : register(b0) {
  matrix g_mViewProj;             // camera: world -> clip
  matrix g_mView;                 // camera: world -> view (depth along -z, right-handed)
  matrix g_mLightViewProj[MAX_CASCADES];  // per cascade: world -> its light clip space
  float4 g_vCascadeEnd;           // view depth where each cascade ends (interval selection)
  float4 g_vToLight;              // xyz: unit vector towards the light; w: ambient
  int g_nCascades;
  float g_fTexelSize;             // 1 / atlas height: one texel of a tile in v
  int g_bVisualizeCascades;
  float g_fPad;
};

cbuffer cbShadowPass : register(b1) {
  matrix g_mShadowViewProj;       // the cascade being rendered
};

struct VS_INPUT {
  float3 vPosition : POSITION;
  float3 vNormal : NORMAL;
  float3 vColor : COLOR;
};

// Depth from the light into one tile of the atlas (the viewport selects the tile).
float4 VSShadow(VS_INPUT input) : SV_Position {
  return mul(g_mShadowViewProj, float4(input.vPosition, 1.0f));
}

struct VS_OUTPUT {
  float4 vPosition : SV_Position;
  float3 vWorld : TEXCOORD0;
  float3 vNormal : NORMAL;
  float3 vColor : COLOR;
  float fViewDepth : TEXCOORD1;
};

VS_OUTPUT VSScene(VS_INPUT input) {
  VS_OUTPUT o;
  float4 world = float4(input.vPosition, 1.0f);
  o.vPosition = mul(g_mViewProj, world);
  o.vWorld = input.vPosition;
  o.vNormal = input.vNormal;
  o.vColor = input.vColor;
  o.fViewDepth = -mul(g_mView, world).z;
  return o;
}

Texture2D g_txShadowAtlas : register(t0);
SamplerComparisonState g_samShadow : register(s0);

static const float3 kCascadeTint[MAX_CASCADES] = {
  float3(1.0f, 0.55f, 0.55f), float3(0.55f, 1.0f, 0.55f), float3(0.55f, 0.55f, 1.0f), float3(1.0f, 1.0f, 0.5f)
};

float ShadowVisibility(float3 vWorld, int iCascade) {
  float4 vLight = mul(g_mLightViewProj[iCascade], float4(vWorld, 1.0f));
  // Light clip space to the cascade's tile: tiles sit side by side along u.
  float2 vUV = vLight.xy * float2(0.5f, -0.5f) + 0.5f;
  float fTileWidth = 1.0f / g_nCascades;
  // Keep the 3x3 kernel inside the tile so it never reads a neighbour cascade.
  float fMargin = 1.5f * g_fTexelSize;
  vUV = clamp(vUV, fMargin, 1.0f - fMargin);
  vUV.x = (vUV.x + iCascade) * fTileWidth;
  float fSum = 0.0f;
  [unroll] for (int y = -1; y <= 1; ++y) {
    [unroll] for (int x = -1; x <= 1; ++x) {
      float2 vOffset = float2(x * g_fTexelSize * fTileWidth, y * g_fTexelSize);
      fSum += g_txShadowAtlas.SampleCmpLevelZero(g_samShadow, vUV + vOffset, vLight.z);
    }
  }
  return fSum / 9.0f;
}

float4 PSScene(VS_OUTPUT input) : SV_Target {
  // Interval selection: the first cascade whose far end lies beyond the pixel.
  int iCascade = 0;
  [unroll] for (int i = 0; i < MAX_CASCADES - 1; ++i) {
    if (i < g_nCascades - 1 && input.fViewDepth > g_vCascadeEnd[i]) iCascade = i + 1;
  }
  float fLit = ShadowVisibility(input.vWorld, iCascade);
  float fNdotL = saturate(dot(normalize(input.vNormal), g_vToLight.xyz));
  float fAmbient = g_vToLight.w;
  float3 vColor = input.vColor;
  if (g_bVisualizeCascades) vColor *= kCascadeTint[iCascade];
  return float4(vColor * (fAmbient + (1.0f - fAmbient) * fNdotL * fLit), 1.0f);
}
