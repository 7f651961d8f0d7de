# Fails when a library or an image for a core without an FPU (the fixed-point kinematics, the
# Cortex-M3 build) references or contains any software floating-point routine, single or double:
# the AEABI helpers (__aeabi_f*, __aeabi_d*, conversions to and from them), libgcc's generic ones
# (__addsf3, __muldf3, ...) and the C library's mathematical functions.
# Usage: cmake -DNM=<nm> -DLIB=<archive or image> [-DDEFINED=1] -P check_no_float.cmake
# With DEFINED=1 (a linked image) every symbol is looked at, not only the undefined ones.
if(DEFINED_SYMS)
  execute_process(COMMAND ${NM} ${LIB} OUTPUT_VARIABLE syms RESULT_VARIABLE rc)
else()
  execute_process(COMMAND ${NM} -u ${LIB} OUTPUT_VARIABLE syms RESULT_VARIABLE rc)
endif()
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "nm failed on ${LIB}")
endif()
string(REGEX MATCHALL "__aeabi_[dfl]?[a-z0-9]*(d|f)[a-z0-9]*|__[a-z]+[sdt]f[0-9]?[23]?" helpers "${syms}")
# Some AEABI helpers are integer ones (__aeabi_ldivmod, __aeabi_uldivmod, __aeabi_idiv, ...,
# __aeabi_lasr, __aeabi_llsl, __aeabi_memcpy...): keep only the floating-point families.
set(found "")
foreach(h IN LISTS helpers)
  if(h MATCHES "^__aeabi_(d|f|[iul]*2[df]|[iul]*l2[df]|cdcmp|cfcmp|cdrcmp|cfrcmp)" OR h MATCHES "^__[a-z]+[sdt]f[0-9]?$|^__[a-z]+[sdt]f[23]$")
    if(NOT h MATCHES "^__aeabi_(ldivmod|uldivmod|idiv|uidiv|idivmod|uidivmod|lasr|llsl|llsr|lmul|lcmp|ulcmp|memcpy|memmove|memset|memclr)")
      list(APPEND found ${h})
    endif()
  endif()
endforeach()
string(REGEX MATCHALL "(^|\n)[0-9a-f ]* [TUtW] (sqrtf?|sinf?|cosf?|tanf?|asinf?|acosf?|atanf?|atan2f?|expf?|logf?|powf?|fabsf?|cbrtf?|hypotf?|floorf?|ceilf?|_printf_float|_scanf_float)\n" libm "${syms}")
if(found OR libm)
  list(REMOVE_DUPLICATES found)
  message(FATAL_ERROR "${LIB} uses floating point: ${found} ${libm}")
endif()
message(STATUS "${LIB}: no floating-point routine")
