// An FX11 effect wrapping the same shaders.
#include "Shadows.hlsl"

RasterizerState rsNoCull { CullMode = NONE; DepthBias = 100; SlopeScaledDepthBias = 2.0; };
DepthStencilState dsLessEqual { DepthEnable = TRUE; DepthFunc = LESS_EQUAL; };

float4 TintPS(VSOut i, uniform float amount) : SV_Target { return ShadowPS(i) * amount; }

technique11 RenderShadows {
  pass P0 {
    SetVertexShader(CompileShader(vs_5_0, QuadVS()));
    SetGeometryShader(NULL);
    SetPixelShader(CompileShader(ps_5_0, TintPS(0.5)));
    SetRasterizerState(rsNoCull);
    SetDepthStencilState(dsLessEqual, 0);
  }
}
