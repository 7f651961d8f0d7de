# Fails when a library for the Cortex-M4F references software double-precision helpers: the FPU
# is single precision only, so such a call means a double crept into the float build.
# Usage: cmake -DNM=<nm> -DLIB=<archive> -P check_no_double.cmake
execute_process(COMMAND ${NM} -u ${LIB} OUTPUT_VARIABLE undefined RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "nm failed on ${LIB}")
endif()
string(REGEX MATCHALL "__aeabi_d[a-z0-9]+|__aeabi_[fil]2d|__aeabi_ui2d|__aeabi_ul2d|[a-z_]+df[23]" doubles "${undefined}")
# Double-precision libm entry points (sqrt, sin, ...) without the f suffix.
string(REGEX MATCHALL "(^|\n) *U (sqrt|sin|cos|tan|asin|acos|atan|atan2|exp|log|pow|fabs|cbrt|hypot)\n" libm "${undefined}")
if(doubles OR libm)
  message(FATAL_ERROR "${LIB} uses double precision on the board: ${doubles} ${libm}")
endif()
message(STATUS "${LIB}: no double-precision arithmetic")
