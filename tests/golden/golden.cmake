# Golden tests: every sample posted for every machine must equal
# tests/golden/<machine>/<sample>.<ext> byte for byte, or fail with the message in
# tests/golden/<machine>/<sample>.err when the machine cannot run it. scripts/update-golden
# rewrites them.
add_executable(golden_diff ${CMAKE_SOURCE_DIR}/tests/golden/golden_diff.cpp)
file(GLOB CAMGEN_SAMPLES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/samples/*.json)
foreach(machine_file ${CAMGEN_MACHINE_FILES})
  get_filename_component(machine ${machine_file} NAME_WE)
  file(READ ${machine_file} machine_text)
  string(REGEX MATCH "\"extension\": *\"([a-z]+)\"" _ ${machine_text})
  set(ext ${CMAKE_MATCH_1})
  foreach(sample_file ${CAMGEN_SAMPLES})
    get_filename_component(sample ${sample_file} NAME_WE)
    camgen_add_test(NAME golden/${machine}/${sample}
      COMMAND ${CMAKE_COMMAND} -DCAMGEN=$<TARGET_FILE:camgen> -DDIFF=$<TARGET_FILE:golden_diff> -DJOB=${sample_file} -DMACHINE=${machine}
              -DEXPECTED=${CMAKE_SOURCE_DIR}/tests/golden/${machine}/${sample}.${ext}
              -DEXPECTED_ERROR=${CMAKE_SOURCE_DIR}/tests/golden/${machine}/${sample}.err
              -DACTUAL=${CMAKE_BINARY_DIR}/golden/${machine}/${sample}.${ext}
              -P ${CMAKE_SOURCE_DIR}/tests/golden/compare.cmake)
  endforeach()
endforeach()
