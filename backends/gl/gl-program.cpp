// Shaders: one separable program per shader (glCreateShaderProgramv), combined per draw into
// program pipelines by the context. A GLSL compile or link failure is an sp::Error naming the
// shader, with the driver's log. The GLSL and its variants come made with the bytecode
// (rhi/src/hlsl/target-glsl.cpp).
#include <cstring>

#include "gl-context.h"

namespace sp::gl {
namespace {

GLenum StageType(ShaderStage s) {
  switch (s) {
    case ShaderStage::Vertex: return GL_VERTEX_SHADER;
    case ShaderStage::Pixel: return GL_FRAGMENT_SHADER;
    case ShaderStage::Geometry: return GL_GEOMETRY_SHADER;
    case ShaderStage::Compute: return GL_COMPUTE_SHADER;
  }
  return GL_VERTEX_SHADER;
}

std::string CreateCall(ShaderStage s) {
  switch (s) {
    case ShaderStage::Vertex: return "CreateVertexShader";
    case ShaderStage::Pixel: return "CreatePixelShader";
    case ShaderStage::Geometry: return "CreateGeometryShader";
    case ShaderStage::Compute: return "CreateComputeShader";
  }
  return "CreateShader";
}

GLuint Compile(GLDevice& dev, const Shader& shader, const std::string& glsl, const std::string& call) {
  const char* src = glsl.c_str();
  // The failure is reported as an exception with the log; the driver's debug message about it
  // must not count as a validation error on top.
  dev.suppressDebugMessages = true;
  GLuint program = glCreateShaderProgramv(StageType(shader.Stage()), 1, &src);
  GLint linked = GL_FALSE;
  if (program) glGetProgramiv(program, GL_LINK_STATUS, &linked);
  dev.suppressDebugMessages = false;
  if (linked) return program;
  std::string log = "(no log)";
  if (program) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    if (length > 1) {
      log.assign(size_t(length), '\0');
      glGetProgramInfoLog(program, length, nullptr, log.data());
      log.resize(std::strlen(log.c_str()));
    }
    glDeleteProgram(program);
  }
  const std::string& name = shader.Bytecode().sourceName.empty() ? shader.Describe() : shader.Bytecode().sourceName;
  ThrowError(ErrorId::SHADER_COMPILE_FAILED, call, name, "the OpenGL driver rejected the generated GLSL: " + log);
}

}  // namespace

GLShader::~GLShader() {
  dev->MakeCurrent();
  dev->DeleteProgramPipeline(computePipeline);
  dev->DeleteProgram(program);
  dev->DeleteProgram(dualSourceProgram);
}

std::unique_ptr<detail::BackendObject> CreateGLShader(GLDevice& dev, Shader& shader) {
  auto s = std::make_unique<GLShader>();
  s->dev = &dev;
  s->owner = &shader;
  const std::string call = CreateCall(shader.Stage());
  if (shader.Bytecode().glsl.empty())
    ThrowError(ErrorId::SHADER_COMPILE_FAILED, call, shader.Bytecode().sourceName, "the bytecode carries no GLSL for the OpenGL backend");
  s->program = Compile(dev, shader, shader.Bytecode().glsl, call);
  s->writesTarget1 = !detail::TargetsOf(shader.Bytecode()).gl.dualSourceGlsl.empty();
  if (shader.Stage() == ShaderStage::Compute) {
    glCreateProgramPipelines(1, &s->computePipeline);
    glUseProgramStages(s->computePipeline, GL_COMPUTE_SHADER_BIT, s->program);
  }
  return s;
}

// The program of the GLSL variant with SV_Target1 at location 0, index 1 (pixel shaders writing
// SV_Target1 only). Created on first use, when a blend state asks for dual-source blending.
GLuint DualSourceProgram(GLDevice& dev, GLShader& shader) {
  if (shader.dualSourceProgram) return shader.dualSourceProgram;
  const std::string& glsl = detail::TargetsOf(shader.owner->Bytecode()).gl.dualSourceGlsl;
  shader.dualSourceProgram = Compile(dev, *shader.owner, glsl, "Draw (dual-source blending)");
  return shader.dualSourceProgram;
}

}  // namespace sp::gl
