# stiffsoft_tests(NAME LIBS...) — one GoogleTest executable from tests/NAME/*_test.cpp.
function(stiffsoft_tests name)
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${name}/*_test.cpp)
  if(NOT sources)
    return()
  endif()
  add_executable(${name}_tests ${sources})
  target_link_libraries(${name}_tests PRIVATE ${ARGN} stiffsoft_test_support GTest::gtest_main)
  if(name STREQUAL "apps" OR name STREQUAL "render")
    add_dependencies(${name}_tests stiffsoft)  # its tests run the binary
  endif()
  target_compile_definitions(${name}_tests PRIVATE
    STIFFSOFT_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    STIFFSOFT_SHARED_DIR="${PROJECT_SOURCE_DIR}/../shared"
    STIFFSOFT_BINARY="$<TARGET_FILE:stiffsoft>")
  set(extra_properties)
  if(name STREQUAL "render")
    # Sanitized (preset `sanitize`), the render tests take the fast unwinder and no leak check:
    # with fast_unwind_on_malloc=0 `stiffsoft render` deadlocks in Mesa's llvmpipe (LLVM's JIT
    # registers its frames under libgcc's unwinder lock, mallocs, and ASan's malloc hook
    # unwinds and waits for that lock), and with the fast one LeakSanitizer reports blocks of
    # VTK and Mesa whose stacks end in their frame-pointer-less code (docs/robustness.md).
    set(extra_properties ENVIRONMENT_MODIFICATION "ASAN_OPTIONS=string_append::fast_unwind_on_malloc=1:detect_leaks=0")
  endif()
  gtest_discover_tests(${name}_tests DISCOVERY_TIMEOUT 60
    PROPERTIES LABELS ${name} ${extra_properties})
endfunction()
