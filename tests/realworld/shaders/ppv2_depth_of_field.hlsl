// Unity Post Processing v2's depth of field, its source unchanged (Builtins/DepthOfField.hlsl of
// the Unity-Technologies/PostProcessing repository, found through the shader folders), run as
// xshade passes in the order PPv2's DepthOfField.cs renders them: the circle of confusion from
// the depth, the half-resolution prefilter, the bokeh gather with the medium kernel, the tent
// postfilter and the combine over the full-resolution source. The temporal CoC filter (pass 1)
// is left out: it needs a history and motion vectors, which a single still frame has not.
//
// What Unity's D3D11 build defines: the API, and shader model 5 for the prefilter's Gather.
#define SHADER_API_D3D11 1
#define SHADER_TARGET 50
#define KERNEL_MEDIUM

#pragma vertex VertDefault
#pragma pass coc        FragCoC      scale=full _CameraDepthTexture=scene.depth
#pragma pass prefilter  FragPrefilter scale=half _MainTex=scene.color _CoCTex=coc
#pragma pass bokeh      FragBlur     scale=half _MainTex=prefilter
#pragma pass postfilter FragPostBlur scale=half _MainTex=bokeh
#pragma pass combine    FragCombine  scale=full _MainTex=scene.color _CoCTex=coc _DepthOfFieldTex=postfilter

#include "Packages/com.unity.postprocessing/PostProcessing/Shaders/Builtins/DepthOfField.hlsl"
