# Every dependency comes from a Debian 12 package (see DEVELOPERS.md); nothing is downloaded.
# cmake/ShadowPortConfig.cmake.in finds the same packages for users of the installed library:
# keep the two lists in step.
find_package(Threads REQUIRED)
find_package(Vulkan 1.3 REQUIRED)                      # libvulkan-dev
find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)    # libopengl-dev, libegl-dev
find_package(glslang REQUIRED)                         # glslang-dev (+ glslang-tools, named by its package)
find_package(SPIRV-Tools REQUIRED)                     # spirv-tools
find_package(SPIRV-Tools-opt REQUIRED)
find_package(spirv_cross_core REQUIRED)                # libspirv-cross-c-shared-dev
find_package(spirv_cross_glsl REQUIRED)
find_package(nlohmann_json 3 REQUIRED)                 # nlohmann-json3-dev
find_package(glm REQUIRED)                             # libglm-dev
find_package(PkgConfig REQUIRED)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)   # libstb-dev (CLI, lab and tests only)
find_path(TINYGLTF_INCLUDE_DIR tiny_gltf.h REQUIRED)  # libtinygltf-dev
find_library(TINYGLTF_LIBRARY NAMES tinygltf libtinygltf.so.2d REQUIRED)

# The toolchain's libraries, linked by name rather than through an interface target of ours so
# that the exported ShadowPort::rhi carries them as plain usage requirements.
set(SP_GLSLANG_LIBRARIES glslang::glslang glslang::HLSL glslang::SPIRV glslang::glslang-default-resource-limits
    SPIRV-Tools-opt SPIRV-Tools-static)
set(SP_SPIRV_CROSS_LIBRARIES spirv-cross-glsl spirv-cross-core)
# glslang's headers hide the HLSL entry points unless this is defined.
set(SP_GLSLANG_DEFINITIONS ENABLE_HLSL)
