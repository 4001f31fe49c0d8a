# The fuzz build (SYLVA_BUILD_FUZZ, preset `fuzz`, `make fuzz`): clang's libFuzzer with ASan and
# UBSan. Every target of ours is compiled with coverage instrumentation (fuzzer-no-link), so the
# fuzzer sees the branches inside the parsers that live in the module libraries; only the fuzz
# executables link the libFuzzer driver (fuzz/CMakeLists.txt). Undefined behaviour aborts
# (-fno-sanitize-recover) so the fuzzer records it as a crash with a reproducer.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "SYLVA_BUILD_FUZZ needs clang and libFuzzer (Debian clang-14, libclang-rt-14-dev); "
                      "configure with `cmake --preset fuzz`")
endif()
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
                    -fno-omit-frame-pointer)
add_link_options(-fsanitize=address,undefined)
