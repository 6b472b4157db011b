// Two techniques for tests/hlsl/effect-test.cpp (drawn on both backends) and the hlslc --fx ctest:
// "Add" blends additively, "CullWrap" culls front faces and samples with a wrapping sampler.
cbuffer PerDraw : register(b0) { float4 g_color; };
Texture2D g_tex : register(t0);
float g_unused < string UIName = "Unused"; float UIMin = 0.0; > = 1;

SamplerState samWrap : register(s0) { Filter = MIN_MAG_MIP_POINT; AddressU = Wrap; AddressV = WRAP; };

RasterizerState rsCullFront { CullMode = Front; FillMode = SOLID; DepthBias = 10; };
DepthStencilState dsOff { DepthEnable = FALSE; DepthWriteMask = ZERO; DepthFunc = LESS_EQUAL; };
BlendState bsAdd
{
    BlendEnable[0] = TRUE;
    SrcBlend = ONE;
    DestBlend = ONE;
    BlendOp = ADD;
    SrcBlendAlpha = ONE;
    DestBlendAlpha = ONE;
    RenderTargetWriteMask[0] = 0x0F;
};

// A full-screen triangle, clockwise on screen (a front face in D3D11) or counter-clockwise.
float4 VSFull(uint id : SV_VertexID, uniform bool clockwise) : SV_Position
{
    float2 p[3] = { float2(-1, -1), float2(-1, 3), float2(3, -1) };
    uint i = clockwise ? id : 2 - id;
    return float4(p[i], 0.5, 1);
}

float4 PSColor(float4 pos : SV_Position, uniform float scale) : SV_Target { return g_color * scale; }

// Texel (x, y) of a 4x4 texture at pixel (x, y), wrapping every 4 pixels.
float4 PSWrap(float4 pos : SV_Position) : SV_Target { return g_tex.Sample(samWrap, pos.xy / 4.0); }

VertexShader vsBack = CompileShader(vs_5_0, VSFull(false));

technique11 Add
{
    pass P0
    {
        SetVertexShader(CompileShader(vs_5_0, VSFull(true)));
        SetGeometryShader(NULL);
        SetPixelShader(CompileShader(ps_5_0, PSColor(0.5)));
        SetRasterizerState(NULL);
        SetDepthStencilState(dsOff, 0);
        SetBlendState(bsAdd, float4(0, 0, 0, 0), 0xFFFFFFFF);
    }
}

technique11 CullWrap
{
    pass Front
    {
        SetVertexShader(CompileShader(vs_5_0, VSFull(true)));
        SetPixelShader(CompileShader(ps_5_0, PSWrap()));
        SetRasterizerState(rsCullFront);
        SetDepthStencilState(dsOff, 3);
        SetBlendState(NULL, float4(1, 1, 1, 1), 0xFFFFFFFF);
    }
    pass Back
    {
        SetVertexShader(vsBack);
        SetPixelShader(CompileShader(ps_5_0, PSWrap()));
        SetRasterizerState(rsCullFront);
    }
}
