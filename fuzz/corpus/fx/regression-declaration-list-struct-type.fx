// An effect file: the technique's CompileShader calls name the entry points and their targets,
// including one (DebugPS) whose signature alone would not say it is a pixel shader, and one
// (TintPS) given a uniform argument, which the report shows.
float4x4 worldViewProj;
float4 color;

struct VSOut {
  float4 pos : SV_Position;
};

VSOut SceneVS(float3 pos : POSITION) {
  VSOut o;
  o.pos = mul(worldViewProj, float4(pos, 1.0));
  return o;
}

float4 ScenePS,VSOut i) : SV_Target { return color; }

float4 DebugPS(VSOut i) : COLOR0 { return float4(1.0, 0.0, 1.0, 1.0); }

float4 TintPS(VSOut i, uniform bool strong) : SV_Target { return strong ? color : color * 0.5; }

// Not named by any technique: an effect's entry points are the ones its passes compile.
float4 UnusedPS(VSOut i) : SV_Target { return 0; }

technique11 Scene {
  pass P0 {
    SetVertexShader(CompileShader(vs_5_0, SceneVS()));
    SetGeometryShader(NULL);
    SetPixelShader(CompileShader(ps_5_0, ScenePS()));
  }
  pass Debug {
    SetVertexShader(CompileShader(vs_4_0, SceneVS()));
    SetPixelShader(CompileShader(ps_4_0, DebugPS()));
  }
  pass Tinted {
    SetVertexShader(CompileShader(vs_5_0, SceneVS()));
    SetPixelShader(CompileShader(ps_5_0, TintPS(true)));
  }
}
