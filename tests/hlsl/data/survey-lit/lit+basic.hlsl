// The lit pass as techniques/renderer.cpp (Renderer::CompileLitShaders) compiles it for the basic
// technique: its lighting include first (it defines ShadowVisibility), then lit.hlsl; both are
// found through -I shaders-hlsl. On disk so that hlslc --survey can compile it from a manifest.
#include "basic/shadow.hlsli"
#include "lit.hlsl"
