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

# An image for the board: linked with the board's linker script, with a map file, a .bin and a
# .hex beside the .elf, and its size printed.
#   tse_board_image(TARGET [SEMIHOSTING])
# SEMIHOSTING: a test or benchmark image for QEMU, linked with newlib's system-call stubs and
# semihosting output; never the production image.
function(tse_board_image target)
  cmake_parse_arguments(ARG "SEMIHOSTING" "" "" ${ARGN})
  set_target_properties(${target} PROPERTIES SUFFIX ".elf")
  target_link_options(${target} PRIVATE -T${TSE_BOARD_LDSCRIPT} -Wl,-Map=$<TARGET_FILE_DIR:${target}>/${target}.map
                      -Wl,--print-memory-usage)
  target_link_libraries(${target} PRIVATE tse_hal_stm32f4 m)
  if(ARG_SEMIHOSTING)
    target_link_libraries(${target} PRIVATE tse_semihost)
    target_link_options(${target} PRIVATE --specs=nosys.specs)
  endif()
  add_custom_command(TARGET ${target} POST_BUILD
    COMMAND ${CMAKE_OBJCOPY} -O binary $<TARGET_FILE:${target}> $<TARGET_FILE_DIR:${target}>/${target}.bin
    COMMAND ${CMAKE_OBJCOPY} -O ihex $<TARGET_FILE:${target}> $<TARGET_FILE_DIR:${target}>/${target}.hex
    COMMAND ${CMAKE_SIZE} $<TARGET_FILE:${target}>
    COMMENT "Image ${target}: .elf, .bin, .hex")
endfunction()
