// Colour helpers. Everything in the library is linear; the harness encodes sRGB when it writes a PNG.
#ifndef XSHADE_COLOR_HLSL
#define XSHADE_COLOR_HLSL

// Rec. 709 luminance of a linear colour.
float luminance(float3 linear_rgb) { return dot(linear_rgb, float3(0.2126, 0.7152, 0.0722)); }

#endif
