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
# the two against each other. ARGS: extra arguments for the sample.
function(sp_sample_test name exe scene)
  set(run "mkdir -p \"${SP_SAMPLES_OUT}\"")
  foreach(backend vulkan gl)
    string(APPEND run " && \"${exe}\" --backend ${backend} --size 192 --out \"${SP_SAMPLES_OUT}/${name}-${backend}.png\" ${ARGN}")
  endforeach()
  string(APPEND run " && ${SP_REPORT_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/samples/check_sample_image.py ${scene}"
                    " \"${SP_SAMPLES_OUT}/${name}-vulkan.png\" \"${SP_SAMPLES_OUT}/${name}-gl.png\"")
  add_test(NAME samples.${name} COMMAND bash -c "${run}")
  set_tests_properties(samples.${name} PROPERTIES FIXTURES_REQUIRED sp_samples_installed TIMEOUT 300)
endfunction()

sp_sample_test(shadow_map ${PROJECT_BINARY_DIR}/samples-installed/shadow-map/shadow-map
               ${CMAKE_CURRENT_SOURCE_DIR}/samples/shadow-map.json)

# add_subdirectory(shadowport) from another project: configure, build the RHI and one sample
# (a second compile of the library, so it runs alone at the end), run it.
add_test(NAME samples.build_through_add_subdirectory
  COMMAND bash -c "mkdir -p \"$3\" && cmake -S \"$0\" -B \"$1\" -DCMAKE_BUILD_TYPE=Release -DSHADOWPORT_SOURCE_DIR=\"$2\" >/dev/null && cmake --build \"$1\" -j \"$(nproc)\" --target shadow-map && \"$1/shadow-map/shadow-map\" --backend gl --size 128 --out \"$3/subdirectory.png\""
          ${CMAKE_CURRENT_SOURCE_DIR}/samples/subdirectory-consumer ${PROJECT_BINARY_DIR}/samples-subdirectory
          ${PROJECT_SOURCE_DIR} ${SP_SAMPLES_OUT})
set_tests_properties(samples.build_through_add_subdirectory PROPERTIES TIMEOUT 1800 RUN_SERIAL TRUE)
