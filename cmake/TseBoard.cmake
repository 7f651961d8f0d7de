# On the board build: fail the build of `target` when it references software double-precision
# arithmetic (the Cortex-M4F's FPU is single precision only).
function(tse_check_no_double target)
  if(CMAKE_CROSSCOMPILING)
    add_custom_command(TARGET ${target} POST_BUILD
      COMMAND ${CMAKE_COMMAND} -DNM=${CMAKE_NM} -DLIB=$<TARGET_FILE:${target}>
              -P ${PROJECT_SOURCE_DIR}/cmake/check_no_double.cmake
      COMMENT "Checking ${target} for double-precision arithmetic")
  endif()
endfunction()
