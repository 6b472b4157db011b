# The samples, tested as users get them: built from the installed package (find_package) and
# once through add_subdirectory, run on both backends, and their pictures checked against a CPU
# ray trace of the same scene (check_sample_image.py).
set(SP_SAMPLES_OUT ${PROJECT_BINARY_DIR}/test-output/samples)

add_test(NAME samples.build_against_installed_package
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/samples/build-installed.sh ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR})
set_tests_properties(samples.build_against_installed_package PROPERTIES FIXTURES_SETUP sp_samples_installed TIMEOUT 900)

# The checker's own test: a picture of the scene lit from elsewhere must fail it.
add_test(NAME samples.check_rejects_a_wrong_picture
  COMMAND bash -c "mkdir -p \"$2\" && \"$0\" --backend vulkan --size 128 --out \"$2/wrong-light.png\" && sed 's/\"to_light\": \\[[^]]*\\]/\"to_light\": [-0.4, 0.6, 0.6]/' \"$3\" > \"$2/wrong-light.json\" && ! ${SP_REPORT_PYTHON} \"$1\" \"$2/wrong-light.json\" \"$2/wrong-light.png\""
          ${PROJECT_BINARY_DIR}/samples-installed/shadow-map/shadow-map ${CMAKE_CURRENT_SOURCE_DIR}/samples/check_sample_image.py
          ${SP_SAMPLES_OUT} ${CMAKE_CURRENT_SOURCE_DIR}/samples/shadow-map.json)
set_tests_properties(samples.check_rejects_a_wrong_picture PROPERTIES FIXTURES_REQUIRED sp_samples_installed)

# One test per sample: both backends, validation on, each picture against the ray trace and
# the two against each other. ARGN: the sample's arguments before the common ones.
function(sp_sample_test name exe scene)
  set(run "mkdir -p \"${SP_SAMPLES_OUT}\" && cd \"${SP_SAMPLES_OUT}\"")
  if(name MATCHES "^technique")
    # The technique sample loads glTF: the checker's boxes written as a file, and the camera
    # and light it expects as arguments.
    string(APPEND run " && args=$(${SP_REPORT_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/samples/make_boxes_gltf.py ${scene} ${name}.gltf)")
    list(PREPEND ARGN ${name}.gltf)
  endif()
  list(JOIN ARGN " " sample_args)
  foreach(backend vulkan gl)
    string(APPEND run " && \"${exe}\" ${sample_args} --backend ${backend} --size 192 --out ${name}-${backend}.png")
    if(name MATCHES "^technique")
      string(APPEND run " $args")
    endif()
  endforeach()
  string(APPEND run " && ${SP_REPORT_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/samples/check_sample_image.py ${scene}"
                    " ${name}-vulkan.png ${name}-gl.png")
  add_test(NAME samples.${name} COMMAND bash -c "${run}")
  set_tests_properties(samples.${name} PROPERTIES FIXTURES_REQUIRED sp_samples_installed TIMEOUT 300
                       ENVIRONMENT "${SP_SHADER_CACHE_ENV}")
endfunction()

set(SP_SAMPLES_BIN ${PROJECT_BINARY_DIR}/samples-installed)
sp_sample_test(shadow_map ${SP_SAMPLES_BIN}/shadow-map/shadow-map ${CMAKE_CURRENT_SOURCE_DIR}/samples/shadow-map.json)
sp_sample_test(cascades ${SP_SAMPLES_BIN}/cascades/cascades ${CMAKE_CURRENT_SOURCE_DIR}/samples/cascades.json)
foreach(technique csm sdsm)
  sp_sample_test(technique_${technique} ${SP_SAMPLES_BIN}/technique/technique ${CMAKE_CURRENT_SOURCE_DIR}/samples/technique-boxes.json
                 --technique ${technique})
endforeach()

# add_subdirectory(shadowport) from another project: configure, build the RHI and one sample
# (a second compile of the library, so it runs alone at the end), run it. With the same flags as
# this build (C++20 without GNU extensions, as the top level sets) and this build's compiler
# launcher, a ccache build (./shadowport uses one when ccache is installed) compiles the library
# from the cache instead of a second time.
add_test(NAME samples.build_through_add_subdirectory
  COMMAND bash -c "mkdir -p \"$3\" && cmake -S \"$0\" -B \"$1\" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_EXTENSIONS=OFF -DCMAKE_CXX_COMPILER_LAUNCHER=\"$4\" -DSHADOWPORT_SOURCE_DIR=\"$2\" >/dev/null && cmake --build \"$1\" -j \"$(nproc)\" --target shadow-map && \"$1/shadow-map/shadow-map\" --backend gl --size 128 --out \"$3/subdirectory.png\""
          ${CMAKE_CURRENT_SOURCE_DIR}/samples/subdirectory-consumer ${PROJECT_BINARY_DIR}/samples-subdirectory
          ${PROJECT_SOURCE_DIR} ${SP_SAMPLES_OUT} "${CMAKE_CXX_COMPILER_LAUNCHER}")
set_tests_properties(samples.build_through_add_subdirectory PROPERTIES TIMEOUT 1800 RUN_SERIAL TRUE)
