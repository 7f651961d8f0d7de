# The boards: one description each, hal/stm32f4/boards/NAME.h (hal_stm32f4/board_desc.h says what
# it holds).  TSE_BOARDS lists them; TSE_BOARD (a cache variable) is the one `tse-fw` is built for;
# every board also gets its own image, tse-fw-NAME (board/CMakeLists.txt), so that one build
# builds them all.
set(TSE_BOARDS_DIR ${PROJECT_SOURCE_DIR}/hal/stm32f4/boards)
file(GLOB _tse_board_files CONFIGURE_DEPENDS ${TSE_BOARDS_DIR}/*.h)
set(TSE_BOARDS "")
foreach(f IN LISTS _tse_board_files)
  get_filename_component(n ${f} NAME_WE)
  list(APPEND TSE_BOARDS ${n})
endforeach()
list(SORT TSE_BOARDS)

set(TSE_BOARD generic_f405 CACHE STRING "the board tse-fw is built for (a file hal/stm32f4/boards/NAME.h)")
set_property(CACHE TSE_BOARD PROPERTY STRINGS ${TSE_BOARDS})
if(NOT TSE_BOARD IN_LIST TSE_BOARDS)
  string(REPLACE ";" ", " _known "${TSE_BOARDS}")
  message(FATAL_ERROR "unknown TSE_BOARD '${TSE_BOARD}': no hal/stm32f4/boards/${TSE_BOARD}.h. "
                      "Known boards: ${_known}")
endif()

# One value of a description: `#define NAME value` (a number, 0x... with an optional u).
function(_tse_board_value file name out)
  file(STRINGS ${file} lines REGEX "^#define ${name} ")
  if(NOT lines MATCHES "^#define ${name} +(0x[0-9A-Fa-f]+|[0-9]+)u?")
    message(FATAL_ERROR "${file}: no numeric #define ${name}")
  endif()
  math(EXPR v "${CMAKE_MATCH_1}")
  set(${out} ${v} PARENT_SCOPE)
endfunction()

# The start of a flash sector of the STM32F405/407 (RM0090 table 5: 4 x 16 KiB, 64 KiB, 128 KiB...).
function(_tse_sector_addr sector out)
  if(sector LESS_EQUAL 4)
    math(EXPR v "0x08000000 + ${sector} * 0x4000")
  else()
    math(EXPR v "0x08020000 + (${sector} - 5) * 0x20000")
  endif()
  set(${out} ${v} PARENT_SCOPE)
endfunction()

# The linker script of board NAME in OUT: the image from BOARD_APP_ADDR to the parameter log's
# first sector (the host checker, tests/boards, holds a description to a sane layout; this only
# refuses one the linker could not place an image in).
function(tse_board_ldscript name out)
  set(file ${TSE_BOARDS_DIR}/${name}.h)
  _tse_board_value(${file} BOARD_APP_ADDR app)
  _tse_board_value(${file} BOARD_PARAM_SECTOR sector)
  _tse_sector_addr(${sector} log)
  if(log LESS_EQUAL app)
    message(FATAL_ERROR "${file}: the parameter log (sector ${sector}) lies below the application address")
  endif()
  math(EXPR length "${log} - ${app}")
  math(EXPR TSE_FLASH_ORIGIN "${app}" OUTPUT_FORMAT HEXADECIMAL)
  math(EXPR TSE_FLASH_LENGTH "${length}" OUTPUT_FORMAT HEXADECIMAL)
  math(EXPR TSE_LOG_BASE "${log}" OUTPUT_FORMAT HEXADECIMAL)
  set(TSE_BOARD_NAME ${name})
  set(script ${PROJECT_BINARY_DIR}/ld/${name}.ld)
  configure_file(${PROJECT_SOURCE_DIR}/hal/stm32f4/ld/board.ld.in ${script} @ONLY)
  set(${out} ${script} PARENT_SCOPE)
endfunction()

# tse_board_desc_NAME: the description compiled into the table the drivers read (an object
# library, so that it links whatever the order of the libraries).  IMAGE: with the .tse_board
# identity (production images).
function(tse_board_desc_library name)
  set(lib tse_board_desc_${name})
  if(TARGET ${lib})
    return()
  endif()
  add_library(${lib} OBJECT ${PROJECT_SOURCE_DIR}/hal/stm32f4/src/board_desc.c)
  target_include_directories(${lib} PRIVATE ${PROJECT_SOURCE_DIR}/hal/stm32f4/include)
  target_compile_definitions(${lib} PRIVATE TSE_BOARD_HEADER="${TSE_BOARDS_DIR}/${name}.h" TSE_BOARD_IMAGE)
endfunction()
