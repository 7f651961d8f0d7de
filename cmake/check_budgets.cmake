# Fails when the image takes more flash or static RAM than its budget.
# Flash: every section loaded into flash (vectors, code, constants, the initial values of .data).
# RAM: .data, .bss, .noinit and the stack (reserved statically, so it counts).
# Usage: cmake -DSIZE=<arm-none-eabi-size> -DELF=<image> -DFLASH_BUDGET=<bytes> -DRAM_BUDGET=<bytes> -P check_budgets.cmake
execute_process(COMMAND ${SIZE} -A ${ELF} OUTPUT_VARIABLE table RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "size failed on ${ELF}")
endif()
set(flash 0)
set(ram 0)
string(REPLACE "\n" ";" lines "${table}")
foreach(line IN LISTS lines)
  if(line MATCHES "^([.][A-Za-z_.]+) +([0-9]+) +([0-9]+)")
    set(name ${CMAKE_MATCH_1})
    set(bytes ${CMAKE_MATCH_2})
    set(addr ${CMAKE_MATCH_3})
    if(addr GREATER_EQUAL 134217728 AND addr LESS 135266304)      # 0x08000000..0x080FFFFF
      math(EXPR flash "${flash} + ${bytes}")
    elseif(addr GREATER_EQUAL 536870912 AND addr LESS 537001984)  # 0x20000000..0x2001FFFF
      math(EXPR ram "${ram} + ${bytes}")
      if(name STREQUAL ".data")
        math(EXPR flash "${flash} + ${bytes}")                   # its initial values
      endif()
    endif()
  endif()
endforeach()
math(EXPR flash_kib "${flash} / 1024")
math(EXPR ram_kib "${ram} / 1024")
if(NOT NAME)
  set(NAME tse-fw)
endif()
message(STATUS "${NAME}: flash ${flash} B (${flash_kib} KiB of ${FLASH_BUDGET} B), static RAM ${ram} B (${ram_kib} KiB of ${RAM_BUDGET} B)")
if(flash GREATER FLASH_BUDGET)
  message(FATAL_ERROR "${NAME} takes ${flash} B of flash: over its budget of ${FLASH_BUDGET} B")
endif()
if(ram GREATER RAM_BUDGET)
  message(FATAL_ERROR "${NAME} takes ${ram} B of static RAM: over its budget of ${RAM_BUDGET} B")
endif()
