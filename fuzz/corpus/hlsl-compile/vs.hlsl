// vs_5_0
cbuffer Camera : register(b0) { row_major float4x4 viewProj; };
struct VSIn { float3 pos : POSITION; float3 normal : NORMAL; };
struct VSOut { float4 pos : SV_Position; float3 normal : NORMAL; };
VSOut main(VSIn i) { VSOut o; o.pos = mul(float4(i.pos, 1), viewProj); o.normal = i.normal; return o; }
