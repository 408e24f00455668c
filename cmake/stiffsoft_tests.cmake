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
  gtest_discover_tests(${name}_tests DISCOVERY_TIMEOUT 60
    PROPERTIES LABELS ${name})
endfunction()
