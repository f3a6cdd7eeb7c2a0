# Imports libdnsr.so as cargo built it (DNSR_LIB, default <repo>/target/release/libdnsr.so) as the target
# dnsr::dnsr, for programs built inside this repository (an installed dnsr is found with find_package(dnsr)).
#
# libdnsr.so records the soname libdnsr.so.<abi> (e.g. libdnsr.so.0.1), the file name the dynamic loader looks
# for when a program starts, and cargo only writes libdnsr.so: a link of that name in the build directory (on the
# build RPATH) lets the programs run against DNSR_LIB in place. A macro, so the RPATH is set in the caller.
macro(dnsr_import_from_cargo repo_root)
  if(NOT TARGET dnsr::dnsr)
    set(DNSR_LIB "${repo_root}/target/release/libdnsr.so" CACHE FILEPATH "libdnsr.so built by cargo")
    set(DNSR_INCLUDE_DIR "${repo_root}/include" CACHE PATH "Directory of dnsr.h")
    if(NOT EXISTS "${DNSR_LIB}")
      message(FATAL_ERROR "DNSR_LIB=${DNSR_LIB} does not exist: run `cargo build --release --lib` first")
    endif()
    add_library(dnsr::dnsr SHARED IMPORTED)
    set_target_properties(dnsr::dnsr PROPERTIES
      IMPORTED_LOCATION "${DNSR_LIB}"
      INTERFACE_INCLUDE_DIRECTORIES "${DNSR_INCLUDE_DIR};${Vulkan_INCLUDE_DIRS}")
    execute_process(COMMAND "${CMAKE_OBJDUMP}" -p "${DNSR_LIB}" OUTPUT_VARIABLE dnsr_objdump ERROR_QUIET)
    if(dnsr_objdump MATCHES "SONAME +([^ \n]+)")
      file(CREATE_LINK "${DNSR_LIB}" "${CMAKE_CURRENT_BINARY_DIR}/${CMAKE_MATCH_1}" SYMBOLIC)
      set(CMAKE_BUILD_RPATH "${CMAKE_CURRENT_BINARY_DIR}")
    endif()
  endif()
endmacro()
