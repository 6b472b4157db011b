// JSON form of ShaderBytecode reflection, shared by the blob format, hlslc's out.json and the
// shader cache (which stores extra keys such as the list of included files).
#pragma once
#include <nlohmann/json.hpp>
#include <sp/rhi/shader.h>

namespace sp {

std::string BytecodeToJson(const ShaderBytecode& b, const nlohmann::json& extra);
ShaderBytecode BytecodeFromJson(const std::string& text, std::vector<uint32_t> spirv, std::string glsl,
                                nlohmann::json* extra);

}  // namespace sp
