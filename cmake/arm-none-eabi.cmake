# Cross toolchain for the actuator controller board: STM32F405/407, Cortex-M4F with the
# single-precision FPU (fpv4-sp-d16), hard-float ABI.  Debian's gcc-arm-none-eabi + newlib.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_OBJCOPY arm-none-eabi-objcopy CACHE FILEPATH "objcopy")
set(CMAKE_SIZE arm-none-eabi-size CACHE FILEPATH "size")
set(CMAKE_NM arm-none-eabi-nm CACHE FILEPATH "nm")

# No OS to link a test program against: probe the compiler with a static library.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

# The Cortex-M3 build (arm-none-eabi-m3.cmake) sets its own flags and includes this file.
if(NOT TSE_CPU_FLAGS)
  set(TSE_CPU_FLAGS "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard")
endif()
# -fstack-usage -fcallgraph-info=su: each object gets a .su (frame of each function) and a .ci
# (call graph with the frames) beside it; cmake/stack_report.py adds them up for an image.
# -g: debug information stays in the .elf (the .bin and .hex carry none), so gdb can read the
# board's state by name, as the boot test does.
set(CMAKE_C_FLAGS_INIT
    "${TSE_CPU_FLAGS} -g -ffunction-sections -fdata-sections -fno-common -fstack-usage -fcallgraph-info=su")
set(CMAKE_ASM_FLAGS_INIT "${TSE_CPU_FLAGS}")
set(CMAKE_EXE_LINKER_FLAGS_INIT "${TSE_CPU_FLAGS} -Wl,--gc-sections --specs=nano.specs")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
