# Cross toolchain for the Cortex-M3 build (issue 29): a core without a floating-point unit (the
# STM32F103's), soft-float ABI, run under QEMU's mps2-an385.  Only the fixed-point kinematics and
# its on-target tests and benchmark are built for it (CMakeLists.txt, TSE_CPU); everything else is
# the board's toolchain file.
set(TSE_CPU cortex-m3)
set(TSE_CPU_FLAGS "-mcpu=cortex-m3 -mthumb -mfloat-abi=soft")
include(${CMAKE_CURRENT_LIST_DIR}/arm-none-eabi.cmake)
