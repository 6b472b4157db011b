# Precompiled headers for the targets with many sources. Every translation unit of this project
# preprocesses 65,000-100,000 lines, almost all of them the standard library (<filesystem>,
# <functional>, <algorithm> through sp/rhi/rhi.h) and, in the tests, GoogleTest: parsing that once
# per target instead of once per file takes 20-40% off a test file's compile (copy-test.cpp:
# 6.8 s -> 3.9 s of CPU at -O3; DEVELOPERS.md, "Build time: precompiled headers").
#
# Only headers that no source changes with a #define before including them: no stb, tinygltf or
# nlohmann/json here. The RHI's own targets (sp_rhi_core, sp_hlsl, the backends) get them only in
# the sanitizer build (rhi/CMakeLists.txt): tests/samples' add_subdirectory test compiles the RHI
# a second time from another build directory with the normal build's flags, and ccache finds those
# objects only while the command lines match, which a precompiled header's path (inside the build
# directory) would break.
#
# ccache caches a file compiled with a precompiled header only with sloppiness pch_defines and
# time_macros (man ccache, "Precompiled headers"); ./shadowport sets them.
option(SHADOWPORT_PCH "Precompile the standard library and GoogleTest headers of the larger targets" ON)

# The standard headers most of our sources include (directly or through sp/rhi/rhi.h).
set(SP_PCH_STD <algorithm> <array> <cmath> <cstdint> <cstring> <filesystem> <functional> <map> <memory>
    <optional> <set> <stdexcept> <string> <string_view> <unordered_map> <vector>)

# sp_precompile_headers(target header...): the standard set plus the headers given.
function(sp_precompile_headers target)
  if(SHADOWPORT_PCH)
    target_precompile_headers(${target} PRIVATE ${SP_PCH_STD} ${ARGN})
  endif()
endfunction()
