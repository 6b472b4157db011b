// Lighting side of Sample Distribution Shadow Maps (techniques/sdsm): csm's lighting as is. The
// sdsm technique fills the same cbuffer CsmShadow: the shared light view is the SDSM light frame
// (x along the camera's view direction projected onto the light plane, origin at the camera),
// each partition is a cascade with its own scale/offset into its array slice (its box fitted to
// the analysed samples), the split distances are the partitions' and selection is by interval.
// With cull=gpu those constants are written by sdsm/fit.hlsl and copied into the constant buffer
// on the GPU; the shader cannot tell the difference.
//
// Defines: those of csm (CSM_MOMENTS and the MOMENT_* defines, or SHADOW_FILTER/SHADOW_KERNEL),
// as CsmTechnique::Defines produces them for the shared parameters.
#include "csm/shadow.hlsli"
