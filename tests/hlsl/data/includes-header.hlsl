#include "header.hlsli"
float4 main() : SV_Target { return float4(HEADER_VALUE, 0, 0, 1); }
