# wirerig_unity_batches(<target>): with WIRERIG_UNITY_BUILD, the target's sources compiled 8 to a
# batch. Its files must not define the same name at namespace scope (helpers shared by several
# files live in a header of the folder).
function(wirerig_unity_batches target)
  if(WIRERIG_UNITY_BUILD)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  endif()
endfunction()

# wirerig_target_options(<target>): warnings and sanitizers as PRIVATE options of
# one target, so nothing leaks into consumers of the installed package.
function(wirerig_target_options target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
  if(WIRERIG_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  # No floating-point exception the source does not raise: the tests trap them (test_main.cpp)
  # and an engine may too. GCC keeps to that by default (-ftrapping-math); clang's default lets
  # it evaluate a division or square root in lanes the code masks out (0/0 in the vertex stage's
  # padding), which then traps.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    target_compile_options(${target} PRIVATE -ffp-exception-behavior=maytrap)
  endif()
  if(WIRERIG_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined
                                             -fno-sanitize-recover=all -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# wirerig_fuzzing_instrumentation(<target>): with WIRERIG_BUILD_FUZZERS, the coverage
# instrumentation libFuzzer steers by (-fsanitize=fuzzer-no-link), for the libraries the fuzz
# targets exercise; the fuzzers themselves link libFuzzer (fuzz/CMakeLists.txt).
function(wirerig_fuzzing_instrumentation target)
  if(WIRERIG_BUILD_FUZZERS)
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
  endif()
endfunction()

# wirerig_add_library(<name> <sources>...): the library wirerig_<name> with its alias
# wirerig::<name>, its public include/ folder, per-target options, and install rules into the
# exported package: the runtime and the C API into wirerigRuntimeTargets (what an engine needs:
# Eigen only), everything else into wirerigTargets.
function(wirerig_add_library name)
  set(target wirerig_${name})
  set(export_set wirerigTargets)
  if(name STREQUAL "runtime" OR name STREQUAL "capi")
    set(export_set wirerigRuntimeTargets)
  endif()
  add_library(${target} ${ARGN})
  add_library(wirerig::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(${target} PUBLIC cxx_std_20)
  wirerig_target_options(${target})
  wirerig_fuzzing_instrumentation(${target})
  install(TARGETS ${target} EXPORT ${export_set}
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()
