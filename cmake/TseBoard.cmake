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

# On a cross build: fail the build of `target` (a library, or with IMAGE a linked image, whose
# every symbol is then looked at) when it references or contains a software floating-point
# routine (cmake/check_no_float.cmake): the fixed-point kinematics and the Cortex-M3 build.
#   tse_check_no_float(TARGET [IMAGE])
function(tse_check_no_float target)
  cmake_parse_arguments(ARG "IMAGE" "" "" ${ARGN})
  if(CMAKE_CROSSCOMPILING)
    set(defined "")
    if(ARG_IMAGE)
      set(defined -DDEFINED_SYMS=1)
    endif()
    add_custom_command(TARGET ${target} POST_BUILD
      COMMAND ${CMAKE_COMMAND} -DNM=${CMAKE_NM} -DLIB=$<TARGET_FILE:${target}> ${defined}
              -P ${PROJECT_SOURCE_DIR}/cmake/check_no_float.cmake
      COMMENT "Checking ${target} for floating point")
  endif()
endfunction()

# An image for a board: linked with the board's linker script (cmake/TseBoards.cmake) and its
# description, with a map file, a .bin and a .hex beside the .elf, and its size printed.
#   tse_board_image(TARGET [SEMIHOSTING] [BOARD NAME])
# SEMIHOSTING: a test or benchmark image for QEMU, linked with newlib's system-call stubs and
# semihosting output; never the production image.  BOARD: default gen_f405.
function(tse_board_image target)
  cmake_parse_arguments(ARG "SEMIHOSTING" "BOARD" "" ${ARGN})
  if(NOT ARG_BOARD)
    set(ARG_BOARD gen_f405)
  endif()
  tse_board_ldscript(${ARG_BOARD} ldscript)
  tse_board_desc_library(${ARG_BOARD})
  set_target_properties(${target} PROPERTIES SUFFIX ".elf" TSE_LDSCRIPT ${ldscript} TSE_BOARD ${ARG_BOARD}
                        LINK_DEPENDS ${ldscript})
  target_link_options(${target} PRIVATE -T${ldscript} -Wl,-Map=$<TARGET_FILE_DIR:${target}>/${target}.map
                      -Wl,--print-memory-usage)
  target_link_libraries(${target} PRIVATE tse_hal_stm32f4 tse_board_desc_${ARG_BOARD} m)
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

# A board build directory configured before cmake/arm-none-eabi.cmake gained -fstack-usage
# -fcallgraph-info=su keeps its cached CMAKE_C_FLAGS: add them here, so that every object gets
# the .su and .ci the stack report reads without a fresh configure.
if(CMAKE_CROSSCOMPILING AND NOT CMAKE_C_FLAGS MATCHES "-fcallgraph-info")
  add_compile_options($<$<COMPILE_LANGUAGE:C>:-fstack-usage> $<$<COMPILE_LANGUAGE:C>:-fcallgraph-info=su>)
endif()

# The worst-case stack of a board image: cmake/stack_report.py adds up the .ci call graphs and
# .su frames (-fstack-usage -fcallgraph-info=su in cmake/arm-none-eabi.cmake) of the objects the
# map says were linked, writes TARGET.stack.txt beside the .elf, and fails the build when the
# thread's deepest chain plus one handler and exception frame per interrupt priority level
# exceeds the linker script's _stack_size.
#   tse_stack_report(TARGET)   (after tse_board_image(TARGET))
function(tse_stack_report target)
  find_program(TSE_PYTHON NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
  if(NOT TSE_PYTHON)
    find_program(TSE_PYTHON NAMES python3 REQUIRED)
  endif()
  add_custom_command(TARGET ${target} POST_BUILD
    COMMAND ${TSE_PYTHON} ${PROJECT_SOURCE_DIR}/cmake/stack_report.py --quiet
            --map $<TARGET_FILE_DIR:${target}>/${target}.map --elf $<TARGET_FILE:${target}>
            --build-dir ${PROJECT_BINARY_DIR} --link-dir ${CMAKE_CURRENT_BINARY_DIR}
            --ldscript $<TARGET_PROPERTY:${target},TSE_LDSCRIPT> --source-root ${PROJECT_SOURCE_DIR}
            --prio-header ${PROJECT_SOURCE_DIR}/hal/stm32f4/include/hal_stm32f4/pinmap.h
    COMMENT "Worst-case stack of ${target}")
endfunction()
