# Every dependency comes from a Debian 12 package (see DEVELOPERS.md); nothing is downloaded.
find_package(Threads REQUIRED)
find_package(Vulkan 1.3 REQUIRED)
find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)
find_package(glslang REQUIRED)            # glslang-dev
find_package(SPIRV-Tools REQUIRED)        # spirv-tools
find_package(SPIRV-Tools-opt REQUIRED)
find_package(spirv_cross_core REQUIRED)   # libspirv-cross-c-shared-dev
find_package(spirv_cross_glsl REQUIRED)
find_package(nlohmann_json 3 REQUIRED)    # nlohmann-json3-dev
find_package(glm REQUIRED)                # libglm-dev
find_package(PkgConfig REQUIRED)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)   # libstb-dev
find_path(TINYGLTF_INCLUDE_DIR tiny_gltf.h REQUIRED)  # libtinygltf-dev
find_library(TINYGLTF_LIBRARY NAMES tinygltf libtinygltf.so.2d REQUIRED)

# glslang's headers hide the HLSL entry points unless this is defined.
add_library(sp_glslang INTERFACE)
target_link_libraries(sp_glslang INTERFACE glslang::glslang glslang::HLSL glslang::SPIRV
                      glslang::glslang-default-resource-limits SPIRV-Tools-opt SPIRV-Tools-static)
target_compile_definitions(sp_glslang INTERFACE ENABLE_HLSL)

add_library(sp_spirv_cross INTERFACE)
target_link_libraries(sp_spirv_cross INTERFACE spirv-cross-glsl spirv-cross-core)
