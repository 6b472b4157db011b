// The lit pass as techniques/renderer.cpp (Renderer::CompileLitShaders) compiles it for the sdsm
// technique: its lighting include first (it defines ShadowVisibility), then lit.hlsl; both are
// found through -I shaders-hlsl. On disk so that hlslc --survey can compile it from a manifest.
#include "sdsm/shadow.hlsli"
#include "lit.hlsl"
