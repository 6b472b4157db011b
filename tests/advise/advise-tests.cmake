# shadowport advise (included from tests/CMakeLists.txt): the selection logic without a GPU in
# shadowport_tests, and the command end to end at 96x54.
target_sources(shadowport_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR}/advise-test.cpp)
target_link_libraries(shadowport_tests PRIVATE sp_eval_advise)

set(SP_ADVISE_TEST_DIR ${PROJECT_BINARY_DIR}/test-output/cli-advise)
foreach(SP_BAD IN ITEMS "budget_metric|--budget acne=1|--budget 'acne=1': unknown metric 'acne' (valid: misclassified,"
                        "budget_form|--budget misclassified|--budget 'misclassified' is not metric=value"
                        "budget_value|--budget misclassified=lots|--budget 'misclassified=lots': 'lots' is not a number"
                        "no_budget|--techniques basic|--budget metric=value is required"
                        "scene|--scene nosuch --budget misclassified=1|unknown scene 'nosuch' (built-in: default,"
                        "technique|--techniques basic,nosuch --budget misclassified=1|unknown technique 'nosuch' (available: basic"
                        "axis|--techniques basic --axes cascades --budget misclassified=1|--axes: no technique searched has a parameter 'cascades'"
                        "minimize|--minimize speed --budget misclassified=1|--minimize must be ms or memory (got 'speed')")
  string(REPLACE "|" ";" SP_BAD_PARTS "${SP_BAD}")
  list(GET SP_BAD_PARTS 0 SP_BAD_NAME)
  list(GET SP_BAD_PARTS 1 SP_BAD_ARGS)
  list(GET SP_BAD_PARTS 2 SP_BAD_EXPECT)
  if(NOT SP_BAD_ARGS MATCHES "--scene")
    set(SP_BAD_ARGS "--scene default ${SP_BAD_ARGS}")
  endif()
  add_test(NAME cli.advise_bad_${SP_BAD_NAME}_names_it
    COMMAND bash -c "out=$(\"$0\" advise $1 --size 16x16 --frames 1 --out \"$3/bad\" 2>&1); rc=$?; echo \"$out\"; [ $rc -ne 0 ] && echo \"$out\" | grep -qF -- \"$2\""
            $<TARGET_FILE:shadowport> "${SP_BAD_ARGS}" "${SP_BAD_EXPECT}" ${SP_ADVISE_TEST_DIR})
  set_tests_properties(cli.advise_bad_${SP_BAD_NAME}_names_it PROPERTIES ENVIRONMENT "${SP_SHADER_CACHE_ENV}")
endforeach()

# A lattice that reaches configurations the technique refuses (box kernels above 15) skips them,
# saying why, and finishes.
add_test(NAME cli.advise_skips_configurations_the_technique_refuses
  COMMAND bash -c "out=$(\"$0\" advise --scene default --techniques basic:filter=box --axes kernel --exhaustive --budget misclassified=100 --size 16x16 --frames 1 --confirm 1 --no-report --out \"$1/refused\" 2>&1); rc=$?; echo \"$out\"; [ $rc -eq 0 ] && echo \"$out\" | grep -qF 'skipped basic:filter=box:kernel=17: the technique refuses it' && echo \"$out\" | grep -qF ', 8 refused by their technique'"
          $<TARGET_FILE:shadowport> ${SP_ADVISE_TEST_DIR})
set_tests_properties(cli.advise_skips_configurations_the_technique_refuses PROPERTIES ENVIRONMENT "${SP_SHADER_CACHE_ENV}" TIMEOUT 300)

if(SP_REPORT_PYTHON)
  # The search against the exhaustive sweep (same optimum under --minimize memory), the cache (a
  # rerun measures nothing), Ctrl-C and resume, an impossible budget, and the page.
  add_test(NAME cli.advise_search_matches_the_exhaustive_sweep_and_resumes
    COMMAND ${SP_REPORT_PYTHON} ${CMAKE_CURRENT_LIST_DIR}/check_advise.py $<TARGET_FILE:shadowport> ${SP_ADVISE_TEST_DIR}/e2e)
  set_tests_properties(cli.advise_search_matches_the_exhaustive_sweep_and_resumes PROPERTIES TIMEOUT 240
    ENVIRONMENT "${SP_SHADER_CACHE_ENV}")
endif()
