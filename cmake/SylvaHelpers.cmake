# Helpers every module uses, so a module's CMakeLists.txt stays ~20 declarative lines.

set(SYLVA_SOURCE_ROOT "${CMAKE_CURRENT_LIST_DIR}/.." CACHE INTERNAL "")
set(SYLVA_EMBED_SCRIPT "${CMAKE_CURRENT_LIST_DIR}/embed_shaders.cmake" CACHE INTERNAL "")

# Warnings and sanitizers for a target of ours (never for third-party code).
function(sylva_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  # Only record the shared libraries a binary really uses: OpenImageIO alone drags in ~250
  # libraries, which costs every test process a second of start-up when it is not needed.
  target_link_options(${target} PRIVATE -Wl,--as-needed)
  if(SYLVA_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(SYLVA_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# sylva_add_module(<name> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...] [SHADERS ...])
# Creates sylva_<name> with alias sylva::<name>, public headers under include/.
# SHADERS are embedded (see sylva_embed_shaders) and registered at static-init time.
function(sylva_add_module name)
  cmake_parse_arguments(M "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS;SHADERS" ${ARGN})
  add_library(sylva_${name} STATIC ${M_SOURCES})
  add_library(sylva::${name} ALIAS sylva_${name})
  target_include_directories(sylva_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>)
  target_link_libraries(sylva_${name} PUBLIC ${M_PUBLIC_DEPS} PRIVATE ${M_PRIVATE_DEPS})
  sylva_target_defaults(sylva_${name})
  if(M_SHADERS)
    sylva_embed_shaders(sylva_${name} ${name} ${M_SHADERS})
  endif()
endfunction()

# sylva_embed_shaders(<target> <module> files...)
# Generates a .cpp holding each shader file as a string view, registered in the
# render module's shader library under "<module>/<relative path>". Because object files
# holding only static registrars could be dropped by the linker, the registration
# function is referenced from sylva_<module>_shaders_anchor(), which the module calls.
function(sylva_embed_shaders target module)
  set(out "${CMAKE_CURRENT_BINARY_DIR}/${module}_embedded_shaders.cpp")
  set(abs_files "")
  foreach(f ${ARGN})
    get_filename_component(af "${f}" ABSOLUTE)
    list(APPEND abs_files "${af}")
  endforeach()
  add_custom_command(
    OUTPUT "${out}"
    COMMAND ${CMAKE_COMMAND} -DMODULE=${module} -DOUT=${out}
            -DBASE=${CMAKE_CURRENT_SOURCE_DIR}/shaders "-DFILES=${abs_files}"
            -P "${SYLVA_EMBED_SCRIPT}"
    DEPENDS ${abs_files} "${SYLVA_EMBED_SCRIPT}"
    COMMENT "Embedding ${module} shaders"
    VERBATIM)
  target_sources(${target} PRIVATE "${out}")
  if(SYLVA_HOT_RELOAD)
    target_compile_definitions(${target} PRIVATE
      SYLVA_SHADER_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}/shaders")
  endif()
endfunction()

# sylva_add_test(<module> <kind> <name> SOURCES ... [DEPS ...])
# kind is one of unit, gl, stability, golden; the ctest labels are "<module>;<kind>".
function(sylva_add_test module kind name)
  if(NOT SYLVA_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(T "" "" "SOURCES;DEPS" ${ARGN})
  set(exe ${module}_${name})
  add_executable(${exe} ${T_SOURCES})
  target_link_libraries(${exe} PRIVATE ${T_DEPS} GTest::gtest GTest::gtest_main)
  sylva_target_defaults(${exe})
  # libfmt first, kept: otherwise the linker takes fmt's functions from the first archive member
  # that has an inline copy (core's image_io.cpp, through OpenImageIO's header-only fmt) and with
  # it OpenImageIO's ~250 libraries, whose symbol lookups cost each test process ~0.16 CPU-s of
  # start-up (0.00 s without) even when it reads and writes no image. One SHELL: group, because
  # CMake de-duplicates link options and would drop the second --as-needed.
  target_link_options(${exe} PRIVATE
    "SHELL:-Wl,--push-state,--no-as-needed $<TARGET_LINKER_FILE:fmt::fmt> -Wl,--pop-state")
  # sylva_tests_<kind> builds every test of one kind and only what they link: `make test-asan`
  # builds sylva_tests_unit alone, because a whole Debug + ASan tree does not fit CI's time.
  if(NOT TARGET sylva_tests_${kind})
    add_custom_target(sylva_tests_${kind})
  endif()
  add_dependencies(sylva_tests_${kind} ${exe})
  gtest_discover_tests(${exe}
    PROPERTIES TIMEOUT 300
    WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}"
    DISCOVERY_TIMEOUT 60)
  # gtest_discover_tests flattens a list given in PROPERTIES ("LABELS a;b" becomes two
  # properties), so the two labels are set by an include file that ctest runs after discovery.
  set(labels_file "${CMAKE_CURRENT_BINARY_DIR}/${exe}_labels.cmake")
  file(WRITE "${labels_file}"
    "set_tests_properties(\${${exe}_TESTS} PROPERTIES LABELS \"${module};${kind}\")\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${labels_file}")
endfunction()

# sylva_add_bench(<module> <name> SOURCES ... [DEPS ...]) : a Google Benchmark executable.
function(sylva_add_bench module name)
  if(NOT SYLVA_BUILD_BENCH)
    return()
  endif()
  cmake_parse_arguments(B "" "" "SOURCES;DEPS" ${ARGN})
  set(exe bench_${module}_${name})
  add_executable(${exe} ${B_SOURCES})
  target_link_libraries(${exe} PRIVATE ${B_DEPS} benchmark::benchmark benchmark::benchmark_main)
  sylva_target_defaults(${exe})
endfunction()

# sylva_add_module_tests(<module> DEPS ...)
# Registers every tests/*_test.cpp of the module as its own test executable. The kind label
# comes from the file name so adding a test never means editing CMake:
#   foo_test.cpp -> unit, foo_gl_test.cpp -> gl, foo_stability_test.cpp -> stability,
#   foo_golden_test.cpp -> golden.
# Files under tests/support/ are linked into every test executable of the module. They are
# compiled once, as the object library <module>_test_support, and its objects linked into each
# executable: the same code as compiling them per executable, without ~290 repeated compiles of
# the ci build (e.g. vegetation's 4 support files for each of its 32 test executables).
function(sylva_add_module_tests module)
  cmake_parse_arguments(T "" "" "DEPS" ${ARGN})
  file(GLOB test_files CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/tests/*_test.cpp")
  file(GLOB support_files CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/tests/support/*.cpp")
  set(support "")
  if(support_files AND SYLVA_BUILD_TESTS)
    set(support ${module}_test_support)
    add_library(${support} OBJECT ${support_files})
    target_link_libraries(${support} PRIVATE ${T_DEPS} GTest::gtest)
    target_include_directories(${support} PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}/tests")
    sylva_target_defaults(${support})
  endif()
  foreach(f ${test_files})
    get_filename_component(stem "${f}" NAME_WE)
    set(kind unit)
    foreach(k gl stability golden)
      if(stem MATCHES "_${k}_test$")
        set(kind ${k})
      endif()
    endforeach()
    string(REGEX REPLACE "_test$" "" name "${stem}")
    sylva_add_test(${module} ${kind} ${name} SOURCES "${f}" DEPS ${T_DEPS})
    if(TARGET ${module}_${name})
      target_include_directories(${module}_${name} PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}/tests")
      if(support)
        target_link_libraries(${module}_${name} PRIVATE ${support})
      endif()
    endif()
  endforeach()
endfunction()

# sylva_add_module_benches(<module> DEPS ...): every bench/*_bench.cpp becomes bench_<module>_<name>.
# Files under bench/support/ are linked into every benchmark of the module (as for tests).
function(sylva_add_module_benches module)
  cmake_parse_arguments(B "" "" "DEPS" ${ARGN})
  file(GLOB bench_files CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/bench/*_bench.cpp")
  file(GLOB support_files CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/bench/support/*.cpp")
  foreach(f ${bench_files})
    get_filename_component(stem "${f}" NAME_WE)
    string(REGEX REPLACE "_bench$" "" name "${stem}")
    sylva_add_bench(${module} ${name} SOURCES "${f}" ${support_files} DEPS ${B_DEPS})
    if(support_files AND TARGET bench_${module}_${name})
      target_include_directories(bench_${module}_${name} PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}/bench")
    endif()
  endforeach()
endfunction()
