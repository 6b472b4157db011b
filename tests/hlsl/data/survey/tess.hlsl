// Hull and domain shaders: found from their attributes, and reported as not supported (their targets fail).
struct CP { float4 pos : POSITION; };
struct PatchTess { float edges[3] : SV_TessFactor; float inside : SV_InsideTessFactor; };
PatchTess ConstHS(InputPatch<CP, 3> p) { PatchTess t; t.edges[0]=t.edges[1]=t.edges[2]=1; t.inside=1; return t; }
[domain("tri")]
[partitioning("integer")]
[outputtopology("triangle_cw")]
[outputcontrolpoints(3)]
[patchconstantfunc("ConstHS")]
CP MainHS(InputPatch<CP, 3> p, uint i : SV_OutputControlPointID) { return p[i]; }
[domain("tri")]
float4 MainDS(PatchTess t, float3 uvw : SV_DomainLocation, const OutputPatch<CP, 3> p) : SV_Position { return p[0].pos * uvw.x; }
