// A shader with a deliberate error on line 4: the toolchain must name this file and line.
float4 main(float4 p : SV_Position) : SV_Target {
  float3 c = p.xyz;
  return float4(c, missingVariable);
}
