# The core's file readers (core/src/io, natively the library geoshift_io) for the wasm flavours, so
# that the web app refuses a damaged file with the CLI's words (wasm/read_file.cpp).
#
# Emscripten has its own system headers and must not see /usr/include, where Debian puts the
# header-only parsers: copies of just those headers go into the build tree. The terrain readers
# (LAS, GeoTIFF through libtiff, PLY points) stay native-only.
set(GEOSHIFT_WASM_VENDOR_INCLUDE "${CMAKE_CURRENT_BINARY_DIR}/vendor-include")
foreach(header tiny_gltf.h tiny_obj_loader.h nlohmann/json.hpp)
  string(MAKE_C_IDENTIFIER "GEOSHIFT_HEADER_${header}" var)
  find_file(${var} ${header} PATHS /usr/include NO_DEFAULT_PATH NO_CMAKE_FIND_ROOT_PATH)
  if(NOT ${var})
    message(FATAL_ERROR "${header} not found in /usr/include (Debian: libtinygltf-dev, "
                        "libtinyobjloader-dev, nlohmann-json3-dev)")
  endif()
endforeach()
file(COPY ${GEOSHIFT_HEADER_tiny_gltf_h} ${GEOSHIFT_HEADER_tiny_obj_loader_h}
     DESTINATION "${GEOSHIFT_WASM_VENDOR_INCLUDE}")
get_filename_component(GEOSHIFT_NLOHMANN_DIR "${GEOSHIFT_HEADER_nlohmann_json_hpp}" DIRECTORY)
file(COPY "${GEOSHIFT_NLOHMANN_DIR}" DESTINATION "${GEOSHIFT_WASM_VENDOR_INCLUDE}")

file(GLOB GEOSHIFT_WASM_IO_SOURCES CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/core/src/io/*.cpp")
list(FILTER GEOSHIFT_WASM_IO_SOURCES EXCLUDE REGEX "/terrain_[a-z]+\\.cpp$")
list(APPEND GEOSHIFT_WASM_IO_SOURCES "${CMAKE_CURRENT_SOURCE_DIR}/io/third_party.cpp")

foreach(mode st mt)
  set(lib geoshift_io_wasm_${mode})
  add_library(${lib} STATIC ${GEOSHIFT_WASM_IO_SOURCES})
  target_include_directories(${lib} SYSTEM PRIVATE "${GEOSHIFT_WASM_VENDOR_INCLUDE}")
  target_compile_definitions(${lib} PRIVATE TINYGLTF_NO_STB_IMAGE TINYGLTF_NO_STB_IMAGE_WRITE)
  target_compile_options(${lib} PRIVATE ${GEOSHIFT_WASM_COMPILE_OPTIONS_${mode}})
  if(mode STREQUAL "st")
    target_link_libraries(${lib} PUBLIC geoshift_core)
  else()
    target_link_libraries(${lib} PUBLIC geoshift_core_mt)
  endif()
endforeach()
