// An #include inside a pass: the block is hidden around the #line directives, so glslang still
// reports the error in PSBroken at its own line (10).
float4 PS() : SV_Target { return 1; }
technique11 T {
    pass P {
#include "pass-body.fxh"
        SetRasterizerState(NULL);
    }
}
float4 PSBroken() : SV_Target { return undeclared; }
