// The OpenGL 4.5 core functions the harness calls, as one table of pointers loaded through a
// proc-address function (OSMesaGetProcAddress or eglGetProcAddress: gl_context.h). Private to the
// harness: nothing here knows how the context was made.
#pragma once

#include <string>
#include <vector>

#include <GL/glcorearb.h>

namespace xshade::harness::gl {

// X(pointer type, member name); the GL entry point is "gl" followed by the member name.
#define XSHADE_GL_FUNCTIONS(X)                                           \
  /* state and queries */                                                \
  X(PFNGLGETSTRINGPROC, GetString)                                       \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                   \
  X(PFNGLGETERRORPROC, GetError)                                         \
  X(PFNGLENABLEPROC, Enable)                                             \
  X(PFNGLDISABLEPROC, Disable)                                           \
  X(PFNGLCLIPCONTROLPROC, ClipControl)                                   \
  X(PFNGLCLAMPCOLORPROC, ClampColor)                                     \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                   \
  X(PFNGLVIEWPORTPROC, Viewport)                                         \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                       \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                       \
  X(PFNGLCOLORMASKPROC, ColorMask)                                       \
  /* a draw's render state */                                            \
  X(PFNGLENABLEIPROC, Enablei)                                           \
  X(PFNGLDISABLEIPROC, Disablei)                                         \
  X(PFNGLBLENDFUNCSEPARATEIPROC, BlendFuncSeparatei)                     \
  X(PFNGLBLENDEQUATIONSEPARATEIPROC, BlendEquationSeparatei)             \
  X(PFNGLCOLORMASKIPROC, ColorMaski)                                     \
  X(PFNGLCULLFACEPROC, CullFace)                                         \
  X(PFNGLFRONTFACEPROC, FrontFace)                                       \
  X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                               \
  X(PFNGLSTENCILFUNCSEPARATEPROC, StencilFuncSeparate)                   \
  X(PFNGLSTENCILOPSEPARATEPROC, StencilOpSeparate)                       \
  X(PFNGLSTENCILMASKPROC, StencilMask)                                   \
  X(PFNGLFINISHPROC, Finish)                                             \
  /* KHR_debug */                                                        \
  X(PFNGLDEBUGMESSAGECALLBACKPROC, DebugMessageCallback)                 \
  X(PFNGLDEBUGMESSAGECONTROLPROC, DebugMessageControl)                   \
  /* textures and samplers */                                            \
  X(PFNGLCREATETEXTURESPROC, CreateTextures)                             \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                             \
  X(PFNGLTEXTURESTORAGE1DPROC, TextureStorage1D)                         \
  X(PFNGLTEXTURESTORAGE2DPROC, TextureStorage2D)                         \
  X(PFNGLTEXTURESTORAGE3DPROC, TextureStorage3D)                         \
  X(PFNGLTEXTURESTORAGE2DMULTISAMPLEPROC, TextureStorage2DMultisample)   \
  X(PFNGLTEXTURESTORAGE3DMULTISAMPLEPROC, TextureStorage3DMultisample)   \
  X(PFNGLTEXTURESUBIMAGE1DPROC, TextureSubImage1D)                       \
  X(PFNGLTEXTURESUBIMAGE2DPROC, TextureSubImage2D)                       \
  X(PFNGLTEXTURESUBIMAGE3DPROC, TextureSubImage3D)                       \
  X(PFNGLTEXTUREPARAMETERIPROC, TextureParameteri)                       \
  X(PFNGLGETTEXTUREIMAGEPROC, GetTextureImage)                           \
  X(PFNGLBINDTEXTUREUNITPROC, BindTextureUnit)                           \
  X(PFNGLCREATESAMPLERSPROC, CreateSamplers)                             \
  X(PFNGLDELETESAMPLERSPROC, DeleteSamplers)                             \
  X(PFNGLSAMPLERPARAMETERIPROC, SamplerParameteri)                       \
  X(PFNGLBINDSAMPLERPROC, BindSampler)                                   \
  /* framebuffers */                                                     \
  X(PFNGLCREATEFRAMEBUFFERSPROC, CreateFramebuffers)                     \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                     \
  X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, NamedFramebufferTexture)           \
  X(PFNGLNAMEDFRAMEBUFFERTEXTURELAYERPROC, NamedFramebufferTextureLayer) \
  X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERPROC, NamedFramebufferDrawBuffer)     \
  X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, NamedFramebufferDrawBuffers)   \
  X(PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC, NamedFramebufferReadBuffer)     \
  X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, CheckNamedFramebufferStatus)   \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                           \
  X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, ClearNamedFramebufferfv)           \
  X(PFNGLCLEARNAMEDFRAMEBUFFERFIPROC, ClearNamedFramebufferfi)           \
  /* buffers and vertex arrays */                                        \
  X(PFNGLCREATEBUFFERSPROC, CreateBuffers)                               \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                               \
  X(PFNGLNAMEDBUFFERSTORAGEPROC, NamedBufferStorage)                     \
  X(PFNGLNAMEDBUFFERDATAPROC, NamedBufferData)                           \
  X(PFNGLNAMEDBUFFERSUBDATAPROC, NamedBufferSubData)                     \
  X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                             \
  X(PFNGLCREATEVERTEXARRAYSPROC, CreateVertexArrays)                     \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                     \
  X(PFNGLVERTEXARRAYVERTEXBUFFERPROC, VertexArrayVertexBuffer)           \
  X(PFNGLVERTEXARRAYELEMENTBUFFERPROC, VertexArrayElementBuffer)         \
  X(PFNGLENABLEVERTEXARRAYATTRIBPROC, EnableVertexArrayAttrib)           \
  X(PFNGLVERTEXARRAYATTRIBFORMATPROC, VertexArrayAttribFormat)           \
  X(PFNGLVERTEXARRAYATTRIBBINDINGPROC, VertexArrayAttribBinding)         \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                           \
  X(PFNGLVERTEXATTRIB4FPROC, VertexAttrib4f)                             \
  X(PFNGLVERTEXATTRIBI4IPROC, VertexAttribI4i)                           \
  X(PFNGLVERTEXATTRIBI4UIPROC, VertexAttribI4ui)                         \
  /* shaders and programs */                                             \
  X(PFNGLCREATESHADERPROC, CreateShader)                                 \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                 \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                               \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                   \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                         \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                 \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                               \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                 \
  X(PFNGLDETACHSHADERPROC, DetachShader)                                 \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                   \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                 \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                       \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                               \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                     \
  X(PFNGLGETUNIFORMBLOCKINDEXPROC, GetUniformBlockIndex)                 \
  X(PFNGLUNIFORMBLOCKBINDINGPROC, UniformBlockBinding)                   \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                     \
  X(PFNGLPROGRAMUNIFORM1IPROC, ProgramUniform1i)                         \
  X(PFNGLGETPROGRAMINTERFACEIVPROC, GetProgramInterfaceiv)               \
  X(PFNGLGETPROGRAMRESOURCENAMEPROC, GetProgramResourceName)             \
  X(PFNGLGETPROGRAMRESOURCEIVPROC, GetProgramResourceiv)                 \
  /* drawing */                                                          \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                     \
  X(PFNGLDRAWELEMENTSPROC, DrawElements)

struct Functions {
#define XSHADE_GL_DECLARE_MEMBER(type, name) type name = nullptr;
  XSHADE_GL_FUNCTIONS(XSHADE_GL_DECLARE_MEMBER)
#undef XSHADE_GL_DECLARE_MEMBER
};

// Returns the address of a GL entry point by its full name ("glClear"), or null.
using ProcAddressFunction = void* (*)(const char* name);

// Fills every pointer of `functions` and returns the full names of those the loader did not
// find (empty when all were found).
std::vector<std::string> load_functions(Functions& functions, ProcAddressFunction get_proc_address);

// "GL_INVALID_OPERATION" for an error code of glGetError, the number in hex for others.
std::string error_name(GLenum error);

}  // namespace xshade::harness::gl
