// Every kind of effect construct, for the parsing tests in tests/hlsl/effect-test.cpp.
#include "states-common.fxh"

SamplerComparisonState samShadow : register(s2)
{
    Filter = COMPARISON_MIN_MAG_LINEAR_MIP_POINT;
    AddressU = BORDER;
    AddressV = Border;
    AddressW = clamp;
    ComparisonFunc = LESS_EQUAL;
    BorderColor = float4(1, 0.5, 0.25, 0);
    MaxAnisotropy = 4;
    MipLODBias = -1.5;
    MinLOD = 0;
    MaxLOD = 3.0f;
};
SamplerState samDefault;

RasterizerState rsWire < string Note = "annotated"; >
{
    FillMode = WIREFRAME;
    CullMode = none;
    FrontCounterClockwise = TRUE;
    DepthBias = -5;
    DepthBiasClamp = 0.25;
    SlopeScaledDepthBias = 2.0f;
    DepthClipEnable = false;
    ScissorEnable = 1;
    MultisampleEnable = TRUE;
    AntialiasedLineEnable = TRUE;
};

DepthStencilState dsStencil
{
    DepthEnable = TRUE;
    DepthWriteMask = ALL;
    DepthFunc = GREATER_EQUAL;
    StencilEnable = TRUE;
    StencilReadMask = 0x0F;
    StencilWriteMask = 0xF0;
    FrontFaceStencilFail = KEEP;
    FrontFaceStencilDepthFail = INCR_SAT;
    FrontFaceStencilPass = REPLACE;
    FrontFaceStencilFunc = EQUAL;
    BackFaceStencilFail = ZERO;
    BackFaceStencilDepthFail = DECR;
    BackFaceStencilPass = INVERT;
    BackFaceStencilFunc = NOT_EQUAL;
};

BlendState bsAlpha
{
    AlphaToCoverageEnable = FALSE;
    BlendEnable[0] = TRUE;
    SrcBlend = SRC_ALPHA;
    DestBlend = INV_SRC_ALPHA;
    BlendOp = REV_SUBTRACT;
    SrcBlendAlpha = ZERO;
    DestBlendAlpha = INV_DEST_ALPHA;
    BlendOpAlpha = MAX;
    RenderTargetWriteMask[0] = 0x07;
};
BlendState bsDefault {};

Texture2D<float> g_shadow : register(t2);

float4 VS(float4 p : POSITION) : SV_Position { return p * SCALE; }
float4 PS(float4 p : SV_Position, uniform bool useTex, uniform float k) : SV_Target
{
    return useTex ? g_tex.Sample(samLinear, p.xy) * k : g_shadow.SampleCmp(samShadow, p.xy, 0.5).xxxx;
}
[numthreads(8, 1, 1)] void CS(uint3 id : SV_DispatchThreadID) {}

VertexShader vsMain = CompileShader(vs_4_0, VS());
PixelShader psNone = NULL;
ComputeShader csMain = CompileShader(cs_5_0, CS());

fxgroup Lighting
{
    technique11 Lit
    {
        pass P0
        {
            SetVertexShader(vsMain);
            SetPixelShader(CompileShader(ps_5_0, PS(true, 2.0)));
            SetRasterizerState(rsWire);
            SetDepthStencilState(dsStencil, 0x80);
            SetBlendState(bsAlpha, float4(0.5, 0.25, 1, 0), 0x0000000F);
        }
        pass P1
        {
            SetPixelShader(psNone);
            SetBlendState(bsDefault, float4(1, 1, 1, 1), 0xFFFFFFFF);
        }
    }
}

technique10 Shadow < string Purpose = "shadow map"; >
{
    pass < int order = 1; >
    {
        SetVertexShader(CompileShader(vs_5_0, VS()));
        SetPixelShader(CompileShader(ps_4_0, PS(false, 1)));
    }
}

technique Compute
{
    pass Main { SetComputeShader(csMain); }
}
