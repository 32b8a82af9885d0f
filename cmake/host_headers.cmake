# SPDX-License-Identifier: GPL-3.0-or-later
# The dependencies of a cross build, taken from the build machine's Debian packages as
# header-only libraries: Eigen, CGAL and CLI11 are header-only anyway; fmt and toml++ are
# compiled into arcpress (FMT_HEADER_ONLY, TOML_HEADER_ONLY), as their packages' CMake files
# name the host's Linux libraries. Only these folders are put on the include path, through
# links, never /usr/include itself, whose C library headers are not the target's.
set(_host_headers ${CMAKE_BINARY_DIR}/host-headers)
file(MAKE_DIRECTORY ${_host_headers})
foreach(pair "fmt;/usr/include/fmt" "toml++;/usr/include/toml++" "CLI;/usr/include/CLI" "Eigen;/usr/include/eigen3/Eigen"
             "CGAL;/usr/include/CGAL" "boost;/usr/include/boost")
  list(GET pair 0 name)
  list(GET pair 1 from)
  if(NOT EXISTS ${from})
    message(FATAL_ERROR "${from} is missing: run scripts/install-deps.sh")
  endif()
  if(NOT EXISTS ${_host_headers}/${name})
    file(CREATE_LINK ${from} ${_host_headers}/${name} SYMBOLIC)
  endif()
endforeach()
add_library(arcpress_host_headers INTERFACE)
target_include_directories(arcpress_host_headers SYSTEM INTERFACE ${_host_headers})
foreach(target Eigen3::Eigen CLI11::CLI11)
  add_library(${target} INTERFACE IMPORTED)
  target_link_libraries(${target} INTERFACE arcpress_host_headers)
endforeach()
add_library(fmt::fmt INTERFACE IMPORTED)
target_link_libraries(fmt::fmt INTERFACE arcpress_host_headers)
target_compile_definitions(fmt::fmt INTERFACE FMT_HEADER_ONLY=1)
add_library(tomlplusplus::tomlplusplus INTERFACE IMPORTED)
target_link_libraries(tomlplusplus::tomlplusplus INTERFACE arcpress_host_headers)
target_compile_definitions(tomlplusplus::tomlplusplus INTERFACE TOML_HEADER_ONLY=1)
