# Writes camgen's man page from its option table: cmake -DCAMGEN=<camgen> -DOUT=<camgen.1> -P
execute_process(COMMAND ${CAMGEN} --man OUTPUT_FILE ${OUT}.tmp RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${CAMGEN} --man failed: ${result}")
endif()
file(RENAME ${OUT}.tmp ${OUT})
